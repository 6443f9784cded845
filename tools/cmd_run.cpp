// `fe2heart run`: every rank reads the spec; ranks agree on protocol and spec; the
// first n_c ranks coordinate (macro problem, MUMPS), the worker ranks hold units.
#include "common/circulation/circulation_run_spec.h"
#include "common/cpu_timer.h"
#include "common/io/atomic_file.h"
#include "coordinator/output/Checkpoint.h"
#include "coordinator/farm/FarmEvaluator.h"
#include "coordinator/farm/FarmLayout.h"
#include "coordinator/output/RunOutput.h"
#include "coordinator/RunSpec.h"
#include "coordinator/output/UnitOutput.h"
#include "coordinator/Simulation.h"
#include "tools/commands.h"
#include "tools/output_folder.h"
#include "tools/memory_limit.h"
#include "tools/run_plots.h"
#include "tools/stop_signal.h"
#include "tools/study_spec.h"
#include "worker/blas_core.h"
#include "tools/unit_spec.h"
#include "worker/worker_loop.h"

#include <spdlog/sinks/basic_file_sink.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <csignal>
#include <ctime>
#include <sched.h>
#include <filesystem>

namespace fe2::cli {

namespace {

/// --restart on rank 0, before anything is built: the checkpoint (checked whole), the
/// spec it ran against this one, and whether the run continues in its own folder.
struct Restart {
  std::unique_ptr<CheckpointFile> file;
  bool in_place = false;             ///< --out is the folder the checkpoint is in: keep its files
  bool continue_traces = false;      ///< ... and its traces are there: cut back and append
  RunResult done;                    ///< the steps behind
  TraceOffsets trace;
  std::vector<std::string> notes;    ///< for the log: newer checkpoints refused, and why
};

Restart open_restart(const RunOptions& o, const RunSpec& spec) {
  Restart r;
  r.file = std::make_unique<CheckpointFile>(open_checkpoint(o.restart, proto::kProtocolVersion, &r.notes));
  const CheckpointHeader& h = r.file->header();
  json saved;
  try {
    saved = json::parse(h.spec_text);
  } catch (const json::exception& e) {
    throw InputError(fmt::format("checkpoint '{}': its spec is not JSON ({})", r.file->path(), e.what()));
  }
  const std::vector<std::string> keys = spec_differences(saved, spec.raw, o.fresh_units);
  if (!keys.empty()) {
    std::string list;
    for (const std::string& k : keys) list += (list.empty() ? "" : ", ") + k;
    const std::string what = fmt::format("--restart '{}': spec '{}' differs from the one the checkpoint ran in {}",
                                         r.file->path(), o.spec, list);
    if (!o.force)
      throw InputError(what + (o.fresh_units ? "; a restart with --fresh-units may change only output, farm, title and the models' unit"
                                             : "; a restart may change only output, farm and title (--fresh-units: also the "
                                               "models' unit, whose points then start afresh)") +
                       " (--force continues anyway)");
    r.notes.push_back(what + " (--force)");
  }
  if (h.steps > spec.steps)
    throw InputError(fmt::format("--restart '{}': the checkpoint is after step {}, the spec has {} steps",
                                 r.file->path(), h.steps, spec.steps));
  r.done = unpack_run_section(h.run, r.trace, fmt::format("checkpoint '{}'", r.file->path()));
  std::error_code ec;
  const auto folder = std::filesystem::path(r.file->path()).parent_path();
  r.in_place = std::filesystem::exists(o.out, ec) &&
               std::filesystem::equivalent(folder.empty() ? "." : folder, o.out, ec);
  // The traces continue if they are there (a checkpoint copied into a new folder starts
  // them afresh).
  r.continue_traces = r.in_place && std::filesystem::exists(std::filesystem::path(o.out) / "trace_iterations.jsonl", ec);
  return r;
}

std::string describe(const RunSpec& spec) {
  long long units = 0, dofs = 0;
  for (int m_index : spec.model_of_points()) {
    const auto& m = spec.models[m_index];
    if (m.kind == PointModelSpec::Kind::fe2) ++units, dofs += m.plan->memory.dofs;
  }
  const bool mixed = spec.formulation.mixed;
  const int order = spec.mesh.order();
  return fmt::format("{} nodes, {} tetrahedra ({}-node), {} ({} points: {} per element; {} FE² units, "
                     "{} micro DOF in all), {} steps{}",
                     spec.mesh.num_nodes(), spec.mesh.num_tets(), order == 1 ? 4 : 10,
                     !mixed ? fmt::format("displacement P{}", order)
                     : spec.formulation.element_pressure ? std::string("mixed enriched Taylor–Hood P2/(P1+P0)")
                     : order == 2                        ? std::string("mixed Taylor–Hood P2/P1")
                                                         : std::string("mixed stabilized P1/P1"),
                     spec.num_points(), spec.points_per_element, units, dofs, spec.steps,
                     spec.dynamic ? ", Newmark dynamics" : ", quasi-static");
}

/// Every rank must run the same protocol and the same spec (preCICE checkRemoteInfo).
/// @note Collective on the world.
void check_ranks_agree(const proto::Group& world, const RunSpec& spec) {
  proto::Hello mine;
  mine.spec_hash = spec.hash;
  mine.rank = world.rank();
  mine.ranks = world.size();
  Bytes b;
  mine.pack(b);
  Bytes verdict;
  const auto all = world.gather(b, 0);
  if (world.rank() == 0) {
    std::string problem;
    for (const Bytes& x : all) {
      try {
        const proto::Hello h = proto::Hello::unpack(x);
        if (h.spec_hash != spec.hash && problem.empty())
          problem = fmt::format("rank {} read a different spec (hash {:016x}) from rank 0 ({:016x}); "
                                "every rank must see the same spec file",
                                h.rank, h.spec_hash, spec.hash);
      } catch (const Error& e) {
        if (problem.empty()) problem = e.what();
      }
    }
    verdict.assign(reinterpret_cast<const std::byte*>(problem.data()),
                   reinterpret_cast<const std::byte*>(problem.data() + problem.size()));
  }
  world.bcast(verdict, 0);
  if (!verdict.empty())
    throw InputError(std::string(reinterpret_cast<const char*>(verdict.data()), verdict.size()));
}

/// True on every rank iff no rank failed to read its input. A rank that failed says
/// why itself (its error may be the only copy: other ranks read other files); rank 0
/// adds how many failed. @note Collective on the world: the first one of a run.
bool agree_input_ok(const proto::Group& world, const std::string& error) {
  if (!error.empty()) {
    if (world.size() > 1) spdlog::error("rank {}: {}", world.rank(), error);
    else spdlog::error("{}", error);
  }
  double failed = error.empty() ? 0.0 : 1.0;
  world.allreduce_sum(&failed, 1);
  if (failed == 0.0) return true;
  if (world.rank() == 0 && error.empty())
    spdlog::error("{} of {} ranks could not read their input (see their messages); stopping",
                  static_cast<int>(failed), world.size());
  return false;
}

/// A fatal error as a log line, for ranks without the file sink.
std::string fatal_log_line(int rank, const std::string& what) {
  const auto now = std::chrono::system_clock::now();
  const std::time_t t = std::chrono::system_clock::to_time_t(now);
  const auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(now.time_since_epoch()).count() % 1000;
  std::tm local{};
  localtime_r(&t, &local);
  char stamp[32];
  std::strftime(stamp, sizeof stamp, "%Y-%m-%d %H:%M:%S", &local);
  return fmt::format("[{}.{:03d}] [critical] rank {}: {}; stopping every rank", stamp,
                     static_cast<int>(ms), rank, what);
}

/// Refuses a run whose units would not fit: each rank's starting share (units of each
/// model, with the model's shared data; factors up to farm.factor_memory_budget) against
/// the memory limit, before any is built.
void check_run_memory(const RunSpec& spec, const FarmLayout& layout, const std::string& limit) {
  std::vector<std::vector<long long>> units(layout.ranks,
                                            std::vector<long long>(spec.models.size(), 0));
  const std::vector<int> model = spec.model_of_points();
  for (size_t u = 0; u < model.size(); ++u) ++units[layout.initial_worker_of_unit[u]][model[u]];
  check_unit_memory(spec.models, units, memory_limit(limit), spec.farm.factor_memory_budget);
}

/// farm.threads_per_rank > 1 needs MPI to allow helper threads beside the one that
/// talks MPI, and units whose jobs never call MPI themselves (MUMPS factors do).
void check_threads_per_rank(const RunSpec& spec) {
  const int threads = spec.farm.threads_per_rank;
  if (threads <= 1) return;
  int provided = MPI_THREAD_SINGLE;
  MPI_Query_thread(&provided);
  if (provided < MPI_THREAD_FUNNELED)
    throw InputError(fmt::format("farm.threads_per_rank = {}: this MPI library gives no thread support "
                                 "beyond MPI_THREAD_SINGLE; expected 1, or an MPI with MPI_THREAD_FUNNELED",
                                 threads));
  for (const auto& m : spec.models)
    if (m.plan && m.plan->may_run_mumps())
      throw InputError(fmt::format(
          "farm.threads_per_rank = {}: model '{}' factors in {} precision with MUMPS ({}/solver: "
          "single_factor '{}', factorization '{}'), and MUMPS calls MPI, which only a rank's main "
          "thread may; expected farm.threads_per_rank 1, or solver.factorization \"cholesky\" with "
          "single_factor \"supernodal\" (or precision \"double\")",
          threads, m.name, m.plan->options.half_storage ? "half" : "single", m.plan->path,
          m.plan->options.single_factor_mumps ? "mumps" : "supernodal",
          m.plan->options.factorization == MicroSolverOptions::Factorization::lu ? "lu" : "auto"));
}

/// mpirun binds a rank to one core by default (Open MPI, up to two ranks): its helper
/// threads then share that core and run no faster than one. Says so, with the fix.
void warn_if_threads_share_cores(int threads, int rank) {
  if (threads <= 1) return;
  cpu_set_t mask;
  CPU_ZERO(&mask);
  if (sched_getaffinity(0, sizeof mask, &mask) != 0) return;
  const int cpus = CPU_COUNT(&mask);
  if (cpus >= threads) return;
  spdlog::warn("rank {}: farm.threads_per_rank is {} but this rank may run on {} CPU(s) only (its "
               "affinity mask): the threads share them. Bind each rank to {} cores: `mpirun "
               "--map-by slot:PE={}` (or `--bind-to none`); Slurm: `--cpus-per-task={}`",
               rank, threads, cpus, threads, threads, threads);
}

std::string format_duration(double s) {
  if (s < 120) return fmt::format("{:.1f} s", s);
  if (s < 7200) return fmt::format("{:.1f} min", s / 60);
  return fmt::format("{:.1f} h", s / 3600);
}

/// The run spec's JSON, with --beats in place of time.beats (spec.json records it).
json spec_json(const RunOptions& o) {
  json j = read_json_file(o.spec);
  if (o.beats <= 0) return j;
  const json* time = j.is_object() && j.contains("time") ? &j["time"] : nullptr;
  if (!time || !time->is_object() || !time->contains("beats"))
    throw InputError(fmt::format("--beats {}: {} has no time.beats, expected a spec of whole beats "
                                 "(time.beats and time.steps_per_beat)",
                                 o.beats, o.spec));
  j["time"]["beats"] = o.beats;
  return j;
}

}  // namespace

// Checks everything a run would read, but builds no unit model: only counts, the
// memory estimate against the limit, and each cell's mesh (periodicity, regions).
int validate(const std::string& file, const std::string& memory_limit_text) {
  const MemoryLimit limit = memory_limit(memory_limit_text);
  const json j = read_json_file(file);
  if (is_circulation_run_spec(j)) return validate_circulation(file);
  if (is_study_spec(j)) return validate_study(file);  // fe2heart study (tools/cmd_study.cpp)
  if (j.is_object() && j.contains("unit") && !j.contains("mesh")) {
    const UnitSpec u = read_unit_spec(j, file, nullptr, false);
    check_unit_memory(*u.plan, 1, limit);
    const int dofs = u.plan->check();
    fmt::print("{}: OK: unit spec, {} hexahedra, {} DOF, {} macro gradient(s), memory ≈ {} "
               "(limit {})\n",
               file, u.plan->memory.elements, dofs, u.path.size(),
               format_bytes(u.plan->memory.bytes_for(1)), format_bytes(limit.bytes));
    return 0;
  }
  const RunSpec spec = read_run_spec(j, file, nullptr, false);
  // A run may spread its units over many ranks, so here one unit of each model must
  // fit; `run` checks each rank's actual share.
  std::vector<long long> units(spec.models.size(), 0);
  for (int m : spec.model_of_points()) ++units[m];
  double one_rank = 0;
  for (size_t m = 0; m < spec.models.size(); ++m) {
    if (!spec.models[m].plan) continue;
    check_unit_memory(*spec.models[m].plan, 1, limit);
    spec.models[m].plan->check();
    one_rank += spec.models[m].plan->memory.bytes_for(units[m]);
  }
  fmt::print("{}: OK: {}; unit memory ≈ {} on one rank (limit {})\n", file, describe(spec),
             format_bytes(one_rank), format_bytes(limit.bytes));
  for (const std::string& w : spec.warnings) fmt::print("warning: {}\n", w);
  return 0;
}

int run(const RunOptions& o) {
  catch_stop_signals();  // again: MPI_Init may have installed handlers of its own (tools/stop_signal.h)
  proto::Transport transport(MPI_COMM_WORLD);
  const proto::Group world(MPI_COMM_WORLD);
  const int rank = world.rank();
  // Rank 0 alone looks for the stop file (one stat per iteration, not one per rank);
  // the coordinators' reduction of stop_request() tells the others.
  if (rank == 0) watch_stop_file(o.stop_file);
  // Every rank reads its own input (a cluster may lack a shared file system, so one
  // node can miss a file the others see). Before any other collective, all ranks agree
  // that input is OK: a rank that failed prints its own error, and every rank exits 2.
  proto::set_stall_timeout(FarmOptions{}.stall_timeout);  // until the spec says otherwise
  RunSpec spec;
  FarmLayout layout;
  Restart restart;  // rank 0
  std::string input_error;
  try {
    spec = read_run_spec(spec_json(o), o.spec, nullptr, /*build_units=*/false);  // built below, if they fit
    if (o.fresh_units && o.restart.empty())
      throw InputError("--fresh-units: only with --restart (it keeps a checkpoint's macro state, the points start afresh)");
    if (rank == 0 && !o.restart.empty()) restart = open_restart(o, spec);
    if (o.fresh_units && restart.in_place)
      throw InputError(fmt::format("--fresh-units: --out '{}' is the checkpoint's own run; a restart with other units "
                                   "writes its traces and series into another folder",
                                   o.out));
    // Before anything is written; a restart continues in its own folder.
    if (rank == 0 && !restart.in_place)
      refuse_earlier_output(o.out, "an fe2heart run", earlier_run_files(o.out), o.overwrite);
    if (!o.policy.empty())
      spec.farm.policy = FarmOptions::policy_of(o.policy);
    // spec.json in the output is the spec that ran (farm-sim replays its farm section).
    if (!o.policy.empty()) spec.raw["farm"]["policy"] = o.policy;
    if (o.coordinators > 0) spec.raw["farm"]["coordinators"] = o.coordinators;
    if (o.threads_per_rank > 0) {
      spec.farm.threads_per_rank = o.threads_per_rank;
      spec.raw["farm"]["threads_per_rank"] = o.threads_per_rank;
    }
    layout = FarmLayout::make(spec, world.size(), o.coordinators);
    check_threads_per_rank(spec);
    if (spec.farm.threads_per_rank > 1) set_blas_threads(1);
    check_run_memory(spec, layout, o.memory_limit);
    UnitStore::fault_from_env();  // a malformed test hook is bad input on every rank
    // Only ranks that hold units build unit models (a coordinator-only rank never does).
    if (layout.is_worker(rank)) build_unit_models(spec);
  } catch (const std::exception& e) {  // InputError, or e.g. bad_alloc on a huge mesh
    input_error = e.what();
  }
  if (!agree_input_ok(world, input_error)) return 2;
  proto::set_stall_timeout(spec.farm.stall_timeout);
  check_ranks_agree(world, spec);
  if (rank != 0) spdlog::set_level(spdlog::level::warn);  // summaries from rank 0 only
  if (layout.is_worker(rank)) warn_if_threads_share_cores(spec.farm.threads_per_rank, rank);

  const bool coordinator = layout.is_coordinator(rank);
  const proto::Group coords = world.split(coordinator ? 0 : -1, rank);
  const std::vector<int> model_of_unit = spec.model_of_points();
  std::unique_ptr<UnitStore> store;

  // From here on a failure on one rank must end every rank: no one may wait forever.
  bool log_open = false;  // rank 0's file sink is in place
  try {
    if (layout.is_worker(rank)) {
      store = std::make_unique<UnitStore>(spec.models, model_of_unit);
      store->set_factor_budget(spec.farm.factor_memory_budget);
      for (size_t u = 0; u < model_of_unit.size(); ++u)
        if (layout.initial_worker_of_unit[u] == rank && !layout.is_local(static_cast<int>(u)))
          store->create(static_cast<int>(u));
    }
    if (!coordinator) {
      run_worker_loop(transport, *store, layout.coordinator_of_unit, spec.farm.batch,
                      spec.farm.threads_per_rank);
      return 0;
    }
    std::unique_ptr<RunOutput> output;
    std::unique_ptr<UnitOutput> unit_output;
    std::unique_ptr<Trace> trace;
    if (rank == 0) {
      output = std::make_unique<RunOutput>(o.out, spec, restart.in_place);
      unit_output = std::make_unique<UnitOutput>(o.out, spec);
      trace = std::make_unique<Trace>(o.out, restart.continue_traces ? &restart.trace : nullptr);
      auto sink = std::make_shared<spdlog::sinks::basic_file_sink_mt>(o.out + "/fe2heart.log", true);
      spdlog::default_logger()->sinks().push_back(sink);
      // Line by line: a killed or aborted run keeps its log up to the last line.
      spdlog::default_logger()->flush_on(spdlog::level::trace);
      log_open = true;
      spdlog::info("fe2heart run {}: {}", o.spec, spec.title);
      for (const std::string& note : restart.notes) spdlog::warn("{}", note);
      spdlog::info("{}", describe(spec));
      for (const std::string& w : spec.warnings) spdlog::warn("{}", w);
      if (const std::string w = blas_core_warning(blas_core()); !w.empty()) spdlog::warn("{}", w);
      for (const auto& m : spec.models) {
        if (m.material) spdlog::info("model {}: {}", m.name, m.material->description());
        if (m.plan)
          for (size_t r = 0; r < m.plan->materials.size(); ++r)
            spdlog::info("model {}, unit region {}: {}", m.name, m.plan->region_names[r],
                         m.plan->materials[r]->description());
      }
      spdlog::info("{} ranks: {} coordinator(s), {} worker rank(s), policy {}", layout.ranks,
                   layout.coordinators, layout.worker_ranks.size(),
                   FarmOptions::name_of(spec.farm.policy));
    }
    FarmEvaluator points(transport, coords, layout, spec, store.get(), trace.get());
    Simulation sim(spec, points, coords, layout.partition(rank));
    RunResult done;
    if (!o.restart.empty()) {
      TraceOffsets ignored;
      done = restore_checkpoint(restart.file.get(), sim, points, coords, ignored, o.fresh_units);
      if (output) {
        output->resume(done, [&](int step) { return sim.is_output_step(step); });
        std::vector<std::pair<int, double>> steps;
        for (const StepRecord& r : done.history)
          if (sim.is_output_step(r.step)) steps.emplace_back(r.step + 1, r.time);
        if (restart.in_place) unit_output->resume(steps);
        spdlog::info("restarted from {} (written by {} rank(s), {} coordinator(s)) after step {}, t = {:.6g}{}",
                     restart.file->path(), restart.file->header().ranks, restart.file->header().coordinators,
                     done.steps, restart.file->header().time,
                     o.fresh_units ? "; the macro state only, every point fresh (--fresh-units)" : "");
      }
    }
    const double t0 = wall_seconds();
    auto write_fields = [&](int step, double time) {
      const PointFields f = sim.gather_point_fields();
      if (output) output->write_fields(sim, f, step, time);
      // output.units: taken by the run before the step's commit (none for step 0).
      if (unit_output && !sim.unit_fields().empty() && sim.unit_fields().front().step == step)
        unit_output->write(sim.unit_fields(), time);
    };
    if (o.restart.empty()) write_fields(0, 0.0);
    int stopped_by = 0;
    bool stop_checkpointed = false;  // at the step boundary, by the step hook
    const int first_step = done.steps;  // --stop-after-steps counts from here
    // Before every Newton iteration: a signal on any coordinator stops all of them, even
    // inside a step that keeps cutting back (its committed state is checkpointed below).
    sim.set_stop_poll([&] {
      const int signal = coords.allreduce_max(stop_request());
      if (signal != 0) stopped_by = signal;
      return signal != 0;
    });
    const RunResult result = sim.run(
        [&](const StepRecord& r) {
          const double elapsed = wall_seconds() - t0;
          const double remaining = elapsed / (r.step + 1) * (spec.steps - r.step - 1);
          std::string residuals;  // each macro field's last norm, then the units'
          for (const auto& f : r.residuals) residuals += fmt::format("{} {:.2e}  ", f.field, f.values.back());
          spdlog::info("step {:4d}/{}  t = {:<10.5g} Newton {:2d}  |R| {}max |r|/r_ref = "
                       "{:.2e}  GMRES {:5d}  refreshes {:4d}{}  elapsed {}, remaining ~{}",
                       r.step + 1, spec.steps, r.time, r.iterations, residuals,
                       r.micro_residuals.back(), r.gmres_iterations, r.refreshes,
                       (r.cutbacks ? fmt::format("  cutbacks {}", r.cutbacks) : "") +
                           (r.retries ? fmt::format("  valve retries {}", r.retries) : ""),
                       format_duration(elapsed), format_duration(remaining));
          if (sim.is_output_step(r.step)) write_fields(r.step + 1, r.time);
          if (output) output->write_progress(sim, r, wall_seconds() - t0);
          // A signal on any coordinator stops all of them at this boundary, after a checkpoint.
          const int signal = coords.allreduce_max(stop_request());
          // The same step count on every coordinator: no collective needed to agree.
          const bool window_done = o.stop_after_steps > 0 && r.step + 1 - first_step >= o.stop_after_steps;
          if (signal != 0 || window_done ||
              (spec.checkpoint_every > 0 && (r.step + 1) % spec.checkpoint_every == 0)) {
            const CheckpointWritten w =
                write_checkpoint(checkpoint_path(o.out), spec, world.size(), sim, points, coords,
                                 output ? output->progress() : RunResult{}, trace ? trace->offsets() : TraceOffsets{});
            spdlog::info("checkpoint after step {}: {} ({}, {:.2f} s)", r.step + 1, w.path,
                         format_bytes(static_cast<double>(w.bytes)), w.seconds);
          }
          if (signal != 0 || window_done) {
            stopped_by = signal;
            stop_checkpointed = true;
            sim.request_stop();
          }
        },
        [&](IterationTiming t) {
          if (!trace) return;
          const IterationTiming& f = points.last();
          t.comm1 = f.comm1;
          t.comm2 = f.comm2;
          t.bytes = f.bytes;
          t.migrations = f.migrations;
          t.jobs = f.jobs;
          t.local_jobs = f.local_jobs;
          t.local_cpu = f.local_cpu;
          t.macro_law_jobs_sent = f.macro_law_jobs_sent;
          t.refresh_forecast_misses = f.refresh_forecast_misses;
          trace->iteration(t);
        },
        std::move(done));
    if (result.stopped && !stop_checkpointed) {
      // Stopped inside a step: the state rolled back to the last commit is what restarts.
      const CheckpointWritten w =
          write_checkpoint(checkpoint_path(o.out), spec, world.size(), sim, points, coords,
                           output ? output->progress() : RunResult{}, trace ? trace->offsets() : TraceOffsets{});
      spdlog::info("checkpoint of the committed state after step {} (the step in progress was abandoned): {} "
                   "({}, {:.2f} s)",
                   result.steps, w.path, format_bytes(static_cast<double>(w.bytes)), w.seconds);
    }
    if (rank == 0) points.shutdown();
    if (output) output->write_summary(sim, result, wall_seconds() - t0);
    if (output && !spec.cavities.empty()) {
      // The pressure–volume curve as a picture; a missing matplotlib costs only the PNG.
      if (const std::string w = run_plot_script(FE2_PV_PLOT_SCRIPT, o.out, "pv_curve.png"); !w.empty())
        spdlog::warn("{}", w);
    }
    if (output && spec.circulation && result.steps > 0) {
      if (const std::string w = run_plot_script(FE2_PV_LOOP_SCRIPT, o.out, "pv_loop.png, pv_time.png"); !w.empty())
        spdlog::warn("{}", w);
    }
    if (result.stopped) {
      const char* name = stopped_by == SIGTERM ? "SIGTERM" : stopped_by == SIGUSR1 ? "SIGUSR1" : stopped_by == SIGINT ? "SIGINT" : nullptr;
      const std::string by = stopped_by == 0                ? fmt::format("--stop-after-steps {}", o.stop_after_steps)
                             : stopped_by == kStopFileFound ? fmt::format("the stop file {}", o.stop_file)
                                                            : fmt::format("signal {}", name ? name : std::to_string(stopped_by));
      spdlog::info("stopped by {} after step {} (t = {:.6g}); checkpoint: {}", by, result.steps,
                   result.history.empty() ? 0.0 : result.history.back().time, checkpoint_path(o.out));
      spdlog::info("continue with: fe2heart run {} --out {} --restart {}", o.spec, o.out, o.out);
      return 0;
    }
    if (!result.converged) {
      spdlog::error("run stopped: {}", result.error);
      spdlog::info("partial results in {}", o.out);
      return 3;
    }
    spdlog::info("done in {:.2f} s: {} steps, {} Newton iterations", wall_seconds() - t0,
                 result.steps, result.newton_iterations);
    spdlog::info("results: {}/summary.json{}; traces: {}/trace_*.jsonl", o.out,
                 spec.write_vtu ? fmt::format(", fields: {} (open in ParaView)", output ? output->pvd_path() : "") : "",
                 o.out);
    return 0;
  } catch (const std::exception& e) {
    spdlog::critical("rank {}: {}; stopping every rank", rank, e.what());
    spdlog::default_logger()->flush();
    // The log must hold every rank's last words, not only rank 0's (best effort: the
    // folder may not exist yet, or not on this node).
    if (!log_open) append_line(o.out + "/fe2heart.log", fatal_log_line(rank, e.what()));
    transport.abort(dynamic_cast<const Error*>(&e) ? dynamic_cast<const Error*>(&e)->exit_code() : 1);
  }
}

}  // namespace fe2::cli
