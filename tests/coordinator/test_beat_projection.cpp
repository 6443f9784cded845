// farm-sim --beat: a replayed window of a beat extrapolated over the beat's phases
// (coordinator/farm/beat_projection.h), on costs whose answer is known by hand.
#include "common/error.h"
#include "coordinator/farm/beat_projection.h"

#include <gtest/gtest.h>

namespace fe2 {
namespace {

/// A beat of 2 inflation, 4 filling, 2 contraction and 2 ejection steps; filling costs 1 s a
/// step, contraction 3, ejection 5 (the small units' own cost).
std::vector<StepCost> small_beat() {
  std::vector<StepCost> b;
  for (int i = 0; i < 2; ++i) b.push_back({"inflation", 100.0});
  for (int i = 0; i < 4; ++i) b.push_back({"filling", 1.0});
  for (int i = 0; i < 2; ++i) b.push_back({"isovolumic contraction", 3.0});
  for (int i = 0; i < 2; ++i) b.push_back({"ejection", 5.0});
  return b;
}

TEST(BeatProjection, ReplayedPhasesKeepTheirTimeAndTheOthersScaleByTheReplayedRatio) {
  // The replay ran one filling step (its restart step: no sample of the phase), contraction
  // (2 steps: 30 and 34 s) and ejection (2 steps: 66 and 74 s).
  const std::vector<StepCost> replay = {{"filling", 1e6},
                                        {"isovolumic contraction", 30.0},
                                        {"isovolumic contraction", 34.0},
                                        {"ejection", 66.0},
                                        {"ejection", 74.0}};
  const BeatProjection p = project_beat(small_beat(), 1, replay);
  ASSERT_EQ(p.phases.size(), 3u);
  EXPECT_EQ(p.phases[0].phase, "filling");
  EXPECT_EQ(p.phases[0].replay_steps, 1);
  EXPECT_DOUBLE_EQ(p.phases[0].beat_cost, 1.0);
  // rho = (30 + 34 + 66 + 74) / (2 x 3 + 2 x 5) = 204 / 16
  EXPECT_DOUBLE_EQ(p.ratio, 204.0 / 16.0);
  EXPECT_DOUBLE_EQ(p.phases[0].seconds_per_step, 204.0 / 16.0);
  EXPECT_DOUBLE_EQ(p.phases[1].seconds_per_step, 32.0);
  EXPECT_DOUBLE_EQ(p.phases[2].seconds_per_step, 70.0);
  EXPECT_DOUBLE_EQ(p.phases[1].steps_per_beat, 2.0);
  // T = 4 x rho + 2 x 32 + 2 x 70; the inflation (100 s a step) is not part of a beat.
  EXPECT_DOUBLE_EQ(p.seconds, 4.0 * 204.0 / 16.0 + 64.0 + 140.0);
}

TEST(BeatProjection, StepsPerBeatDivideByTheBeatsRunAndUnknownPhasesAreIgnored) {
  std::vector<StepCost> two = small_beat();
  const std::vector<StepCost> more = small_beat();
  two.insert(two.end(), more.begin() + 2, more.end());  // a second beat, no second inflation
  const std::vector<StepCost> replay = {
      {"inflation", 1e6}, {"filling", 1.5}, {"filling", 2.5}, {"isovolumic relaxation", 1e6}};
  const BeatProjection p = project_beat(two, 2, replay);
  EXPECT_DOUBLE_EQ(p.ratio, 2.0);
  EXPECT_DOUBLE_EQ(p.phases[0].steps_per_beat, 4.0);
  EXPECT_DOUBLE_EQ(p.seconds, 4.0 * 2.0 + 2.0 * 6.0 + 2.0 * 10.0);
}

TEST(BeatProjection, AReplaySharingNoPhaseWithTheBeatIsAnInputError) {
  EXPECT_THROW(project_beat(small_beat(), 1, {{"inflation", 3.0}, {"inflation", 3.0}}), InputError);
  EXPECT_THROW(project_beat(small_beat(), 1, {{"filling", 3.0}}), InputError);  // one step: no sample
  EXPECT_THROW(project_beat(small_beat(), 0, {{"filling", 3.0}, {"filling", 3.0}}), InputError);
}

TEST(BeatProjection, StepCostsSumEachStepsIterationsUnderItsPhase) {
  const std::vector<StepCost> s =
      step_costs({8, 8, 8, 9, 9}, {1.0, 2.0, 4.0, 8.0, 16.0}, {{8, "filling"}, {9, "ejection"}}, "RUN");
  ASSERT_EQ(s.size(), 2u);
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
