#include "coordinator/farm/Trace.h"

#include "common/error.h"

#include <algorithm>
#include <filesystem>

namespace fe2 {

namespace {
/// A trace file: new, or (`keep` not null) an existing one cut to `*keep` bytes and appended to.
std::ofstream open(const std::string& path, const uint64_t* keep) {
  if (keep) {
    std::error_code ec;
    const bool present = std::filesystem::exists(path, ec);
    if (!present || std::filesystem::file_size(path, ec) < *keep)
      throw InputError(fmt::format("cannot continue trace file '{}': it has fewer than the {} bytes the "
                                   "checkpoint recorded", path, *keep));
    std::filesystem::resize_file(path, *keep, ec);
    if (ec) throw InputError(fmt::format("cannot cut trace file '{}' back to {} bytes ({})", path, *keep, ec.message()));
  }
  std::ofstream f(path, keep ? std::ios::app : std::ios::trunc);
  if (!f) throw InputError(fmt::format("cannot write trace file '{}'", path));
  return f;
}
}  // namespace

Trace::Trace(const std::string& dir, const TraceOffsets* resume)
    : dir_(dir),
      iterations_(open(dir + "/trace_iterations.jsonl", resume ? &resume->iterations : nullptr)),
      workers_(open(dir + "/trace_workers.jsonl", resume ? &resume->workers : nullptr)),
      units_(open(dir + "/trace_units.jsonl", resume ? &resume->units : nullptr)) {}

TraceOffsets Trace::offsets() {
  auto at = [this](std::ofstream& f, const char* name) {
    f.flush();
    std::error_code ec;
    const auto n = std::filesystem::file_size(dir_ + "/" + name, ec);
    if (ec) throw Error(fmt::format("cannot read the size of trace file '{}/{}' ({})", dir_, name, ec.message()));
    return static_cast<uint64_t>(n);
  };
  return {at(iterations_, "trace_iterations.jsonl"), at(workers_, "trace_workers.jsonl"),
          at(units_, "trace_units.jsonl")};
}

void Trace::iteration(const IterationTiming& t) {
  const nlohmann::json j = {{"step", t.step},         {"iteration", t.iteration},
                            {"entire", t.entire},     {"micro_lc", t.micro_lc},
                            {"macro", t.macro},       {"assemble", t.assemble},
                            {"assemble_fluid", t.assemble_fluid},
                            {"solve", t.solve},       {"comm1", t.comm1},
                            {"macro_cpu_max", t.macro_cpu_max}, {"macro_cpu_sum", t.macro_cpu_sum},
                            {"coordinators", t.coordinators}, {"macro_factorized", t.macro_factorized},
                            {"macro_gmres", t.macro_gmres},
                            {"comm2", t.comm2},       {"bytes", t.bytes},
                            {"migrations", t.migrations}, {"jobs", t.jobs},
                            {"local_jobs", t.local_jobs}, {"local_cpu", t.local_cpu},
                            {"macro_law_jobs_sent", t.macro_law_jobs_sent},
                            {"refresh_forecast_misses", t.refresh_forecast_misses}};
  units_.flush();
  workers_.flush();
  iterations_ << j.dump() << '\n' << std::flush;
}

void Trace::worker(const proto::WorkerStats& s, double micro_phase, double t0) {
  // A rank of several threads (farm.threads_per_rank): busy_wall is its threads' mean,
  // the wall time the rank was busy as a one-thread rank's is; busy stays the CPU sum.
  const double busy_wall = s.busy_wall / std::max(1, s.threads);
  const nlohmann::json j = {{"step", s.step},
                            {"iteration", s.iteration},
                            {"worker", s.worker},
                            {"units", s.units_held},
                            {"jobs", s.jobs},
                            {"busy", s.busy_cpu},
                            {"busy_wall", busy_wall},
                            {"idle", std::max(0.0, micro_phase - busy_wall)},
                            {"threads", s.threads},
                            {"wait", s.wait_wall},
                            {"t_begin", s.t_begin - t0},
                            {"t_end", s.t_end - t0},
                            {"migrations_in", s.migrations_in},
                            {"migrations_out", s.migrations_out},
                            {"bytes", s.bytes_sent + s.bytes_received}};
  workers_ << j.dump() << '\n';
}

void Trace::unit(int step, int iteration, int worker, const proto::JobCost& c) {
  const nlohmann::json j = {{"step", step},
                            {"iteration", iteration},
                            {"unit", c.unit},
                            {"worker", worker},
                            {"cost", c.cpu_seconds},
                            {"refresh_cost", c.cpu_refresh},
                            {"kind", c.kind == proto::Refresh::refresh ? "refresh" : "reuse"},
                            {"gmres", c.gmres_iterations},
                            {"state_bytes", c.state_bytes},
                            {"factor_evictions", c.factor_evictions},
                            {"factor_rebuilt", c.factor_rebuilt != 0}};
  units_ << j.dump() << '\n';  // flushed with the iteration line
}

}  // namespace fe2
