// The beat a coupled run reports (common/circulation/beat_report.h): the window of the
// last period, the whole beats run, and systole at the left ventricle's pressure peak,
// on a synthetic run of two cavities whose right ventricle peaks higher elsewhere.
#include "common/circulation/beat_report.h"
#include "common/circulation/circulation_factory.h"
#include "common/circulation/circulation_schema.h"

#include <gtest/gtest.h>

namespace fe2 {
namespace {

CirculationPtr two_windkessels(double period) {
  const json j = {{"kind", "windkessel"}, {"period", period}, {"cavities", {{"lv", json::object()}, {"rv", json::object()}}}};
  SpecNode node(j, "/circulation", *circulation_schema());
  return make_circulation(node);
}

/// Samples 0..steps at t = k dt: LV pressure 1000 + k but 9000 at `lv_peak` and 20000 at
/// `early_peak` (before the window), RV pressure 500 but 30000 at `rv_peak`; LV volume
/// 100 + 10 (k mod 8), RV volume 50.
std::vector<CirculationSample> synthetic_run(int steps, double dt, int lv_peak, int early_peak, int rv_peak) {
  std::vector<CirculationSample> run(steps + 1);
  for (int k = 0; k <= steps; ++k) {
    CirculationSample& s = run[k];
    s.t = k * dt;
    s.p = {k == lv_peak ? 9000.0 : k == early_peak ? 20000.0 : 1000.0 + k, k == rv_peak ? 30000.0 : 500.0};
    s.V = {100.0 + 10.0 * (k % 8), 50.0};
  }
  return run;
}

TEST(BeatReport, WindowIsTheLastPeriodAndSystoleTheLeftVentriclePeak) {
  const CirculationPtr c = two_windkessels(1.0);
  ASSERT_EQ(c->cavity_names()[c->left_ventricle()], "lv");
  // 24 steps of 1/8 s: three beats of 8 steps; the last period is samples 16..24.
  const auto run = synthetic_run(24, 0.125, 19, 11, 22);
  const BeatWindow w = beat_window(run, c->period());
  EXPECT_EQ(w.first, 16u);
  EXPECT_EQ(w.last, 24u);
  EXPECT_EQ(w.per_beat, 8);
  EXPECT_EQ(w.beats, 3);
  EXPECT_TRUE(w.whole_period);
  EXPECT_EQ(systole_sample(run, w, 1), 22u);  // the RV's own peak

  const json r = beat_report(*c, run);
  EXPECT_EQ(r["systole_step"], 19);
  EXPECT_DOUBLE_EQ(r["systole_time"].get<double>(), 19 * 0.125);
  EXPECT_EQ(r["systole_cavity"], "lv");
  EXPECT_EQ(r["beats_run"], 3);
  EXPECT_EQ(r["figures_over"], "the last period");
  EXPECT_DOUBLE_EQ(r["period"].get<double>(), 1.0);
  const json& lv = r["cavities"]["lv"];
  EXPECT_DOUBLE_EQ(lv["peak_pressure"].get<double>(), 9000.0);  // not the 20000 before the window
  EXPECT_DOUBLE_EQ(lv["EDV"].get<double>(), 170.0);
  EXPECT_DOUBLE_EQ(lv["ESV"].get<double>(), 100.0);
  EXPECT_DOUBLE_EQ(lv["EF"].get<double>(), 70.0 / 170.0);
  EXPECT_EQ(lv["EDV_per_beat"].size(), 3u);
  EXPECT_DOUBLE_EQ(r["cavities"]["rv"]["peak_pressure"].get<double>(), 30000.0);
}

TEST(BeatReport, ARunShorterThanAPeriodIsReportedWhole) {
  const CirculationPtr c = two_windkessels(1.0);
  // 5 steps of 1/8 s: the window is every step (sample 0, the unloaded state, left out).
  const auto run = synthetic_run(5, 0.125, 1, -1, 3);
  const BeatWindow w = beat_window(run, c->period());
  EXPECT_EQ(w.first, 1u);
  EXPECT_EQ(w.last, 5u);
  EXPECT_EQ(w.beats, 0);
  EXPECT_FALSE(w.whole_period);
  const json r = beat_report(*c, run);
  EXPECT_EQ(r["figures_over"], "the whole run (shorter than a period)");
  EXPECT_EQ(r["systole_step"], 1);
  EXPECT_DOUBLE_EQ(r["cavities"]["lv"]["peak_pressure"].get<double>(), 9000.0);
}

TEST(BeatReport, TooShortARunIsRefused) {
  const CirculationPtr c = two_windkessels(1.0);
  const auto run = synthetic_run(1, 0.125, -1, -1, -1);
  try {
    beat_window(run, c->period());
    FAIL() << "two samples accepted";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("2 samples, expected the initial state and two steps"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace fe2
