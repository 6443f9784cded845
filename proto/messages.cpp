#include "proto/messages.h"

#include <algorithm>
#include <cmath>

namespace fe2::proto {

namespace {

void header(ByteWriter& w, Type t) {
  w.put<uint16_t>(kProtocolVersion);
  w.put<uint16_t>(static_cast<uint16_t>(t));
}


void finish(const ByteReader& r) {
  if (!r.at_end())
    throw Error(fmt::format("{}: {} trailing bytes after the message", r.what(), r.remaining()));
}

template <class T>
void check_count(const ByteReader& r, uint64_t n, size_t min_bytes_each) {
  if (n > r.remaining() / std::max<size_t>(1, min_bytes_each))
    throw Error(fmt::format("{}: {} entries cannot fit in the {} bytes left", r.what(), n,
                            r.remaining()));
}

}  // namespace

const char* name_of(Type t) {
  switch (t) {
    case Type::hello: return "Hello";
    case Type::control: return "Control";
    case Type::pull: return "Pull";
    case Type::batch: return "Batch";
    case Type::stats: return "Stats";
    case Type::state: return "State";
    case Type::costs: return "Costs";
    case Type::unit_fields: return "Fields";
  }
  return "unknown";
}

void check_header(ByteReader& r, Type expected) {
  const auto version = r.get<uint16_t>();
  const auto type = r.get<uint16_t>();
  if (version != kProtocolVersion)
    throw Error(fmt::format("{}: protocol version {} received, this rank speaks {}", r.what(),
                            version, kProtocolVersion));
  if (type != static_cast<uint16_t>(expected))
    throw Error(fmt::format("{}: message type {} received where {} ({}) was expected", r.what(),
                            type, static_cast<int>(expected), name_of(expected)));
}

void pack_job(ByteWriter& w, const JobInput& j) {
  w.put(j.unit);
  w.put(j.step);
  w.put(j.iteration);
  w.put(j.time);
  w.put(j.dt);
  w.put(j.apply_update);
  w.put(j.force_refresh);
  w.put_raw(j.Zbar.data(), 9 * sizeof(double));
  w.put_raw(j.Zbar_dot.data(), 9 * sizeof(double));
  w.put(j.Zbar_dot_coefficient);
  w.put(j.activation_time);
  w.put(j.settle);
}

JobInput unpack_job(ByteReader& r) {
  JobInput j;
  j.unit = r.get<int32_t>();
  j.step = r.get<int32_t>();
  j.iteration = r.get<int32_t>();
  j.time = r.get<double>();
  j.dt = r.get<double>();
  j.apply_update = r.get<uint8_t>();
  j.force_refresh = r.get<uint8_t>();
  r.get_raw(j.Zbar.data(), 9 * sizeof(double));
  r.get_raw(j.Zbar_dot.data(), 9 * sizeof(double));
  j.Zbar_dot_coefficient = r.get<double>();
  j.activation_time = r.get<double>();
  j.settle = r.get<uint8_t>();
  if (j.unit < 0 || j.iteration < 1 || !j.Zbar.allFinite() || !j.Zbar_dot.allFinite() ||
      !std::isfinite(j.Zbar_dot_coefficient) || !std::isfinite(j.activation_time))
    throw Error(fmt::format("{}: invalid job (unit {}, iteration {})", r.what(), j.unit, j.iteration));
  return j;
}

void pack_result(ByteWriter& w, const JobOutput& o) {
  w.put(o.unit);
  w.put_raw(o.A_hom.data(), 81 * sizeof(double));
  w.put_raw(o.P_tilde.data(), 9 * sizeof(double));
  w.put_raw(o.P_bar.data(), 9 * sizeof(double));
  w.put(o.r_norm);
  w.put(o.r_ref);
  w.put(o.r_floor);
  w.put(o.gmres_iterations);
  w.put(static_cast<uint8_t>(o.kind));
  w.put(o.cpu_seconds);
  w.put(o.cpu_assembly);
  w.put(o.cpu_refresh);
  w.put(o.cpu_solve);
  w.put(o.next_refresh);
  w.put(o.state_bytes);
  w.put(o.active_tension);
  w.put(o.factor_evictions);
  w.put(o.factor_rebuilt);
  w.put(o.excess_flops);
  w.put(o.refresh_flops);
  w.put(o.failed);
  w.put_string(o.message);
}

JobOutput unpack_result(ByteReader& r) {
  JobOutput o;
  o.unit = r.get<int32_t>();
  r.get_raw(o.A_hom.data(), 81 * sizeof(double));
  r.get_raw(o.P_tilde.data(), 9 * sizeof(double));
  r.get_raw(o.P_bar.data(), 9 * sizeof(double));
  o.r_norm = r.get<double>();
  o.r_ref = r.get<double>();
  o.r_floor = r.get<double>();
  o.gmres_iterations = r.get<int32_t>();
  const auto kind = r.get<uint8_t>();
  if (kind > 1) throw Error(fmt::format("{}: refresh kind {} out of range", r.what(), kind));
  o.kind = static_cast<Refresh>(kind);
  o.cpu_seconds = r.get<double>();
  o.cpu_assembly = r.get<double>();
  o.cpu_refresh = r.get<double>();
  o.cpu_solve = r.get<double>();
  o.next_refresh = r.get<uint8_t>();
  o.state_bytes = r.get<uint64_t>();
  o.active_tension = r.get<double>();
  o.factor_evictions = r.get<int32_t>();
  o.factor_rebuilt = r.get<uint8_t>();
  o.excess_flops = r.get<double>();
  o.refresh_flops = r.get<double>();
  o.failed = r.get<uint8_t>();
  o.message = r.get_string();
  if (o.unit < 0) throw Error(fmt::format("{}: result for unit {}", r.what(), o.unit));
  if (o.next_refresh > all_next_jobs)
    throw Error(fmt::format("{}: next-refresh bits {} out of range", r.what(), o.next_refresh));
  if (!(o.excess_flops >= 0 && o.excess_flops < 1e30) || !(o.refresh_flops >= 0 && o.refresh_flops < 1e30))
    throw Error(fmt::format("{}: excess flops {}, refresh flops {}: expected finite and >= 0", r.what(),
                            o.excess_flops, o.refresh_flops));
  if (o.factor_evictions < 0 || o.factor_rebuilt > 1)
    throw Error(fmt::format("{}: factor evictions {}, rebuilt flag {} out of range", r.what(),
                            o.factor_evictions, o.factor_rebuilt));
  return o;
}

void Hello::pack(Bytes& out) const {
  ByteWriter w(out);
  header(w, Type::hello);
  w.put(spec_hash);
  w.put(rank);
  w.put(ranks);
}

Hello Hello::unpack(const Bytes& in) {
  ByteReader r(in, "Hello message");
  check_header(r, Type::hello);
  Hello h;
  h.spec_hash = r.get<uint64_t>();
  h.rank = r.get<int32_t>();
  h.ranks = r.get<int32_t>();
  finish(r);
  return h;
}

void Control::pack(Bytes& out) const {
  ByteWriter w(out);
  header(w, Type::control);
  w.put(static_cast<uint8_t>(command));
  w.put(step);
  w.put(iteration);
  w.put(time);
  w.put(dt);
  w.put_array(moves.data(), moves.size());
  w.put(with_factors);
}

Control Control::unpack(const Bytes& in) {
  ByteReader r(in, "Control message");
  check_header(r, Type::control);
  Control c;
  const auto cmd = r.get<uint8_t>();
  if (cmd < 1 || cmd > kLastCommand) throw Error(fmt::format("Control message: unknown command {}", cmd));
  c.command = static_cast<Command>(cmd);
  c.step = r.get<int32_t>();
  c.iteration = r.get<int32_t>();
  c.time = r.get<double>();
  c.dt = r.get<double>();
  c.moves = r.get_array<Move>();
  c.with_factors = r.get<uint8_t>();
  finish(r);
  if (c.with_factors > 1)
    throw Error(fmt::format("Control message: with_factors {}, expected 0 or 1", c.with_factors));
  for (const Move& m : c.moves)
    if (m.unit < 0 || m.from < 0 || m.to < 0)
      throw Error(fmt::format("Control message: invalid move of unit {} from {} to {}", m.unit,
                              m.from, m.to));
  return c;
}

void Pull::pack(Bytes& out) const {
  ByteWriter w(out);
  header(w, Type::pull);
  w.put(worker);
  w.put(max_jobs);
  w.put<uint64_t>(results.size());
  for (const auto& o : results) pack_result(w, o);
}

Pull Pull::unpack(const Bytes& in) {
  ByteReader r(in, "Pull message");
  check_header(r, Type::pull);
  Pull p;
  p.worker = r.get<int32_t>();
  p.max_jobs = r.get<int32_t>();
  const auto n = r.get<uint64_t>();
  check_count<JobOutput>(r, n, kJobOutputBytes);
  for (uint64_t i = 0; i < n; ++i) p.results.push_back(unpack_result(r));
  finish(r);
  if (p.worker < 0 || p.max_jobs < 0)
    throw Error(fmt::format("Pull message: worker {}, max_jobs {}", p.worker, p.max_jobs));
  return p;
}

void Batch::pack(Bytes& out) const {
  ByteWriter w(out);
  header(w, Type::batch);
  w.put<uint8_t>(done);
  w.put<uint64_t>(jobs.size());
  for (const auto& j : jobs) pack_job(w, j);
}

Batch Batch::unpack(const Bytes& in) {
  ByteReader r(in, "Batch message");
  check_header(r, Type::batch);
  Batch b;
  b.done = r.get<uint8_t>() != 0;
  const auto n = r.get<uint64_t>();
  check_count<JobInput>(r, n, kJobInputBytes);
  for (uint64_t i = 0; i < n; ++i) b.jobs.push_back(unpack_job(r));
  finish(r);
  return b;
}

void WorkerStats::pack(Bytes& out) const {
  ByteWriter w(out);
  header(w, Type::stats);
  w.put(*this);
}

WorkerStats WorkerStats::unpack(const Bytes& in) {
  ByteReader r(in, "Stats message");
  check_header(r, Type::stats);
  const auto s = r.get<WorkerStats>();
  finish(r);
  if (s.worker < 0 || s.t_end < s.t_begin)
    throw Error(fmt::format("Stats message: worker {}, interval [{}, {}]", s.worker, s.t_begin, s.t_end));
  return s;
}

void UnitState::pack(Bytes& out) const {
  ByteWriter w(out);
  header(w, Type::state);
  w.put(unit);
  w.put_array(state.data(), state.size());
}

UnitState UnitState::unpack(const Bytes& in) {
  ByteReader r(in, "State message");
  check_header(r, Type::state);
  UnitState s;
  s.unit = r.get<int32_t>();
  s.state = r.get_array<std::byte>();
  finish(r);
  if (s.unit < 0) throw Error(fmt::format("State message: unit {}", s.unit));
  return s;
}

void UnitFields::pack(Bytes& out) const {
  ByteWriter w(out);
  header(w, Type::unit_fields);
  w.put(unit);
  w.put(step);
  w.put_raw(Zbar.data(), 9 * sizeof(double));
  w.put_raw(P_bar.data(), 9 * sizeof(double));
  w.put<uint8_t>(active);
  w.put_array(this->w.data(), this->w.size());
  w.put_array(P.data(), P.size());
  w.put_array(det_F.data(), det_F.size());
  w.put_array(active_tension.data(), active_tension.size());
}

UnitFields UnitFields::unpack(const Bytes& in) {
  ByteReader r(in, "Fields message");
  check_header(r, Type::unit_fields);
  UnitFields f;
  f.unit = r.get<int32_t>();
  f.step = r.get<int32_t>();
  r.get_raw(f.Zbar.data(), 9 * sizeof(double));
  r.get_raw(f.P_bar.data(), 9 * sizeof(double));
  const auto active = r.get<uint8_t>();
  f.active = active != 0;
  f.w = r.get_array<double>();
  f.P = r.get_array<double>();
  f.det_F = r.get_array<double>();
  f.active_tension = r.get_array<double>();
  finish(r);
  const size_t m = f.det_F.size();
  auto finite = [](const std::vector<double>& v) {
    return std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); });
  };
  if (f.unit < 0 || f.step < 0 || active > 1 || f.w.empty() || f.w.size() % 3 != 0 || m == 0 ||
      f.P.size() != 9 * m || f.active_tension.size() != m)
    throw Error(fmt::format("Fields message: invalid fields (unit {}, step {}, active {}, {} w "
                            "values, {} P values, {} det F, {} T_a; expected 3 per node, 9, 1 and "
                            "1 per cell)",
                            f.unit, f.step, active, f.w.size(), f.P.size(), m,
                            f.active_tension.size()));
  if (!f.Zbar.allFinite() || !f.P_bar.allFinite() || !finite(f.w) || !finite(f.P) ||
      !finite(f.det_F) || !finite(f.active_tension))
    throw Error(fmt::format("Fields message: non-finite value in the fields of unit {}", f.unit));
  return f;
}

JobCost JobCost::of(const JobOutput& o) {
  JobCost c;
  c.unit = o.unit;
  c.kind = o.kind;
  c.gmres_iterations = o.gmres_iterations;
  c.cpu_seconds = o.cpu_seconds;
  c.cpu_refresh = o.cpu_refresh;
  c.next_refresh = o.next_refresh;
  c.state_bytes = o.state_bytes;
  c.factor_evictions = o.factor_evictions;
  c.factor_rebuilt = o.factor_rebuilt;
  c.failed = o.failed;
  return c;
}

void CostReport::pack(Bytes& out) const {
  ByteWriter w(out);
  header(w, Type::costs);
  w.put(step);
  w.put(iteration);
  w.put<uint64_t>(jobs.size());
  for (const JobCost& c : jobs) {
    w.put(c.unit);
    w.put(static_cast<uint8_t>(c.kind));
    w.put(c.gmres_iterations);
    w.put(c.cpu_seconds);
    w.put(c.cpu_refresh);
    w.put(c.next_refresh);
    w.put(c.state_bytes);
    w.put(c.factor_evictions);
    w.put(c.factor_rebuilt);
    w.put(c.failed);
  }
}

CostReport CostReport::unpack(const Bytes& in) {
  ByteReader r(in, "Costs message");
  check_header(r, Type::costs);
  CostReport rep;
  rep.step = r.get<int32_t>();
  rep.iteration = r.get<int32_t>();
  const auto n = r.get<uint64_t>();
  check_count<JobCost>(r, n, kJobCostBytes);
  rep.jobs.resize(n);
  for (JobCost& c : rep.jobs) {
    c.unit = r.get<int32_t>();
    const auto kind = r.get<uint8_t>();
    c.gmres_iterations = r.get<int32_t>();
    c.cpu_seconds = r.get<double>();
    c.cpu_refresh = r.get<double>();
    c.next_refresh = r.get<uint8_t>();
    c.state_bytes = r.get<uint64_t>();
    c.factor_evictions = r.get<int32_t>();
    c.factor_rebuilt = r.get<uint8_t>();
    c.failed = r.get<uint8_t>();
    // Validate on receipt: these numbers steer the rebalancer and land in the trace.
    if (c.unit < 0 || kind > 1 || c.gmres_iterations < 0 || !(c.cpu_seconds >= 0.0) ||
        !(c.cpu_refresh >= 0.0) || !std::isfinite(c.cpu_seconds) || !std::isfinite(c.cpu_refresh) ||
        c.next_refresh > all_next_jobs || c.failed > 1 || c.factor_evictions < 0 ||
        c.factor_rebuilt > 1)
      throw Error(fmt::format(
          "Costs message: invalid job cost (unit {}, kind {}, GMRES {}, cpu {} s, refresh {} s, "
          "next-refresh bits {}, failed {})",
          c.unit, kind, c.gmres_iterations, c.cpu_seconds, c.cpu_refresh, c.next_refresh, c.failed));
    c.kind = static_cast<Refresh>(kind);
  }
  finish(r);
  if (rep.step < 0 || rep.iteration < 1)
    throw Error(fmt::format("Costs message: step {}, iteration {}", rep.step, rep.iteration));
  return rep;
}

}  // namespace fe2::proto
