#include "coordinator/output/Checkpoint.h"

#include "common/cpu_timer.h"
#include "proto/version.h"

#include <algorithm>
#include <memory>

namespace fe2 {

namespace {

/// A JSON pointer at or under a model's micro unit: /models/<name>/unit[/...].
bool is_unit_key(const std::string& pointer) {
  const std::string models = "/models/";
  if (pointer.rfind(models, 0) != 0) return false;
  const size_t slash = pointer.find('/', models.size());
  if (slash == std::string::npos) return false;
  const std::string rest = pointer.substr(slash);
  return rest == "/unit" || rest.rfind("/unit/", 0) == 0;
}

template <class T>
void put_vector(ByteWriter& w, const std::vector<T>& v) {
  w.put_array(v.data(), v.size());
}

void put_bools(ByteWriter& w, const std::vector<bool>& v) {
  const std::vector<uint8_t> b(v.begin(), v.end());
  put_vector(w, b);
}

std::vector<bool> get_bools(ByteReader& r) {
  const auto b = r.get_array<uint8_t>();
  return {b.begin(), b.end()};
}

void put_strings(ByteWriter& w, const std::vector<std::string>& v) {
  w.put<uint64_t>(v.size());
  for (const std::string& s : v) w.put_string(s);
}

std::vector<std::string> get_strings(ByteReader& r) {
  const auto n = r.get<uint64_t>();
  if (n > r.remaining() / sizeof(uint64_t))
    throw InputError(fmt::format("{}: {} strings cannot fit in the bytes left", r.what(), n));
  std::vector<std::string> v(n);
  for (auto& s : v) s = r.get_string();
  return v;
}

void put_flows(ByteWriter& w, const CavityFlows& f) {
  w.put<int32_t>(f.n);
  put_vector(w, f.Q_net);
  put_vector(w, f.dQ_dp);
  put_vector(w, f.Q_in);
  put_vector(w, f.Q_out);
  put_bools(w, f.inflow_open);
  put_bools(w, f.outflow_open);
  put_strings(w, f.phase);
  put_vector(w, f.pressures);
  put_vector(w, f.volumes);
  put_vector(w, f.flows);
  w.put<int32_t>(f.newton_iterations);
}

CavityFlows get_flows(ByteReader& r) {
  CavityFlows f;
  f.n = r.get<int32_t>();
  f.Q_net = r.get_array<double>();
  f.dQ_dp = r.get_array<double>();
  f.Q_in = r.get_array<double>();
  f.Q_out = r.get_array<double>();
  f.inflow_open = get_bools(r);
  f.outflow_open = get_bools(r);
  f.phase = get_strings(r);
  f.pressures = r.get_array<double>();
  f.volumes = r.get_array<double>();
  f.flows = r.get_array<double>();
  f.newton_iterations = r.get<int32_t>();
  return f;
}

void put_record(ByteWriter& w, const StepRecord& s) {
  w.put<int32_t>(s.step);
  w.put(s.time);
  w.put<int32_t>(s.iterations);
  w.put<int32_t>(s.cutbacks);
  w.put<int32_t>(s.retries);
  w.put<uint64_t>(s.residuals.size());
  for (const auto& f : s.residuals) {
    w.put_string(f.field);
    put_vector(w, f.values);
    put_vector(w, f.corrections);
  }
  put_vector(w, s.micro_residuals);
  w.put<int32_t>(s.gmres_iterations);
  w.put<int32_t>(s.refreshes);
  w.put<int32_t>(s.factor_evictions);
  w.put<int32_t>(s.factor_rebuilds);
  w.put(s.factor_rebuild_cpu_seconds);
  w.put<int32_t>(s.forced_refreshes);
  w.put<int32_t>(s.collective_refreshes);
  w.put(s.wall_seconds);
  w.put(s.micro_cpu_seconds);
  put_vector(w, s.cavity_volumes);
  put_vector(w, s.load_pressures);
  w.put<uint64_t>(s.probes.size());
  for (const Vec3& x : s.probes) w.put_raw(x.data(), 3 * sizeof(double));
  put_vector(w, s.cavity_pressures);
  put_flows(w, s.circulation);
  w.put<uint64_t>(s.observables.size());
  for (const auto& [name, value] : s.observables) {
    w.put_string(name);
    w.put(value);
  }
}

StepRecord get_record(ByteReader& r) {
  StepRecord s;
  s.step = r.get<int32_t>();
  s.time = r.get<double>();
  s.iterations = r.get<int32_t>();
  s.cutbacks = r.get<int32_t>();
  s.retries = r.get<int32_t>();
  const auto fields = r.get<uint64_t>();
  if (fields > r.remaining())
    throw InputError(fmt::format("{}: {} residual fields cannot fit in the bytes left", r.what(), fields));
  s.residuals.resize(fields);
  for (auto& f : s.residuals) {
    f.field = r.get_string();
    f.values = r.get_array<double>();
    f.corrections = r.get_array<double>();
  }
  s.micro_residuals = r.get_array<double>();
  s.gmres_iterations = r.get<int32_t>();
  s.refreshes = r.get<int32_t>();
  s.factor_evictions = r.get<int32_t>();
  s.factor_rebuilds = r.get<int32_t>();
  s.factor_rebuild_cpu_seconds = r.get<double>();
  s.forced_refreshes = r.get<int32_t>();
  s.collective_refreshes = r.get<int32_t>();
  s.wall_seconds = r.get<double>();
  s.micro_cpu_seconds = r.get<double>();
  s.cavity_volumes = r.get_array<double>();
  s.load_pressures = r.get_array<double>();
  const auto probes = r.get<uint64_t>();
  if (probes > r.remaining() / (3 * sizeof(double)))
    throw InputError(fmt::format("{}: {} probes cannot fit in the bytes left", r.what(), probes));
  s.probes.resize(probes);
  for (Vec3& x : s.probes) r.get_raw(x.data(), 3 * sizeof(double));
  s.cavity_pressures = r.get_array<double>();
  s.circulation = get_flows(r);
  const auto observables = r.get<uint64_t>();
  if (observables > r.remaining())
    throw InputError(fmt::format("{}: {} observables cannot fit in the bytes left", r.what(), observables));
  for (uint64_t k = 0; k < observables; ++k) {
    std::string name = r.get_string();
    s.observables.emplace_back(std::move(name), r.get<double>());
  }
  return s;
}

}  // namespace

Bytes pack_run_section(const RunResult& done, const TraceOffsets& trace) {
  Bytes b;
  ByteWriter w(b);
  w.put<int32_t>(done.steps);
  w.put<int32_t>(done.newton_iterations);
  w.put(done.edv_change);
  w.put<uint64_t>(done.history.size());
  for (const StepRecord& s : done.history) put_record(w, s);
  w.put(trace);
  return b;
}

RunResult unpack_run_section(const Bytes& b, TraceOffsets& trace, const std::string& what) {
  ByteReader r(b, what);
  RunResult done;
  done.steps = r.get<int32_t>();
  done.newton_iterations = r.get<int32_t>();
  done.edv_change = r.get<double>();
  const auto n = r.get<uint64_t>();
  if (n != static_cast<uint64_t>(done.steps) || done.steps < 0)
    throw InputError(fmt::format("{}: {} step records for {} steps", what, n, done.steps));
  for (uint64_t k = 0; k < n; ++k) done.history.push_back(get_record(r));
  trace = r.get<TraceOffsets>();
  if (!r.at_end()) throw InputError(fmt::format("{}: {} bytes after the run section", what, r.remaining()));
  done.converged = true;
  return done;
}

CheckpointWritten write_checkpoint(const std::string& path, const RunSpec& spec, int ranks, Simulation& sim,
                                   PointEvaluator& points, const proto::Group& coords, const RunResult& done,
                                   const TraceOffsets& trace) {
  const double t0 = wall_seconds();
  CheckpointHeader h;
  ByteWriter macro(h.macro);
  sim.save_state(macro);  // every coordinator: it also drops the kept macro factor
  std::unique_ptr<CheckpointWriter> file;
  if (coords.rank() == 0) {
    h.protocol = proto::kProtocolVersion;
    h.spec_hash = spec.hash;
    h.spec_text = spec.raw.dump();
    h.steps = done.steps;
    h.time = done.history.empty() ? 0.0 : done.history.back().time;
    h.ranks = ranks;
    h.coordinators = coords.size();
    h.run = pack_run_section(done, trace);
    file = std::make_unique<CheckpointWriter>(path, h, spec.num_points());
  }
  points.save_states([&](int unit, const Bytes& state) { file->add_unit(unit, state); }, spec.checkpoint_factors);
  CheckpointWritten out;
  if (file) {
    out.path = path;
    out.bytes = file->finish();
  }
  out.seconds = wall_seconds() - t0;
  return out;
}

RunResult restore_checkpoint(const CheckpointFile* file, Simulation& sim, PointEvaluator& points,
                             const proto::Group& coords, TraceOffsets& trace, bool fresh_points) {
  Bytes macro, run;
  std::string what = "checkpoint";
  if (coords.rank() == 0) {
    macro = file->header().macro;
    run = file->header().run;
    what = fmt::format("checkpoint '{}'", file->path());
  }
  coords.bcast(macro, 0);
  coords.bcast(run, 0);
  ByteReader r(macro, what + " (macro state)");
  sim.restore_state(r);
  if (!r.at_end()) throw InputError(fmt::format("{}: {} bytes after the macro state", what, r.remaining()));
  const RunResult done = unpack_run_section(run, trace, what + " (run section)");
  if (fresh_points) {  // the points stay as built, in their initial state, and settle first
    sim.settle_fresh_points();
    return done;
  }
  std::vector<int> units;
  if (file) {
    units = file->units();
    const auto n = static_cast<size_t>(sim.spec().num_points());
    if (units.size() != n)
      throw InputError(fmt::format("{} holds {} point states; this spec has {} points", what, units.size(), n));
    std::vector<int> sorted = units;
    std::sort(sorted.begin(), sorted.end());
    for (size_t k = 0; k < n; ++k)
      if (sorted[k] != static_cast<int>(k))
        throw InputError(fmt::format("{} holds no state of point {}", what, k));
  }
  points.restore_states(units, [&](int unit) { return file->unit_state(unit); });
  return done;
}

std::vector<std::string> spec_differences(const nlohmann::json& saved, const nlohmann::json& now, bool fresh_points) {
  std::vector<std::string> keys;
  for (const auto& op : nlohmann::json::diff(saved, now)) {
    const std::string p = op.at("path").get<std::string>();
    auto under = [&](const std::string& top) { return p == top || p.rfind(top + "/", 0) == 0; };
    if (under("/output") || under("/farm") || under("/title")) continue;
    if (fresh_points && is_unit_key(p)) continue;
    keys.push_back(p);
  }
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  return keys;
}

}  // namespace fe2
