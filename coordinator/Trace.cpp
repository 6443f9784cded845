#include "coordinator/Trace.h"

#include "common/error.h"

namespace fe2 {

namespace {
std::ofstream open(const std::string& path) {
  std::ofstream f(path, std::ios::trunc);
  if (!f) throw InputError(fmt::format("cannot write trace file '{}'", path));
  return f;
}
}  // namespace

Trace::Trace(const std::string& dir)
    : iterations_(open(dir + "/trace_iterations.jsonl")),
      workers_(open(dir + "/trace_workers.jsonl")),
      units_(open(dir + "/trace_units.jsonl")) {}

void Trace::iteration(const IterationTiming& t) {
  const nlohmann::json j = {{"step", t.step},         {"iteration", t.iteration},
                            {"entire", t.entire},     {"micro_lc", t.micro_lc},
                            {"macro", t.macro},       {"assemble", t.assemble},
                            {"solve", t.solve},       {"comm1", t.comm1},
                            {"comm2", t.comm2},       {"bytes", t.bytes},
                            {"migrations", t.migrations}, {"jobs", t.jobs},
                            {"local_jobs", t.local_jobs}, {"local_cpu", t.local_cpu},
                            {"macro_law_jobs_sent", t.macro_law_jobs_sent}};
  units_.flush();
  workers_.flush();
  iterations_ << j.dump() << '\n' << std::flush;
}

void Trace::worker(const proto::WorkerStats& s, double micro_phase, double t0) {
  const nlohmann::json j = {{"step", s.step},
                            {"iteration", s.iteration},
                            {"worker", s.worker},
                            {"units", s.units_held},
                            {"jobs", s.jobs},
                            {"busy", s.busy_cpu},
                            {"busy_wall", s.busy_wall},
                            {"idle", std::max(0.0, micro_phase - s.busy_wall)},
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
