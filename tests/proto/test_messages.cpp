// Every message: a round trip, and a corrupted or truncated buffer is an error, not a crash.
#include "proto/messages.h"

#include <gtest/gtest.h>

#include <cmath>

namespace fe2::proto {
namespace {

JobInput some_job(int unit) {
  JobInput j;
  j.unit = unit;
  j.step = 3;
  j.iteration = 2;
  j.time = 0.25;
  j.dt = 0.05;
  j.apply_update = 1;
  for (int i = 0; i < 9; ++i) j.Zbar[i] = 0.01 * i, j.Zbar_dot[i] = -0.1 * i;
  j.Zbar_dot_coefficient = 40.0 + unit;
  j.activation_time = 0.0125 * unit;
  return j;
}

JobOutput some_result(int unit) {
  JobOutput o;
  o.unit = unit;
  for (int i = 0; i < 81; ++i) o.A_hom.data()[i] = i + 0.5;
  for (int i = 0; i < 9; ++i) o.P_tilde[i] = i, o.P_bar[i] = -i;
  o.r_norm = 1e-9;
  o.gmres_iterations = 4;
  o.kind = Refresh::refresh;
  o.cpu_seconds = 0.1;
  o.active_tension = 4.5e4 + unit;
  o.factor_evictions = 2 + unit;
  o.factor_rebuilt = 1;
  o.excess_flops = 3.5e8 * (unit + 1);
  o.refresh_flops = 6.7e10 + unit;
  o.failed = 1;
  o.message = "did not converge";
  return o;
}

/// Truncations and a wrong version must throw fe2::Error.
template <class M>
void expect_rejects_corruption(const Bytes& good) {
  for (size_t cut : {size_t{0}, size_t{1}, good.size() / 2, good.size() - 1})
    EXPECT_THROW(M::unpack(Bytes(good.begin(), good.begin() + cut)), Error) << "cut at " << cut;
  Bytes wrong_version = good;
  wrong_version[0] = std::byte{0x7f};
  EXPECT_THROW(M::unpack(wrong_version), Error);
  Bytes longer = good;
  longer.push_back(std::byte{0});
  EXPECT_THROW(M::unpack(longer), Error);
}

TEST(Messages, BatchRoundTripAndCorruption) {
  Batch b;
  b.jobs = {some_job(4), some_job(9)};
  Bytes bytes;
  b.pack(bytes);
  EXPECT_EQ(bytes.size(), 4 + 1 + 8 + 2 * kJobInputBytes);  // sizes from one constexpr
  const Batch back = Batch::unpack(bytes);
  ASSERT_EQ(back.jobs.size(), 2u);
  EXPECT_EQ(back.jobs[1].unit, 9);
  EXPECT_EQ(back.jobs[0].Zbar, b.jobs[0].Zbar);
  EXPECT_EQ(back.jobs[0].Zbar_dot, b.jobs[0].Zbar_dot);
  EXPECT_EQ(back.jobs[1].Zbar_dot_coefficient, 49.0);
  EXPECT_EQ(back.jobs[1].activation_time, 0.0125 * 9);
  EXPECT_FALSE(back.done);
  expect_rejects_corruption<Batch>(bytes);
  // A message of another type is refused by name.
  Control c;
  Bytes other;
  c.pack(other);
  EXPECT_THROW(Batch::unpack(other), Error);
}

TEST(Messages, PullCarriesResultsExactly) {
  Pull p;
  p.worker = 2;
  p.max_jobs = 3;
  p.results = {some_result(1), some_result(7)};
  Bytes bytes;
  p.pack(bytes);
  const Pull back = Pull::unpack(bytes);
  ASSERT_EQ(back.results.size(), 2u);
  EXPECT_EQ(back.results[1].A_hom, p.results[1].A_hom);
  EXPECT_EQ(back.results[0].message, "did not converge");
  EXPECT_EQ(back.results[0].kind, Refresh::refresh);
  EXPECT_EQ(back.results[1].active_tension, p.results[1].active_tension);
  EXPECT_EQ(back.results[1].factor_evictions, 9);
  EXPECT_EQ(back.results[0].factor_rebuilt, 1);
  EXPECT_EQ(back.results[1].excess_flops, p.results[1].excess_flops);
  EXPECT_EQ(back.results[1].refresh_flops, p.results[1].refresh_flops);
  EXPECT_EQ(back.max_jobs, 3);
  expect_rejects_corruption<Pull>(bytes);
}

TEST(Messages, ControlStatsStateHelloRoundTrip) {
  Control c;
  c.command = Command::rebalance;
  c.moves = {{3, 0, 2}, {5, 1, 0}};
  Bytes b1;
  c.pack(b1);
  const Control c2 = Control::unpack(b1);
  ASSERT_EQ(c2.moves.size(), 2u);
  EXPECT_EQ(c2.moves[1].to, 0);
  expect_rejects_corruption<Control>(b1);
  Bytes bad = b1;
  bad[4] = std::byte{9};  // command out of range
  EXPECT_THROW(Control::unpack(bad), Error);
  // A checkpoint that asks for the units' factors says so in its last byte.
  c.command = Command::checkpoint;
  c.with_factors = 1;
  Bytes bf;
  c.pack(bf);
  EXPECT_EQ(bf.size(), b1.size());
  EXPECT_EQ(Control::unpack(bf).with_factors, 1);
  EXPECT_EQ(Control::unpack(b1).with_factors, 0);
  bf.back() = std::byte{2};
  EXPECT_THROW(Control::unpack(bf), Error);

  WorkerStats s;
  s.worker = 1;
  s.busy_cpu = 0.5;
  s.t_begin = 1.0;
  s.t_end = 2.0;
  Bytes b2;
  s.pack(b2);
  EXPECT_EQ(WorkerStats::unpack(b2).busy_cpu, 0.5);
  expect_rejects_corruption<WorkerStats>(b2);

  UnitState st;
  st.unit = 11;
  st.state = Bytes(100, std::byte{0x42});
  Bytes b3;
  st.pack(b3);
  EXPECT_EQ(UnitState::unpack(b3).state, st.state);
  expect_rejects_corruption<UnitState>(b3);

  Hello h;
  h.spec_hash = 0xdeadbeef;
  h.rank = 3;
  h.ranks = 4;
  Bytes b4;
  h.pack(b4);
  EXPECT_EQ(Hello::unpack(b4).spec_hash, 0xdeadbeefu);
  expect_rejects_corruption<Hello>(b4);
}

// The cost message: what coordinator 0 needs of each job, and nothing invalid gets in.
TEST(Messages, CostReportRoundTripAndCorruption) {
  CostReport c;
  c.step = 4;
  c.iteration = 3;
  JobOutput o = some_result(12);
  o.cpu_refresh = 0.04;
  o.next_refresh = next_step | restart_step;
  o.state_bytes = 123456789;
  o.failed = 0;
  c.jobs = {JobCost::of(o), JobCost::of(some_result(2))};
  Bytes bytes;
  c.pack(bytes);
  EXPECT_EQ(bytes.size(), 4 + 2 * 4 + 8 + 2 * kJobCostBytes);  // sizes from one constexpr
  const CostReport back = CostReport::unpack(bytes);
  EXPECT_EQ(back.step, 4);
  EXPECT_EQ(back.iteration, 3);
  ASSERT_EQ(back.jobs.size(), 2u);
  const JobCost& j = back.jobs[0];
  EXPECT_EQ(j.unit, 12);
  EXPECT_EQ(j.kind, Refresh::refresh);
  EXPECT_EQ(j.gmres_iterations, 4);
  EXPECT_EQ(j.cpu_seconds, 0.1);
  EXPECT_EQ(j.cpu_refresh, 0.04);
  EXPECT_EQ(j.next_refresh, next_step | restart_step);
  EXPECT_EQ(j.state_bytes, 123456789u);
  EXPECT_EQ(j.failed, 0);
  EXPECT_EQ(j.factor_evictions, 14);
  EXPECT_EQ(j.factor_rebuilt, 1);
  EXPECT_EQ(back.jobs[1].failed, 1);
  expect_rejects_corruption<CostReport>(bytes);
  // Values that would mislead the rebalancer are refused on receipt.
  auto with = [&](auto change) {
    CostReport bad = c;
    change(bad.jobs[1]);
    Bytes b;
    bad.pack(b);
    return b;
  };
  EXPECT_THROW(CostReport::unpack(with([](JobCost& x) { x.unit = -1; })), Error);
  EXPECT_THROW(CostReport::unpack(with([](JobCost& x) { x.cpu_seconds = -1.0; })), Error);
  EXPECT_THROW(CostReport::unpack(with([](JobCost& x) { x.cpu_refresh = NAN; })), Error);
  EXPECT_THROW(CostReport::unpack(with([](JobCost& x) { x.next_refresh = 8; })), Error);
  EXPECT_THROW(CostReport::unpack(with([](JobCost& x) { x.kind = static_cast<Refresh>(2); })), Error);
  EXPECT_THROW(CostReport::unpack(with([](JobCost& x) { x.factor_evictions = -1; })), Error);
  EXPECT_THROW(CostReport::unpack(with([](JobCost& x) { x.factor_rebuilt = 2; })), Error);
  // A message of another type is refused.
  Pull p;
  Bytes other;
  p.pack(other);
  EXPECT_THROW(CostReport::unpack(other), Error);
}

// A unit's micro fields (output.units): every number arrives, and sizes that do not
// fit one mesh or a non-finite value are refused on receipt.
TEST(Messages, UnitFieldsRoundTripAndCorruption) {
  UnitFields f;
  f.unit = 7;
  f.step = 12;
  for (int i = 0; i < 9; ++i) f.Zbar[i] = 0.01 * i, f.P_bar[i] = 100.0 - i;
  f.active = true;
  for (int i = 0; i < 3 * 5; ++i) f.w.push_back(1e-3 * i);
  for (int i = 0; i < 9 * 2; ++i) f.P.push_back(i - 4.5);
  f.det_F = {0.99, 1.01};
  f.active_tension = {0.0, 5.5e4};
  Bytes bytes;
  f.pack(bytes);
  EXPECT_EQ(bytes.size(), 4 + 2 * 4 + 18 * 8 + 1 + 4 * 8 + (15 + 18 + 2 + 2) * 8);
  const UnitFields back = UnitFields::unpack(bytes);
  EXPECT_EQ(back.unit, 7);
  EXPECT_EQ(back.step, 12);
  EXPECT_EQ(back.Zbar, f.Zbar);
  EXPECT_EQ(back.P_bar, f.P_bar);
  EXPECT_TRUE(back.active);
  EXPECT_EQ(back.w, f.w);
  EXPECT_EQ(back.P, f.P);
  EXPECT_EQ(back.det_F, f.det_F);
  EXPECT_EQ(back.active_tension, f.active_tension);
  EXPECT_EQ(back.nodes(), 5);
  EXPECT_EQ(back.cells(), 2);
  expect_rejects_corruption<UnitFields>(bytes);
  auto with = [&](auto change) {
    UnitFields bad = f;
    change(bad);
    Bytes b;
    bad.pack(b);
    return b;
  };
  EXPECT_THROW(UnitFields::unpack(with([](UnitFields& x) { x.w.pop_back(); })), Error);
  EXPECT_THROW(UnitFields::unpack(with([](UnitFields& x) { x.P.pop_back(); })), Error);
  EXPECT_THROW(UnitFields::unpack(with([](UnitFields& x) { x.active_tension.push_back(0); })), Error);
  EXPECT_THROW(UnitFields::unpack(with([](UnitFields& x) { x.det_F[1] = NAN; })), Error);
  EXPECT_THROW(UnitFields::unpack(with([](UnitFields& x) { x.unit = -2; })), Error);

  // The request: a Control 'fields' naming (unit, holder, rank 0).
  Control c;
  c.command = Command::fields;
  c.step = 12;
  c.moves = {{7, 2, 0}};
  Bytes cb;
  c.pack(cb);
  const Control c2 = Control::unpack(cb);
  EXPECT_EQ(c2.command, Command::fields);
  ASSERT_EQ(c2.moves.size(), 1u);
  EXPECT_EQ(c2.moves[0].from, 2);
  Bytes other;
  c.pack(other);
  EXPECT_THROW(UnitFields::unpack(other), Error);  // a Control is not a Fields message
}

TEST(Messages, ResultCarriesTheNextRefreshBitsAndStateSize) {
  Pull p;
  p.worker = 0;
  JobOutput o = some_result(3);
  o.next_refresh = next_iteration;
  o.state_bytes = 4096;
  p.results = {o};
  Bytes bytes;
  p.pack(bytes);
  const Pull back = Pull::unpack(bytes);
  EXPECT_EQ(back.results[0].next_refresh, next_iteration);
  EXPECT_EQ(back.results[0].state_bytes, 4096u);
  o.next_refresh = 9;  // no such bit
  p.results = {o};
  Bytes bad;
  p.pack(bad);
  EXPECT_THROW(Pull::unpack(bad), Error);
}

// Which bit answers for which next job: (s, i+1), (s, 1) and (s+1, 1); anything else
// is unknown (no refresh assumed).
TEST(Messages, RefreshesNextPicksTheBitOfTheFollowingJob) {
  EXPECT_TRUE(refreshes_next(next_iteration, 5, 2, 5, 3));
  EXPECT_FALSE(refreshes_next(restart_step | next_step, 5, 2, 5, 3));
  EXPECT_TRUE(refreshes_next(restart_step, 5, 2, 5, 1));
  EXPECT_FALSE(refreshes_next(next_iteration | next_step, 5, 2, 5, 1));
  EXPECT_TRUE(refreshes_next(next_step, 5, 2, 6, 1));
  EXPECT_FALSE(refreshes_next(next_iteration | restart_step, 5, 2, 6, 1));
  EXPECT_FALSE(refreshes_next(all_next_jobs, 5, 2, 7, 1));  // not a job that can follow
  EXPECT_FALSE(refreshes_next(all_next_jobs, 5, 2, 5, 4));
  EXPECT_FALSE(refreshes_next(all_next_jobs, -2, 0, 0, 1));  // after a rollback: unknown
}

}  // namespace
}  // namespace fe2::proto
