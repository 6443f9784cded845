// fe2heart: multi-scale FE² heart simulation. See README.md and `fe2heart --help`.
#include "common/error.h"
#include "coordinator/farm/FarmOptions.h"
#include "tools/commands.h"
#include "tools/stop_signal.h"

#include <CLI/CLI.hpp>
#include <mpi.h>
#include <spdlog/spdlog.h>

int main(int argc, char** argv) {
  // Before MPI_Init: a stop request during a run's start-up must not kill a rank.
  fe2::cli::catch_stop_signals();
  // Funneled: only a rank's main thread calls MPI; farm.threads_per_rank's helper
  // threads only compute (worker/JobPool.h).
  int provided = 0;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
  CLI::App app{"fe2heart: a multi-scale FE² heart simulator (macro tetrahedra driven by "
               "periodic micro units of cardiac cells)"};
  app.require_subcommand(1);
  app.fallthrough();  // --log-level may follow the subcommand
  std::string level = "info";
  app.add_option("--log-level", level, "trace, debug, info, warn, error")
      ->check(CLI::IsMember({"trace", "debug", "info", "warn", "error"}));

  fe2::cli::RunOptions run;
  auto* c_run = app.add_subcommand("run", "run a scene: writes DIR/summary.json, a log and "
                                          "VTU/PVD fields");
  c_run->add_option("spec", run.spec, "run spec (JSON)")->required();
  c_run->add_option("--out", run.out, "output folder")->required();
  c_run->add_option("--threads-per-rank", run.threads_per_rank,
                    "threads that run a rank's unit jobs (overrides farm.threads_per_rank)")
      ->check(CLI::Range(1, 256));
  c_run->add_option("--coordinators", run.coordinators,
                    "coordinator ranks (overrides farm.coordinators in the spec)")
      ->check(CLI::Range(1, 1000000));
  c_run->add_option("--policy", run.policy, "unit placement (overrides farm.policy)")
      ->check(CLI::IsMember(fe2::FarmOptions::policy_names()));
  const std::string memory_help =
      "memory a rank may use, e.g. 8G, 500M or bytes (default: the available memory, "
      "MemAvailable, shared by the ranks of a node); unit models that would not fit are "
      "refused before they are built";
  c_run->add_option("--memory-limit", run.memory_limit, memory_help);
  c_run->add_flag("--overwrite", run.overwrite,
                  "replace an earlier run in the --out folder (its files only; without this "
                  "flag such a folder is refused)");
  c_run->add_option("--restart", run.restart,
                    "continue from a checkpoint: a run folder (its newest good checkpoint.bin, else "
                    "checkpoint.bin.previous) or a checkpoint file; any number of ranks and "
                    "coordinators. With --out the same folder, its traces, series and summary continue");
  c_run->add_option("--beats", run.beats,
                    "run this many beats (replaces time.beats of a spec of whole beats; with "
                    "time.periodic_tolerance it stops earlier once periodic)")
      ->check(CLI::Range(1, 10000));
  c_run->add_flag("--fresh-units", run.fresh_units,
                  "with --restart: take the checkpoint's macro state only; every integration point starts "
                  "from the initial state of this spec's model (its units may differ from the checkpoint's "
                  "under models.<name>.unit: e.g. a beat's costly phase with units of the paper's size, "
                  "from a checkpoint of a cheap beat)");
  c_run->add_option("--stop-after-steps", run.stop_after_steps,
                    "stop after this many steps of this run, with a checkpoint (as SIGUSR1 would): a "
                    "window of a beat for a benchmark")
      ->check(CLI::Range(1, 10000000));
  c_run->add_option("--stop-file", run.stop_file,
                    "stop as on SIGUSR1 (a checkpoint, exit 0) once this file exists; polled before every "
                    "Newton iteration. Unlike a signal it cannot come too early: `fe2heart study` stops "
                    "its variants this way");
  c_run->add_flag("--force", run.force,
                  "--restart although the spec differs from the checkpoint's outside output, farm and "
                  "title (e.g. a later time.t_end, other tolerances); the state must still fit the spec "
                  "(same mesh, points and unit models), else it is refused");

  std::string validate_spec;
  auto* c_validate = app.add_subcommand("validate", "check a run or unit spec and its meshes");
  c_validate->add_option("spec", validate_spec, "spec (JSON)")->required();
  std::string validate_memory;
  c_validate->add_option("--memory-limit", validate_memory, memory_help);

  fe2::cli::UnitOptions unit;
  auto* c_unit = app.add_subcommand(
      "unit", "equilibrate one micro unit under Z̄ (or a sequence) and print JSON with P_bar "
              "(9) and A_hom (81), column-major");
  c_unit->add_option("spec", unit.spec, "unit spec (JSON)")->required();
  c_unit->add_option("--vtu", unit.vtu, "also write the equilibrated unit as VTU");

  auto* c_doc = app.add_subcommand("spec-doc", "every spec key with its type, default, range and "
                                               "help, from the spec schemas the readers read by");
  bool doc_markdown = false;
  c_doc->add_flag("--markdown", doc_markdown, "as markdown tables (docs/spec-reference.md)");
  auto* c_schema = app.add_subcommand("spec-schema", "the spec schema as JSON Schema 2020-12 "
                                                     "(for editors and validators)");
  std::string schema_kind = "run";
  for (const auto& k : fe2::cli::spec_kinds())
    if (std::string(k.name) != "run")
      c_schema->add_flag_callback("--" + std::string(k.name), [&schema_kind, name = std::string(k.name)] {
        schema_kind = name;
      }, fmt::format("the schema of {} (default: run specs)", k.heading));

  fe2::cli::CirculationOptions circulation;
  auto* c_circulation = app.add_subcommand(
      "circulation", "a 0D circulation alone, elastance ventricles standing in for the wall: "
                     "writes DIR/circulation.csv, summary.json (EDV, ESV, SV, EF, ...) and pv_loop.png");
  c_circulation->add_option("spec", circulation.spec, "circulation spec (JSON)")->required();
  c_circulation->add_option("--out", circulation.out, "output folder")->required();
  c_circulation->add_flag("--overwrite", circulation.overwrite,
                          "replace an earlier run in --out (without it such a folder is refused)");

  fe2::cli::BenchOptions bench;
  auto* c_bench = app.add_subcommand("bench", "benchmarks that print figures (not tests)");
  c_bench->require_subcommand(1);
  auto* c_bench_unit = c_bench->add_subcommand(
      "unit", "time one micro unit: assembly, iteration with a cached factor, refresh");
  c_bench_unit->add_option("--dofs", bench.dofs, "target unit size in DOF")
      ->check(CLI::Range(24, 3000000));
  c_bench_unit->add_option("--repeat", bench.repeat, "repetitions (medians are reported)")
      ->check(CLI::Range(1, 100));
  c_bench_unit->add_option("--stale-stretch", bench.stale_stretch,
                           "fibre stretch between the factored state and the timed iteration")
      ->check(CLI::Range(0.0, 0.2));
  c_bench_unit->add_option("--cell", bench.cell, "cell layout")
      ->check(CLI::IsMember({"two_cells", "homogeneous", "laminate"}));
  c_bench_unit->add_flag("--single", bench.single,
                         "also time a unit whose factor is single precision");
  c_bench_unit->add_option("--single-factor", bench.single_factor,
                           "that factor: supernodal LLᵀ on CHOLMOD's analysis, the same "
                           "kept in binary16 (half), or MUMPS")
      ->check(CLI::IsMember({"supernodal", "half", "mumps"}));
  c_bench_unit->add_option("--blr-tolerance", bench.blr_tolerance,
                           "block low-rank threshold of a MUMPS factor (0: full rank)")
      ->check(CLI::Range(0.0, 0.5));
  c_bench_unit->add_option("--gmres-forcing", bench.gmres_forcing,
                           "Step 1 tolerance: gmres_rtol always, or the inexact-Newton forcing")
      ->check(CLI::IsMember({"constant", "residual"}));

  bool blas_suggested_only = false;
  auto* c_bench_blas = c_bench->add_subcommand(
      "blas", "which OpenBLAS kernels run, and a better OPENBLAS_CORETYPE for this CPU if any");
  c_bench_blas->add_flag("--suggested-coretype", blas_suggested_only,
                         "print only the suggested OPENBLAS_CORETYPE (empty line: none)");

  auto* c_trace = app.add_subcommand("trace", "read a run's load-balance traces");
  c_trace->require_subcommand(1);
  std::string trace_dir, plot_out;
  bool trace_json = false;
  auto* c_trace_summary = c_trace->add_subcommand(
      "summary", "paper Table I ratios, imbalance, micro-phase efficiency, bytes, migrations");
  c_trace_summary->add_option("dir", trace_dir, "output folder of a run")->required();
  c_trace_summary->add_flag("--json", trace_json, "print JSON");
  auto* c_trace_plot = c_trace->add_subcommand(
      "plot", "PNGs: cumulative Entire/Micro+L+C/Macro per step (paper Fig. 7), worker Gantt charts");
  c_trace_plot->add_option("dir", trace_dir, "output folder of a run")->required();
  c_trace_plot->add_option("--out", plot_out, "where to write the PNGs (default: the run folder)");

  fe2::cli::FarmSimOptions sim;
  auto* c_sim = app.add_subcommand(
      "farm-sim", "replay a run's measured unit costs on W simulated workers (same scheduler "
                  "and rebalancer) and predict efficiencies");
  c_sim->add_option("dir", sim.dir, "output folder of a run")->required();
  c_sim->add_option("--workers", sim.workers, "simulated worker counts (default 6144 60000 600000)");
  c_sim->add_option("--units-per-worker", sim.units_per_worker, "units per worker (default 1 4)");
  // Farm settings default to the run's own (DIR/spec.json); these flags override them.
  c_sim->add_option("--policy", sim.policy, "placement policy (default: the run's farm.policy)")
      ->check(CLI::IsMember(fe2::FarmOptions::policy_names()));
  c_sim->add_option("--rebalance-at", sim.rebalance_at, "default: the run's farm.rebalance_at")
      ->check(CLI::IsMember({"iteration", "step"}));
  c_sim->add_option("--latency", sim.latency, "seconds per message (default: the run's farm.latency)")
      ->check(CLI::NonNegativeNumber);
  c_sim->add_option("--bandwidth", sim.bandwidth, "bytes per second (default: the run's farm.bandwidth)")
      ->check(CLI::PositiveNumber);
  c_sim->add_option("--batch", sim.batch, "jobs per pull (default: the run's farm.batch)")
      ->check(CLI::Range(1, 1000000));
  c_sim->add_option("--min-gain", sim.min_gain, "default: the run's farm.min_gain")
      ->check(CLI::Range(0.0, 1.0));
  c_sim->add_option("--tolerated-imbalance", sim.tolerated_imbalance,
                    "default: the run's farm.tolerated_imbalance")
      ->check(CLI::Range(0.0, 10.0));
  c_sim->add_option("--macro-scale", sim.macro_scale, "multiply the measured Macro time");
  c_sim->add_option("--macro-from", sim.macro_from,
                    "a run folder whose macro costs replace the replayed run's, iteration by iteration "
                    "of the same kind (factorizing, kept-factor, no solve): the busiest coordinator's CPU "
                    "medians (e.g. a macro-law run at the paper's macro size)");
  c_sim->add_option("--beat", sim.beat,
                    "a run folder with a whole beat of the same heart (e.g. its cheap units): the replay "
                    "extrapolated to one beat's seconds and core-hours over the beat's circulation phases");
  c_sim->add_flag("--without-timing-noise", sim.without_timing_noise,
                  "replay each job at the median cost of the jobs of its kind (refresh or reuse, GMRES "
                  "count) in its iteration x its unit's persistent factor: the run without the measuring "
                  "machine's timing noise (the cost spread line says how large it was)");
  c_sim->add_option("--max-units", sim.max_units, "skip configurations with more units");

  fe2::cli::StudyOptions study;
  auto* c_study = app.add_subcommand(
      "study", "run variants of a base spec, measure their cost and error against a reference: "
               "DIR/study.json, study.csv, study.txt, pareto.png (docs/study.md)");
  c_study->footer(
      "STUDY.json:\n"
      "  \"base\": \"spec.json\"            the base run spec (relative to the study file)\n"
      "  \"variants\": [{\"name\": \"fine\", \"set\": {\"/time/steps\": 16, \"/newton/rtol\": 1e-10}}]\n"
      "                                  edits by JSON pointer (RFC 6901); {} runs the base unchanged\n"
      "  \"one_at_a_time\": {\"/time/steps\": [4, 8]}   one variant per value, named steps=4, steps=8\n"
      "  \"reference\": \"finest\"          the variant with the most CPU seconds (default), a variant\n"
      "                                  name, or {\"run\": \"DIR of an earlier run\"}\n"
      "  \"quantities\": [...]            displacement (of the probes), probes, cavity_volumes,\n"
      "                                  cavity_pressures, load_pressures, or a pointer into\n"
      "                                  summary.json such as \"/circulation/cavities/lv/EF\"\n"
      "  \"np\": 1                        ranks per variant; \"mpirun\": [\"mpirun\", \"-n\", \"{np}\"]\n"
      "Error: max over steps and entries of |q - q_ref| / max |q_ref|, the reference interpolated\n"
      "linearly in time at the variant's step times. Each variant runs as `fe2heart run` in\n"
      "DIR/variants/NAME/run; a failed one is reported with its exit code and last error line.");
  c_study->add_option("study", study.spec, "study file (JSON)")->required();
  c_study->add_option("--out", study.out, "output folder")->required();
  c_study->add_option("--np", study.np, "ranks per variant (overrides \"np\")")->check(CLI::Range(1, 100000));
  auto* o_overwrite = c_study->add_flag("--overwrite", study.overwrite, "replace an earlier study in --out");
  c_study->add_flag("--resume", study.resume,
                    "go on with an earlier study in --out: keep each variant it finished (\"ok\") with the "
                    "same spec, ranks and launcher; run the others")
      ->excludes(o_overwrite);

  int rc = 0;
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    rc = app.exit(e);
    if (rc != 0) rc = 2;  // usage errors are bad input (CLI11 says 105, 106, ...); --help stays 0
    MPI_Finalize();
    return rc;
  }
  if (!*c_run) fe2::cli::release_stop_signals();  // only `run` stops at a checkpoint
  spdlog::set_level(spdlog::level::from_str(level));
  spdlog::set_pattern("[%H:%M:%S.%e] [%^%l%$] %v");
  try {
    if (*c_run) rc = fe2::cli::run(run);
    else if (*c_validate) rc = fe2::cli::validate(validate_spec, validate_memory);
    else if (*c_unit) rc = fe2::cli::unit(unit);
    else if (*c_bench_unit) rc = fe2::cli::bench_unit(bench);
    else if (*c_bench_blas) rc = fe2::cli::bench_blas(blas_suggested_only);
    else if (*c_trace_summary) rc = fe2::cli::trace_summary(trace_dir, trace_json);
    else if (*c_trace_plot) rc = fe2::cli::trace_plot(trace_dir, plot_out);
    else if (*c_sim) rc = fe2::cli::farm_sim(sim);
    else if (*c_doc) rc = fe2::cli::spec_doc(doc_markdown);
    else if (*c_schema) rc = fe2::cli::spec_schema(schema_kind);
    else if (*c_circulation) rc = fe2::cli::circulation(circulation);
    else if (*c_study) rc = fe2::cli::study(study);
  } catch (const fe2::Error& e) {
    int rank = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    if (rank == 0) spdlog::error("{}", e.what());  // every rank has the same input error
    rc = e.exit_code();
  } catch (const std::exception& e) {
    spdlog::error("unexpected error: {}", e.what());
    rc = 1;
  }
  MPI_Finalize();
  return rc;
}
