// Timing noise in a replayed run (timing_noise.h): costs built as m(i) · a(v) · ε(v, i)
// with known factors; the decomposition finds them, and the replay without noise keeps
// the work (kinds, persistent unit factors) and drops ε.
#include "coordinator/farm/timing_noise.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace fe2 {
namespace {

constexpr int kUnits = 64;
constexpr int kIterations = 40;

double persistent_factor(int v) { return 1.0 + 0.1 * ((v % 5) - 2) / 2.0; }  // 0.9 … 1.1

/// The sample std of log a(v) over the modelled units (1 … kUnits − 1).
double std_persistent_expected() {
  double mean = 0.0, s = 0.0;
  for (int v = 1; v < kUnits; ++v) mean += std::log(persistent_factor(v)) / (kUnits - 1);
  for (int v = 1; v < kUnits; ++v) s += std::pow(std::log(persistent_factor(v)) - mean, 2);
  return std::sqrt(s / (kUnits - 2));
}

/// Unit v costs m(i) · a(v) · ε(v, i); every fourth unit's job is a refresh of 5× the
/// cost, and unit 0's job is alone of its GMRES count (a kind of one).
FarmSimInput trace(double noise, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> gauss(0.0, 1.0);
  FarmSimInput in;
  for (int i = 0; i < kIterations; ++i) {
    const double m = 0.1 * (1.0 + 0.3 * std::sin(i));
    std::vector<double> cost(kUnits), part(kUnits, 0.0);
    std::vector<char> refreshed(kUnits, 0);
    std::vector<int> gmres(kUnits, 3);
    for (int v = 0; v < kUnits; ++v) {
      const double a = persistent_factor(v);
      refreshed[v] = v % 4 == 1;
      cost[v] = m * (refreshed[v] ? 5.0 : 1.0) * a * std::exp(noise * gauss(rng));
      if (refreshed[v]) part[v] = 0.8 * cost[v];
    }
    gmres[0] = 500;
    in.cost.push_back(cost);
    in.refreshed.push_back(refreshed);
    in.refresh_part.push_back(part);
    in.gmres.push_back(gmres);
    in.macro.push_back(0.0);
  }
  in.state_bytes.assign(kUnits, 1000.0);
  return in;
}

TEST(TimingNoise, WithoutNoiseTheReplayIsUnchanged) {
  FarmSimInput in = trace(0.0, 1);
  const FarmSimInput before = in;
  const CostSpread s = cost_spread(in);
  EXPECT_LT(s.noise, 1e-12);
  EXPECT_NEAR(s.persistent, std_persistent_expected(), 0.01);
  remove_timing_noise(in);
  for (int i = 0; i < kIterations; ++i)
    for (int v = 0; v < kUnits; ++v) {
      EXPECT_NEAR(in.cost[i][v], before.cost[i][v], 1e-12 * before.cost[i][v]) << i << " " << v;
      EXPECT_NEAR(in.refresh_part[i][v], before.refresh_part[i][v], 1e-12) << i << " " << v;
    }
}

TEST(TimingNoise, FindsTheNoiseAndReplaysWithoutIt) {
  FarmSimInput in = trace(0.2, 7);
  const FarmSimInput clean = trace(0.0, 7);
  const CostSpread s = cost_spread(in);
  // 2520 modelled jobs: σ = 0.2 to a few percent. a(v), a mean of 40 jobs, scatters by
  // 0.2 / √40 = 0.032 on top of the true 0.070 (0.077 unshrunk); shrunk by true² /
  // observed², its spread is true² / observed = 0.064.
  const double truth = std_persistent_expected();
  EXPECT_NEAR(s.noise, 0.2, 0.02);
  EXPECT_NEAR(s.persistent, truth * truth / std::hypot(truth, 0.2 / std::sqrt(40.0)), 0.006);
  EXPECT_LT(std::abs(s.lag1), 0.1);
  EXPECT_EQ(s.jobs, static_cast<long long>(kIterations) * (kUnits - 1));
  EXPECT_EQ(s.all_jobs, static_cast<long long>(kIterations) * kUnits);
  const FarmSimInput noisy = in;
  remove_timing_noise(in);
  double before = 0.0, after = 0.0;
  for (int i = 0; i < kIterations; ++i)
    for (int v = 1; v < kUnits; ++v) {
      before = std::max(before, std::abs(std::log(noisy.cost[i][v] / clean.cost[i][v])));
      after = std::max(after, std::abs(std::log(in.cost[i][v] / clean.cost[i][v])));
    }
  // The worst of 2520 jobs with σ = 0.2 is about 3.5 σ off. What is left after is the
  // error of the kinds' medians (16 refresh jobs: 1.25 σ / √16 = 0.06) and of a(v),
  // the worst of them about 3 times that.
  EXPECT_GT(before, 0.5);
  EXPECT_LT(after, 0.25);
  // The kind of one keeps its measured cost.
  for (int i = 0; i < kIterations; ++i) EXPECT_EQ(in.cost[i][0], noisy.cost[i][0]);
}

TEST(TimingNoise, PersistentCostsRepeatAndStayInTheReplay) {
  // No noise but a unit that is always 1.5× its kind: persistent, kept by the replay.
  FarmSimInput in = trace(0.0, 3);
  for (auto& c : in.cost) c[6] *= 1.5;
  const FarmSimInput before = in;
  remove_timing_noise(in);
  for (int i = 0; i < kIterations; ++i) EXPECT_NEAR(in.cost[i][6], before.cost[i][6], 1e-12);
}

}  // namespace
}  // namespace fe2
