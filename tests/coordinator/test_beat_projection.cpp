// farm-sim --beat: a replayed window of a beat extrapolated over the beat's segments
// (coordinator/farm/beat_projection.h), on costs whose answer is known by hand.
#include "common/error.h"
#include "coordinator/farm/beat_projection.h"

#include <gtest/gtest.h>

namespace fe2 {
namespace {

/// Steps 0-1 inflation, 2-5 filling (1 s a step), 6-7 isovolumic contraction (3 s), 8-9
/// ejection (5 s), 10-11 both valves shut again (labelled isovolumic contraction, 0.5 s): the
/// small units' own costs.
std::vector<StepCost> small_beat() {
  std::vector<StepCost> b;
  const auto add = [&](int n, const char* phase, double s) {
    for (int i = 0; i < n; ++i) b.push_back({static_cast<int>(b.size()), phase, s});
  };
  add(2, "inflation", 100.0);
  add(4, "filling", 1.0);
  add(2, "isovolumic contraction", 3.0);
  add(2, "ejection", 5.0);
  add(2, "isovolumic contraction", 0.5);
  return b;
}

TEST(BeatProjection, ReplayedSegmentsKeepTheirTimeAndTheOthersScaleByTheReplayedRatio) {
  // The replay ran step 5 (its restart step: one step is no sample of filling), the
  // contraction (30 and 34 s) and the ejection (66 and 74 s).
  const std::vector<StepCost> replay = {{5, "filling", 1e6},
                                        {6, "isovolumic contraction", 30.0},
                                        {7, "isovolumic contraction", 34.0},
                                        {8, "ejection", 66.0},
                                        {9, "ejection", 74.0}};
  const BeatProjection p = project_beat(small_beat(), 1, replay);
  ASSERT_EQ(p.segments.size(), 4u);
  EXPECT_EQ(p.segments[0].phase, "filling");
  EXPECT_EQ(p.segments[0].replay_steps, 1);
  EXPECT_FALSE(p.segments[0].replayed());
  EXPECT_DOUBLE_EQ(p.segments[0].beat_cost, 1.0);
  // The late shut-valve steps are a segment apart from the systolic contraction.
  EXPECT_EQ(p.segments[3].phase, "isovolumic contraction");
  EXPECT_EQ(p.segments[3].first_step, 10);
  EXPECT_EQ(p.segments[3].replay_steps, 0);
  // rho = (30 + 34 + 66 + 74) / (2 x 3 + 2 x 5) = 204 / 16
  const double rho = 204.0 / 16.0;
  EXPECT_DOUBLE_EQ(p.ratio, rho);
  EXPECT_DOUBLE_EQ(p.segments[0].seconds_per_step, rho);
  EXPECT_DOUBLE_EQ(p.segments[1].seconds_per_step, 32.0);
  EXPECT_DOUBLE_EQ(p.segments[2].seconds_per_step, 70.0);
  EXPECT_DOUBLE_EQ(p.segments[3].seconds_per_step, 0.5 * rho);
  EXPECT_DOUBLE_EQ(p.segments[1].steps_per_beat, 2.0);
  // T = 4 rho + 2 x 32 + 2 x 70 + 2 x 0.5 rho; the inflation (100 s a step) is not part of a beat.
  EXPECT_DOUBLE_EQ(p.seconds, 4.0 * rho + 64.0 + 140.0 + rho);
}

TEST(BeatProjection, TheRatioComparesTheSameSteps) {
  // The replay ran only the first of the ejection's steps twice over (8 and a step the beat
  // lacks): rho takes the beat's cost of the steps the replay ran, not the segment's mean.
  std::vector<StepCost> beat = small_beat();
  beat[8].seconds = 4.0;  // ejection: 4 and 5 s
  const BeatProjection p = project_beat(beat, 1, {{2, "filling", 10.0}, {3, "filling", 14.0}, {99, "ejection", 1e6}});
  EXPECT_DOUBLE_EQ(p.ratio, 12.0);  // (10 + 14) / (1 + 1)
  EXPECT_DOUBLE_EQ(p.segments[2].seconds_per_step, 12.0 * 4.5);
}

TEST(BeatProjection, StepsPerBeatDivideByTheBeatsRun) {
  std::vector<StepCost> two = small_beat();
  const std::vector<StepCost> more = small_beat();
  for (auto it = more.begin() + 2; it != more.end(); ++it) two.push_back({it->step + 10, it->phase, it->seconds});
  // Beat 2's filling (steps 12-15) follows beat 1's shut valves (10-11): its own segment.
  const BeatProjection p = project_beat(two, 2, {{0, "inflation", 1e6}, {2, "filling", 1.5}, {3, "filling", 2.5}});
  EXPECT_DOUBLE_EQ(p.ratio, 2.0);
  ASSERT_EQ(p.segments.size(), 8u);  // filling, contraction, ejection, valves shut; twice
  EXPECT_DOUBLE_EQ(p.segments[0].steps_per_beat, 2.0);
  EXPECT_DOUBLE_EQ(p.segments[0].seconds_per_step, 2.0);
  // Both beats' steps at rho = 2, halved: (4 x 1 + 2 x 3 + 2 x 5 + 2 x 0.5) x 2 beats x 2 / 2.
  EXPECT_DOUBLE_EQ(p.seconds, 2.0 * (4.0 + 6.0 + 10.0 + 1.0));
}

TEST(BeatProjection, AReplayCoveringNoSegmentIsAnInputError) {
  EXPECT_THROW(project_beat(small_beat(), 1, {{0, "inflation", 3.0}, {1, "inflation", 3.0}}), InputError);
  EXPECT_THROW(project_beat(small_beat(), 1, {{2, "filling", 3.0}}), InputError);  // one step: no sample
  EXPECT_THROW(project_beat(small_beat(), 0, {{2, "filling", 3.0}, {3, "filling", 3.0}}), InputError);
}

TEST(BeatProjection, StepCostsSumEachStepsIterationsUnderItsPhase) {
  const std::vector<StepCost> s =
      step_costs({8, 8, 8, 9, 9}, {1.0, 2.0, 4.0, 8.0, 16.0}, {{8, "filling"}, {9, "ejection"}}, "RUN");
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s[0].step, 8);
  EXPECT_EQ(s[0].phase, "filling");
  EXPECT_DOUBLE_EQ(s[0].seconds, 7.0);
  EXPECT_EQ(s[1].phase, "ejection");
  EXPECT_DOUBLE_EQ(s[1].seconds, 24.0);
  try {
    step_costs({8, 10}, {1.0, 1.0}, {{8, "filling"}}, "RUN");
    FAIL() << "a step without a phase was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("RUN: step 10"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace fe2
