// The material-point context: every micro Gauss point and every
// macro-law point gets t, Δt, its rate Ż and its own history, which the point model
// commits, rolls back and serializes. The law of tests/support/history_law.h records
// the context it was given in its history and stiffens with an internal variable α
// integrated from the committed history, so wrong context, a lost commit, a missed
// rollback or a history dropped in transit all change numbers.
#include "tests/support/history_law.h"
#include "tests/worker/unit_fixtures.h"
#include "worker/MacroLawPoint.h"
#include "worker/micro_kernel.h"

#include <gtest/gtest.h>

#include <cstring>

namespace fe2 {
namespace {

using test::gradient;
using test::HistoryLaw;

constexpr double kRate = 5.0;  // k of the history law

/// Two stiff cells with history in a soft matrix without: offsets must skip the matrix.
MicroModelPtr history_model() {
  CellLayout c;
  c.kind = "two_cells";
  c.size = Vec3(1.0, 0.4, 0.4);
  c.resolution = {6, 4, 4};
  c.gap = 0.1;
  c.cross_section = 0.5;
  return test::make_unit_model(c, {std::make_shared<NeoHookean>(1.0e3, 0.3),          // ecm
                                   std::make_shared<HistoryLaw>(2.0e4, 0.4, kRate)});  // cell
}

proto::JobInput job(int step, int iteration, const Vec9& Z, const Vec9& Z_n, double time,
                    double dt, bool force_refresh = false) {
  proto::JobInput in;
  in.step = step;
  in.iteration = iteration;
  in.time = time;
  in.dt = dt;
  in.apply_update = iteration > 1;
  in.force_refresh = force_refresh;
  in.Zbar = Z;
  in.Zbar_dot = (Z - Z_n) / dt;  // the coordinator's quasi-static rate
  return in;
}

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

void expect_same_bits(const proto::JobOutput& a, const proto::JobOutput& b, const std::string& at) {
  EXPECT_EQ(std::memcmp(a.A_hom.data(), b.A_hom.data(), sizeof(double) * 81), 0) << at;
  EXPECT_EQ(std::memcmp(a.P_tilde.data(), b.P_tilde.data(), sizeof(double) * 9), 0) << at;
  EXPECT_EQ(std::memcmp(a.P_bar.data(), b.P_bar.data(), sizeof(double) * 9), 0) << at;
  EXPECT_EQ(a.r_norm, b.r_norm) << at;
}

const Vec9 Z1 = gradient({0.03, 0.0, 0.01, 0.0, -0.01, 0.0, 0.0, 0.0, 0.01});
const Vec9 Z2 = 1.5 * Z1;
const Vec9 Z3 = gradient({0.05, 0.01, 0.01, 0.0, -0.02, 0.0, 0.01, 0.0, 0.02});
const Vec9 Z_failed = gradient({-0.35, 0.1, 0.0, 0.05, 0.3, 0.0, 0.0, 0.0, -0.2});

// ---------------------------------------------------------------- micro Gauss points

// At every Gauss point of the cells: t and Δt of the job; Ż = Ż̄ + B̃ẇ with
// ẇ = (w − w_committed)/Δt, recomputed here from the unit's w and the shape gradients;
// α_{n+1} from the α committed at the end of the previous step.
TEST(PointHistory, MicroGaussPointsGetTimeStepRateAndCommittedHistory) {
  const auto model = history_model();
  MicroUnit unit(model);
  size_t cell_elements = 0;
  for (int e = 0; e < model->num_elements(); ++e)
    cell_elements += model->material_of(e).history_size() > 0;
  ASSERT_GT(cell_elements, 0u);
  ASSERT_LT(cell_elements, static_cast<size_t>(model->num_elements()));
  EXPECT_EQ(unit.history().size(), cell_elements * 8 * HistoryLaw::kSize);

  for (int it = 1; it <= 3; ++it) unit.iterate(job(0, it, Z1, Vec9::Zero(), 0.1, 0.1));
  unit.commit_step();
  const Vec w_n = unit.w();
  const std::vector<double> history_n = unit.history();
  const double t = 0.15, dt = 0.05;
  const proto::JobInput in = job(1, 2, Z2, Z1, t, dt);
  unit.iterate(job(1, 1, Z2, Z1, t, dt));
  unit.iterate(in);  // applies δw: ẇ ≠ 0 at this assembly
  EXPECT_TRUE(same_bits(unit.history_committed(), history_n));

  const HistoryLaw* law = nullptr;
  for (int e = 0; e < model->num_elements() && !law; ++e)
    law = dynamic_cast<const HistoryLaw*>(&model->material_of(e));
  ASSERT_NE(law, nullptr);
  double max_fluctuation_rate = 0.0;
  int points = 0;
  for (int e = 0; e < model->num_elements(); ++e) {
    if (model->material_of(e).history_size() == 0) continue;
    const auto& eq = model->element_equations(e);
    Eigen::Matrix<double, 3, 8> w_dot;
    for (int i = 0; i < 3; ++i)
      for (int a = 0; a < 8; ++a) {
        const int g = eq[hex_local(i, a)];
        w_dot(i, a) = g >= 0 ? (unit.w()[g] - w_n[g]) / dt : 0.0;
      }
    for (int q = 0; q < 8; ++q) {
      const Mat3 Bw_dot = w_dot * model->geometry(e).grad[q].transpose();
      const Vec9 Zdot = in.Zbar_dot + as_vec9(Bw_dot);
      max_fluctuation_rate = std::max(max_fluctuation_rate, Bw_dot.norm());
      const double* h = unit.history().data() + model->history_offset(e) + q * HistoryLaw::kSize;
      const double* hc =
          unit.history_committed().data() + model->history_offset(e) + q * HistoryLaw::kSize;
      ASSERT_EQ(h[HistoryLaw::kTime], t) << "element " << e << " point " << q;
      ASSERT_EQ(h[HistoryLaw::kDt], dt) << "element " << e << " point " << q;
      const Vec9 got = Eigen::Map<const Vec9>(h + HistoryLaw::kZdot);
      ASSERT_LT((got - Zdot).norm(), 1e-12 * Zdot.norm()) << "element " << e << " point " << q;
      MaterialPointContext c{t, dt, got};
      ASSERT_EQ(h[HistoryLaw::kAlpha], law->alpha_next(hc[HistoryLaw::kAlpha], c));
      // The committed α is step 0's: 0.1 · k (1 + 0.1) ‖Ż‖², with Ż the rate of step 0.
      ASSERT_GT(hc[HistoryLaw::kAlpha], 0.0) << "element " << e << " point " << q;
      ++points;
    }
  }
  EXPECT_EQ(points, static_cast<int>(cell_elements) * 8);
  // The fluctuation's rate is a real part of Ż here (not only Ż̄).
  EXPECT_GT(max_fluctuation_rate, 0.05 * in.Zbar_dot.norm());
}

// A cut-back: step 1 fails at a far-away Z̄ after a refresh, is rolled back and retried
// with half the step. Everything after, outputs and history, equals bit for bit a run
// that took the half step at once; the rollback returns the history to the committed one.
TEST(PointHistory, MicroRollbackAndRetryEqualsRunThatNeverFailed) {
  const auto model = history_model();
  MicroUnit failed(model), straight(model);
  for (MicroUnit* u : {&failed, &straight}) {
    for (int it = 1; it <= 3; ++it) u->iterate(job(0, it, Z1, Vec9::Zero(), 0.1, 0.1));
    u->commit_step();
  }
  const std::vector<double> committed = failed.history();
  failed.iterate(job(1, 1, Z_failed, Z1, 0.2, 0.1, /*force_refresh=*/true));
  failed.iterate(job(1, 2, Z_failed, Z1, 0.2, 0.1));
  ASSERT_FALSE(same_bits(failed.history(), committed));  // the failed step wrote history
  failed.rollback_step();
  EXPECT_TRUE(same_bits(failed.history(), committed));
  EXPECT_TRUE(same_bits(failed.history_committed(), committed));

  for (int step = 1; step <= 2; ++step) {
    const Vec9& Z = step == 1 ? Z2 : Z3;
    const Vec9& Z_n = step == 1 ? Z1 : Z2;
    const double t = step == 1 ? 0.15 : 0.2;
    for (int it = 1; it <= 4; ++it) {
      const auto a = failed.iterate(job(step, it, Z, Z_n, t, 0.05));
      const auto b = straight.iterate(job(step, it, Z, Z_n, t, 0.05));
      expect_same_bits(a, b, fmt::format("step {} iteration {}", step, it));
    }
    failed.commit_step();
    straight.commit_step();
    EXPECT_TRUE(same_bits(failed.history(), straight.history())) << "step " << step;
  }
}

// serialize/deserialize: the history (current and committed) round-trips bit for bit, and
// a unit migrated in the middle of a step continues exactly as the one that stayed,
// through the commit into the next step.
TEST(PointHistory, MicroMigrationMidStepContinuesBitForBit) {
  const auto model = history_model();
  MicroUnit stayed(model);
  for (int it = 1; it <= 3; ++it) stayed.iterate(job(0, it, Z1, Vec9::Zero(), 0.1, 0.1));
  stayed.commit_step();
  for (int it = 1; it <= 2; ++it) stayed.iterate(job(1, it, Z2, Z1, 0.15, 0.05));
  Bytes state;
  stayed.serialize(state);
  EXPECT_EQ(stayed.state_bytes(), state.size());
  MicroUnit moved(model);
  moved.deserialize(state);
  ASSERT_FALSE(stayed.history().empty());
  EXPECT_TRUE(same_bits(moved.history(), stayed.history()));
  EXPECT_TRUE(same_bits(moved.history_committed(), stayed.history_committed()));
  Bytes again;
  moved.serialize(again);
  EXPECT_EQ(again, state);

  for (int step = 1; step <= 2; ++step) {
    const Vec9& Z = step == 1 ? Z2 : Z3;
    const Vec9& Z_n = step == 1 ? Z1 : Z2;
    const double t = step == 1 ? 0.15 : 0.2;
    for (int it = step == 1 ? 3 : 1; it <= 5; ++it) {
      const auto a = stayed.iterate(job(step, it, Z, Z_n, t, 0.05));
      const auto b = moved.iterate(job(step, it, Z, Z_n, t, 0.05));
      expect_same_bits(a, b, fmt::format("step {} iteration {}", step, it));
    }
    stayed.commit_step();
    moved.commit_step();
    EXPECT_TRUE(same_bits(moved.history(), stayed.history())) << "step " << step;
  }
}

TEST(PointHistory, MicroStateOfAnOlderVersionIsRefusedNamingBothVersions) {
  const auto model = history_model();
  MicroUnit unit(model);
  Bytes state;
  unit.serialize(state);
  // The version follows the kind string (length prefix + "micro_unit").
  const size_t at = sizeof(uint64_t) + unit.kind().size();
  uint32_t version;
  std::memcpy(&version, state.data() + at, sizeof version);
  EXPECT_EQ(version, 4u);
  // Version 3 is version 4 without the factor record (its last byte): still read.
  Bytes v3(state.begin(), state.end() - 1);
  const uint32_t three = 3;
  std::memcpy(v3.data() + at, &three, sizeof three);
  MicroUnit from_v3(model);
  EXPECT_NO_THROW(from_v3.deserialize(v3));
  EXPECT_THROW(from_v3.deserialize(Bytes(state.begin(), state.end() - 1)), Error);  // 4 needs it
  const uint32_t old_version = 2;
  std::memcpy(state.data() + at, &old_version, sizeof old_version);
  MicroUnit other(model);
  try {
    other.deserialize(state);
    FAIL() << "an old state was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("version 2, expected 3 or 4"), std::string::npos) << e.what();
  }
}

// Laws without history allocate none and read no context; a law that reads the context
// but keeps no history (as a viscous law will) gives the same bits as the stateless path.
class ContextReadingNeoHookean final : public Material {
 public:
  ContextReadingNeoHookean(double E, double nu) : nh_(E, nu) {}
  std::string name() const override { return "test_context_neo_hookean"; }
  double energy(const Vec9& Z) const override { return nh_.energy(Z); }
  void stress_and_tangent(const Vec9& Z, Vec9& Pi, Mat9& A) const override {
    ADD_FAILURE() << "the stateless path was taken for a law that reads its context";
    nh_.stress_and_tangent(Z, Pi, A);
  }
  bool uses_context() const override { return true; }
  void stress_and_tangent_at(const Vec9& Z, const MaterialPointContext& c, PointHistory h,
                             Vec9& Pi, Mat9& A, Mat9& A_rate) const override {
    A_rate.setZero();
    EXPECT_TRUE(h.committed.empty() && h.current.empty());
    EXPECT_EQ(c.dt, 0.05);
    nh_.stress_and_tangent(Z, Pi, A);
  }
  double stiffness_scale() const override { return nh_.stiffness_scale(); }

 private:
  NeoHookean nh_;
};

TEST(PointHistory, StatelessLawsKeepNoHistoryAndGiveTheSameBits) {
  const auto plain = test::two_cell_model();
  CellLayout c;
  c.kind = "two_cells";
  c.size = Vec3(1.0, 0.4, 0.4);
  c.resolution = {6, 4, 4};
  c.gap = 0.1;
  c.cross_section = 0.5;
  const auto reading = test::make_unit_model(
      c, {std::make_shared<ContextReadingNeoHookean>(1.0e3, 0.3),
          std::make_shared<ContextReadingNeoHookean>(2.0e4, 0.4)});
  EXPECT_EQ(plain->history_size(), 0u);
  EXPECT_EQ(reading->history_size(), 0u);
  MicroUnit a(plain), b(reading);
  EXPECT_TRUE(a.history().empty());
  for (int it = 1; it <= 3; ++it)
    expect_same_bits(a.iterate(job(0, it, Z1, Vec9::Zero(), 0.05, 0.05)),
                     b.iterate(job(0, it, Z1, Vec9::Zero(), 0.05, 0.05)),
                     fmt::format("iteration {}", it));
}

// ---------------------------------------------------------------- macro-law points

TEST(PointHistory, MacroLawPointGetsTheJobContextAndCommitsItsHistory) {
  const auto law = std::make_shared<HistoryLaw>(1.0e4, 0.3, kRate);
  const NeoHookean nh(1.0e4, 0.3);
  MacroLawPoint point(law);
  ASSERT_EQ(point.history().size(), static_cast<size_t>(HistoryLaw::kSize));

  const proto::JobInput in1 = job(0, 1, Z1, Vec9::Zero(), 0.1, 0.1);  // Ż̄ = 10 Z1
  auto out = point.iterate(in1);
  const double alpha1 = 0.1 * kRate * 1.1 * (10.0 * Z1).squaredNorm();
  EXPECT_NEAR(point.history()[HistoryLaw::kAlpha], alpha1, 1e-15);
  EXPECT_EQ(point.history()[HistoryLaw::kTime], 0.1);
  EXPECT_EQ(point.history()[HistoryLaw::kDt], 0.1);
  for (int i = 0; i < 9; ++i) EXPECT_EQ(point.history()[HistoryLaw::kZdot + i], in1.Zbar_dot[i]);
  EXPECT_LT((out.P_bar - (1.0 + alpha1) * nh.stress(Z1)).norm(), 1e-13 * nh.stress(Z1).norm());
  EXPECT_EQ(point.history_committed()[HistoryLaw::kAlpha], 0.0);
  point.commit_step();
  EXPECT_EQ(point.history_committed()[HistoryLaw::kAlpha], point.history()[HistoryLaw::kAlpha]);

  const proto::JobInput in2 = job(1, 1, Z2, Z1, 0.15, 0.05);  // Ż̄ = 10 Z1 again
  point.iterate(in2);
  const double alpha2 = point.history_committed()[HistoryLaw::kAlpha] +
                        0.05 * kRate * 1.15 * (Z2 - Z1).squaredNorm() / (0.05 * 0.05);
  EXPECT_NEAR(point.history()[HistoryLaw::kAlpha], alpha2, 1e-14);
  EXPECT_GT(point.history_committed()[HistoryLaw::kAlpha], 0.0);
}

TEST(PointHistory, MacroLawPointRollbackRetryAndMigrationAreBitForBit) {
  const auto law = std::make_shared<HistoryLaw>(1.0e4, 0.3, kRate);
  MacroLawPoint failed(law), straight(law);
  for (MacroLawPoint* p : {&failed, &straight}) {
    p->iterate(job(0, 1, Z1, Vec9::Zero(), 0.1, 0.1));
    p->commit_step();
  }
  const std::vector<double> committed = failed.history();
  failed.iterate(job(1, 1, Z_failed, Z1, 0.2, 0.1));
  ASSERT_FALSE(same_bits(failed.history(), committed));
  failed.rollback_step();
  EXPECT_TRUE(same_bits(failed.history(), committed));

  // Migrate the rolled-back point mid-retry; all three continue identically.
  expect_same_bits(failed.iterate(job(1, 1, Z2, Z1, 0.15, 0.05)),
                   straight.iterate(job(1, 1, Z2, Z1, 0.15, 0.05)), "retry");
  Bytes state;
  failed.serialize(state);
  EXPECT_EQ(failed.state_bytes(), state.size());
  MacroLawPoint moved(law);
  moved.deserialize(state);
  EXPECT_TRUE(same_bits(moved.history(), failed.history()));
  EXPECT_TRUE(same_bits(moved.history_committed(), failed.history_committed()));
  for (MacroLawPoint* p : {&failed, &straight, &moved}) p->commit_step();
  const auto a = failed.iterate(job(2, 1, Z3, Z2, 0.2, 0.05));
  const auto b = straight.iterate(job(2, 1, Z3, Z2, 0.2, 0.05));
  const auto c = moved.iterate(job(2, 1, Z3, Z2, 0.2, 0.05));
  expect_same_bits(a, b, "step 2, rolled back");
  expect_same_bits(c, b, "step 2, migrated");
  EXPECT_TRUE(same_bits(moved.history(), straight.history()));
}

TEST(PointHistory, MacroLawStateOfVersion1IsRefusedNamingBothVersions) {
  // Version 1: kind, then Z̄ alone.
  Bytes old;
  ByteWriter w(old);
  w.put_string("macro_law");
  const Vec9 Z = Z1;
  w.put_array(Z.data(), 9);
  MacroLawPoint point(std::make_shared<NeoHookean>(1.0e4, 0.3));
  try {
    point.deserialize(old);
    FAIL() << "a version-1 state was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("version 1, expected 2"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace fe2
