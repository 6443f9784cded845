// The material-point context seam of Material (MaterialPointContext.h): stateless laws
// keep no history, read no context, and their context verb is bit for bit their
// stateless pair; a law with history (the test law of tests/support) integrates from
// the committed history with the context's t, Δt and Ż.
#include "common/materials/Guccione.h"
#include "common/materials/NeoHookean.h"
#include "common/materials/StVenantKirchhoff.h"
#include "tests/support/history_law.h"

#include <gtest/gtest.h>

#include <cstring>
#include <vector>

namespace fe2 {
namespace {

Vec9 some_Z() {
  Vec9 Z;
  Z << 0.04, -0.01, 0.02, 0.015, -0.03, 0.005, -0.02, 0.01, 0.025;
  return Z;
}

MaterialPointContext some_context() {
  MaterialPointContext c;
  c.time = 0.7;
  c.dt = 0.05;
  c.Zdot << 0.3, -0.2, 0.1, 0.05, 0.4, -0.1, 0.2, 0.0, -0.3;
  return c;
}

TEST(MaterialPointContext, StatelessLawsIgnoreTheContextBitForBit) {
  const std::vector<MaterialPtr> laws = {std::make_shared<NeoHookean>(1.0e4, 0.3),
                                         std::make_shared<StVenantKirchhoff>(1.0e4, 0.3),
                                         std::make_shared<Guccione>(GuccioneParameters{})};
  const Vec9 Z = some_Z();
  for (const auto& law : laws) {
    EXPECT_EQ(law->history_size(), 0) << law->name();
    EXPECT_FALSE(law->uses_context()) << law->name();
    Vec9 Pi, Pi_at;
    Mat9 A, A_at, A_rate = Mat9::Constant(1.0);
    law->stress_and_tangent(Z, Pi, A);
    law->stress_and_tangent_at(Z, some_context(), {}, Pi_at, A_at, A_rate);
    EXPECT_FALSE(law->rate_dependent()) << law->name();
    EXPECT_EQ(A_rate.norm(), 0.0) << law->name();
    EXPECT_EQ(std::memcmp(Pi.data(), Pi_at.data(), sizeof(double) * 9), 0) << law->name();
    EXPECT_EQ(std::memcmp(A.data(), A_at.data(), sizeof(double) * 81), 0) << law->name();
  }
}

// α_{n+1} = α_n + Δt k (1 + t) Ż:Ż and Π = (1 + α_{n+1}) Π^NH, computed here by hand.
TEST(MaterialPointContext, HistoryLawIntegratesFromTheCommittedHistory) {
  const double k = 2.0;
  const test::HistoryLaw law(1.0e4, 0.3, k);
  const NeoHookean nh(1.0e4, 0.3);
  ASSERT_EQ(law.history_size(), test::HistoryLaw::kSize);
  EXPECT_TRUE(law.uses_context());
  const MaterialPointContext c = some_context();
  std::vector<double> committed(test::HistoryLaw::kSize, 0.0), current(test::HistoryLaw::kSize, -1.0);
  committed[test::HistoryLaw::kAlpha] = 0.25;
  const Vec9 Z = some_Z();
  Vec9 Pi, Pi_nh;
  Mat9 A, A_nh, A_rate;
  law.stress_and_tangent_at(Z, c, {committed, current}, Pi, A, A_rate);
  nh.stress_and_tangent(Z, Pi_nh, A_nh);

  // Ż:Ż = 0.09+0.04+0.01+0.0025+0.16+0.01+0.04+0+0.09 = 0.4425
  const double alpha = 0.25 + 0.05 * k * (1.0 + 0.7) * 0.4425;
  EXPECT_NEAR(current[test::HistoryLaw::kAlpha], alpha, 1e-15);
  EXPECT_EQ(current[test::HistoryLaw::kTime], 0.7);
  EXPECT_EQ(current[test::HistoryLaw::kDt], 0.05);
  for (int i = 0; i < 9; ++i) EXPECT_EQ(current[test::HistoryLaw::kZdot + i], c.Zdot[i]);
  EXPECT_EQ(committed[test::HistoryLaw::kAlpha], 0.25);  // read, never written
  EXPECT_LT((Pi - (1.0 + alpha) * Pi_nh).norm(), 1e-13 * Pi_nh.norm());
  EXPECT_LT((A - (1.0 + alpha) * A_nh).norm(), 1e-13 * A_nh.norm());

  // Evaluating again from the same committed history gives the same current history:
  // a Newton iteration may be repeated.
  const std::vector<double> first = current;
  law.stress_and_tangent_at(Z, c, {committed, current}, Pi, A, A_rate);
  EXPECT_EQ(current, first);
}

}  // namespace
}  // namespace fe2
