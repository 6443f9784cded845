// Every message: a round trip, and a corrupted or truncated buffer is an error, not a crash.
#include "proto/messages.h"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace fe2::proto
