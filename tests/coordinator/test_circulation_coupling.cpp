// An LV whose cavity pressure is an unknown of the macro system, coupled
// strongly to a 3-element Windkessel through smooth-diode valves (CavityPressureTerm).
// Over a beat the valves are never both open, the phases come in the order of a heart
// (filling, isovolumic contraction, ejection, isovolumic relaxation), the cavity volume
// does not move while both valves are shut, and ejection pushes blood into the arteries.
#include "common/circulation/beat_summary.h"
#include "coordinator/macro/CavityPressureTerm.h"
#include "tests/coordinator/scene_fixtures.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

namespace fs = std::filesystem;

namespace fe2 {
namespace {

/// The Land et al. 2015 LV (mm; cavity ≈ 2.7 mL, so the Windkessel is scaled to that
/// size), Holzapfel–Ogden with Land 2017 cross-bridges, Taylor–Hood P2/P1, excited from
/// the endocardium. Valves shut with R_closed = 1e12 Pa·s/mm³: a leak of
/// ~1e-8 mm³/s at 10 kPa, far below what the test resolves.
json lv_beat(int steps, double t_end) {
  return {{"mesh", {{"kind", "lv"}, {"divisions", {8, 4, 1}}, {"order", 2}}},
          {"frame", {{"kind", "rule"}}},
          {"formulation", {{"kind", "mixed"}}},
          {"activation", {{"kind", "eikonal"}, {"sources", {{{"surface", "endo"}, {"time", 0.1}}}}, {"velocity", 500.0}}},
          {"models", {{"myocardium", {{"kind", "macro_law"}, {"material", {
              {"model", "holzapfel_ogden"}, {"volumetric", "none"}, {"viscosity", 100.0},
              {"active", {{"model", "land2017"}, {"max_substep", 1e-3}, {"T_ref", 60000.0}}}}}}}}},
          {"dirichlet", {{{"set", "base"}}}},
          {"cavities", {{"lv", {{"surface", "endo"}}}}},
          {"circulation", {{"kind", "windkessel"}, {"period", 0.8}, {"cavities", {{"lv", {
              {"preload", {{"kind", "pressure"}, {"pressure", 1000.0}}},
              {"inflow_valve", {{"R_open", 0.05}, {"R_closed", 1e12}, {"width", 0.5}}},
              {"outflow_valve", {{"R_open", 0.05}, {"R_closed", 1e12}, {"width", 0.5}}},
              {"windkessel", {{"Zc", 0.3}, {"Rp", 5.0}, {"C", 0.25}, {"p_distal", 600.0}, {"p0", 9000.0}}}}}}}}},
          {"time", {{"t_end", t_end}, {"steps", steps}}},
          {"newton", {{"rtol", 1e-10}, {"max_iterations", 25}}},
          {"output", {{"vtu", false}}}};
}

TEST(CirculationCoupling, LvBeatHasTheFourPhasesAndHoldsItsVolumeWhileTheValvesAreShut) {
  const RunSpec spec = read_run_spec(lv_beat(60, 0.6), "");
  LocalEvaluator points(spec.models, spec.model_of_points());
  Simulation sim(spec, points);
  const RunResult r = sim.run();
  ASSERT_TRUE(r.converged) << r.error;
  const double V_ref = sim.cavity_term()->reference_volumes()[0];
  std::vector<std::string> phases;  // distinct, in order of appearance
  double worst_isovolumic = 0.0, V_min = 1e300, V_max = 0.0, p_max = 0.0;
  int quadratic_checks = 0;
  for (size_t s = 0; s < r.history.size(); ++s) {
    const StepRecord& h = r.history[s];
    ASSERT_EQ(h.circulation.n, 1);
    EXPECT_FALSE(h.circulation.inflow_open[0] && h.circulation.outflow_open[0]) << "step " << s;
    const std::string& phase = h.circulation.phase[0];
    if (phases.empty() || phases.back() != phase) {
      phases.push_back(phase);
      // The step the aortic valve opens in: the strongly coupled Newton (wall, cavity
      // pressure and smooth valves in one tangent) still squares its residuals.
      // One Newton error: the pair (wall, cavity) squares together, its parts need not
      // each (R_c follows the wall's error: 1.1e-5 → 3.5e-9 there, C ≈ 30).
      if (phase == "ejection") {
        std::vector<double> res;
        for (size_t k = 0; k < h.residual("displacement").size(); ++k) res.push_back(std::max(h.residual("displacement")[k], h.residual("cavity_pressure")[k]));
        for (double x : res) std::printf("%.2e ", x);
        std::printf("(step %zu, the aortic valve opens)\n", s);
        quadratic_checks += test::expect_quadratic_iterations(res, "valve opening, step " + std::to_string(s));
      }
    }
    const double V = h.cavity_volumes[0], V_prev = s ? r.history[s - 1].cavity_volumes[0] : V_ref;
    if (phase.rfind("isovolumic", 0) == 0) worst_isovolumic = std::max(worst_isovolumic, std::abs(V - V_prev) / V_ref);
    V_min = std::min(V_min, V), V_max = std::max(V_max, V), p_max = std::max(p_max, h.cavity_pressures[0]);
    // The constraint converged with the rest: |R_c| / V_ref at the last iteration.
    EXPECT_LE(h.residual("cavity_pressure").back(), 1e-10) << "step " << s;
  }
  std::printf("LV beat: phases");
  for (const auto& p : phases) std::printf(" → %s", p.c_str());
  std::printf("\n  EDV %.0f, ESV %.0f mm³ (EF %.0f %%), peak p %.1f kPa, worst isovolumic |ΔV|/V %.1e\n", V_max,
              V_min, 100 * (V_max - V_min) / V_max, 1e-3 * p_max, worst_isovolumic);
  const std::vector<std::string> expected = {"filling", "isovolumic contraction", "ejection",
                                             "isovolumic relaxation", "filling"};
  ASSERT_GE(phases.size(), 4u);
  for (size_t k = 0; k < std::min(phases.size(), expected.size()); ++k) EXPECT_EQ(phases[k], expected[k]);
  EXPECT_LT(worst_isovolumic, 1e-8);
  EXPECT_GE(quadratic_checks, 2);  // two iterations in the asymptotic range
  EXPECT_GT((V_max - V_min) / V_max, 0.1);  // it ejects
  EXPECT_GT(p_max, 9000.0);                 // above the arterial pressure it opened against
}

// Beat after beat (time.beats, calcium repeating with the period) the loop settles: the
// run stops once the EDV changes by less than time.periodic_tolerance over a beat, and
// the last beat's loop then closes (the volume it ends with is the one it started with).
TEST(CirculationCoupling, BeatsUntilTheLoopIsPeriodic) {
  json j = lv_beat(1, 1.0);
  j["time"] = {{"beats", 5}, {"steps_per_beat", 40}, {"periodic_tolerance", 2e-4}};
  j["models"]["myocardium"]["material"]["active"]["calcium"] = {{"period", 0.8}};
  const RunSpec spec = read_run_spec(j, "");
  EXPECT_EQ(spec.steps, 200);
  EXPECT_DOUBLE_EQ(spec.t_end, 4.0);
  LocalEvaluator points(spec.models, spec.model_of_points());
  Simulation sim(spec, points);
  const RunResult r = sim.run();
  ASSERT_TRUE(r.converged) << r.error;
  const int beats = static_cast<int>(r.history.size()) / 40;
  std::printf("periodic after %d beats: EDV change %.2e\n", beats, r.edv_change);
  EXPECT_TRUE(r.periodic);
  EXPECT_LT(r.edv_change, 2e-4);
  EXPECT_LT(beats, 5);  // stopped before the last beat
  EXPECT_EQ(r.history.size() % 40, 0u);
  // The last beat's loop closes to within its EDV change.
  const double V_end = r.history.back().cavity_volumes[0], V_start = r.history[r.history.size() - 41].cavity_volumes[0];
  EXPECT_LT(std::abs(V_end - V_start) / V_end, 1e-3);
}

/// A macro term that makes the Newton iteration fail once at each of the given times
/// (as an inverted element would), so the step is cut back and retried.
class FailOnceAt final : public MacroTerm {
 public:
  explicit FailOnceAt(std::vector<double> times) : times_(std::move(times)) {}
  std::string name() const override { return "fail once (test)"; }
  void declare(MacroSystem&) override {}
  void assemble(const MacroState& s, MacroAssembly&) override {
    for (double& t : times_)
      if (std::abs(s.time - t) < 1e-9) {
        t = -1.0;
        throw NumericalError(fmt::format("injected failure at t = {}", s.time));
      }
  }

 private:
  std::vector<double> times_;
};

// The closed loop of Regazzoni et al. 2022 around the wall's LV (elastance RV, atria,
// systemic and pulmonary RLC compartments; resistances, elastances and inertances ×40,
// compliances and volumes ÷40 for this 2.6 mL LV): the blood in the compartments plus
// the wall's cavity stays constant to the Newton tolerance step after step, also
// through steps cut back and retried (the circulation's state rolls back with the step).
TEST(CirculationCoupling, ClosedLoopAroundTheWallConservesBloodThroughCutSteps) {
  json j = lv_beat(40, 0.8);
  j["circulation"] = json::parse(R"JSON({"kind": "closed_loop", "period": 0.8, "cavities": {"lv": {"inflow_valve": {"R_open": 0.05, "R_closed": 1000000000000.0, "width": 0.5}, "outflow_valve": {"R_open": 0.05, "R_closed": 1000000000000.0, "width": 0.5}}}, "systemic": {"R_ar": 4.26632, "C_ar": 0.2250175, "L_ar": 0.026664399999999998, "R_ven": 1.38656, "C_ven": 11.250924999999999, "L_ven": 0.00266644, "p_ar_init": 10665.8, "p_ven_init": 3999.7}, "pulmonary": {"R_ar": 0.8666, "C_ar": 1.8751550000000001, "L_ar": 0.00266644, "R_ven": 0.8666, "C_ven": 3.0002500000000003, "L_ven": 0.00266644, "p_ar_init": 4666.3, "p_ven_init": 3199.7}, "left_atrium": {"E_min": 0.47995999999999994, "E_max": 0.85328, "V0": 100.0, "V_init": 1625.0, "onset": 0.64, "contraction": 0.136, "relaxation": 0.136}, "right_atrium": {"E_min": 0.37330399999999997, "E_max": 0.69328, "V0": 100.0, "V_init": 1625.0, "onset": 0.64, "contraction": 0.136, "relaxation": 0.136}, "right_ventricle": {"E_min": 0.266644, "E_max": 3.1997199999999997, "V0": 250.0, "V_init": 3625.0, "onset": 0.1, "contraction": 0.272, "relaxation": 0.136}})JSON");
  const RunSpec spec = read_run_spec(j, "");
  LocalEvaluator points(spec.models, spec.model_of_points());
  Simulation sim(spec, points);
  sim.add_term(std::make_unique<FailOnceAt>(std::vector<double>{0.2, 0.66}));
  const RunResult r = sim.run();
  ASSERT_TRUE(r.converged) << r.error;
  const Circulation& circ = *spec.circulation;
  std::vector<double> state(circ.state_size());
  circ.initial_state(state);
  const double blood0 = circ.blood_volume(state) + sim.cavity_term()->reference_volumes()[0];
  double drift = 0.0;
  int cut = 0;
  bool ejected = false;
  for (const StepRecord& h : r.history) {
    double blood = h.cavity_volumes[0];
    for (double v : h.circulation.volumes) blood += v;
    drift = std::max(drift, std::abs(blood - blood0) / blood0);
    cut += h.cutbacks;
    ejected = ejected || h.circulation.phase[0] == "ejection";
    EXPECT_FALSE(h.circulation.inflow_open[0] && h.circulation.outflow_open[0]) << "t = " << h.time;
  }
  std::printf("closed loop around the LV: blood %.1f mm³, worst drift %.1e (relative), %d cut-backs\n", blood0,
              drift, cut);
  EXPECT_EQ(cut, 2);
  EXPECT_TRUE(ejected);
  EXPECT_LT(drift, 1e-8);
}

}  // namespace
}  // namespace fe2

namespace fe2 {
namespace {

// A physiology check on the shipped macro-law beat (configs/lv-beat-macro.json, the
// default beat's human-sized LV with macro-law points, one beat from end-diastole in 80
// steps, a few seconds). Measured: EDV 110.6, ESV 54.0 mL (EF 51 %), peak 16.1 kPa.
TEST(HardPhysiology, DefaultMacroBeatEjectsAPhysiologicalFraction) {
  const fs::path file = fs::path(FE2_SOURCE_DIR) / "configs" / "lv-beat-macro.json";
  json j = json::parse(std::ifstream(file));
  j["output"] = {{"vtu", false}};
  const RunSpec spec = read_run_spec(j, file.parent_path().string());
  LocalEvaluator points(spec.models, spec.model_of_points());
  Simulation sim(spec, points);
  const RunResult r = sim.run();
  ASSERT_TRUE(r.converged) << r.error;
  std::vector<double> t, V, p;
  for (const StepRecord& h : r.history)
    t.push_back(h.time), V.push_back(h.cavity_volumes[0]), p.push_back(h.cavity_pressures[0]);
  const BeatFigures b = beat_figures(t, p, V, 0, t.size() - 1);
  std::printf("default macro beat: EDV %.0f, ESV %.0f mm³, EF %.1f %%, peak %.2f kPa\n", b.EDV, b.ESV, 100 * b.EF,
              1e-3 * b.peak_pressure);
  EXPECT_GT(b.ESV, 0.0);
  EXPECT_GT(b.EDV, b.ESV);
  EXPECT_GE(b.EF, 0.40);
  EXPECT_LE(b.EF, 0.65);
  EXPECT_GE(b.peak_pressure, 12e3);
  EXPECT_LE(b.peak_pressure, 18e3);
}

}  // namespace
}  // namespace fe2

namespace fe2 {
namespace {

// The default beat's heart with FE² units that are the macro law (homogeneous units of
// the same Holzapfel–Ogden + Land 2017 material, a volumetric penalty so the units have
// one) gives the macro-law beat's PV loop: the homogenized law of a homogeneous unit is
// the law itself. To fit the hard suite: 40 ms steps, from end-diastole through the
// ejection and relaxation into filling (t = 0.4 s; about 50 s).
TEST(HardPhysiology, HomogeneousUnitsOfTheMacroLawGiveTheMacroBeat) {
  const fs::path file = fs::path(FE2_SOURCE_DIR) / "configs" / "lv-beat-macro.json";
  auto beat = [&](bool fe2) {
    json j = json::parse(std::ifstream(file));
    j["output"] = {{"vtu", false}};
    j["time"] = {{"t_end", 0.4}, {"steps", 10}, {"inflation_steps", 4}};
    j["newton"] = {{"rtol", 1e-11}, {"micro_rtol", 1e-12}, {"max_iterations", 30}};
    j["models"]["myocardium"] = test::macro_law_or_its_units(j["models"]["myocardium"]["material"], fe2);
    const RunSpec spec = read_run_spec(j, file.parent_path().string());
    LocalEvaluator points(spec.models, spec.model_of_points());
    Simulation sim(spec, points);
    return sim.run();
  };
  const RunResult law = beat(false), fe2 = beat(true);
  ASSERT_TRUE(law.converged) << law.error;
  ASSERT_TRUE(fe2.converged) << fe2.error;
  ASSERT_EQ(law.history.size(), fe2.history.size());
  double dV = 0.0, dp = 0.0, V = 0.0, p = 0.0;
  for (size_t k = 0; k < law.history.size(); ++k) {
    const StepRecord &a = law.history[k], &b = fe2.history[k];
    V = std::max(V, a.cavity_volumes[0]), p = std::max(p, a.cavity_pressures[0]);
    dV = std::max(dV, std::abs(a.cavity_volumes[0] - b.cavity_volumes[0]));
    dp = std::max(dp, std::abs(a.cavity_pressures[0] - b.cavity_pressures[0]));
  }
  std::printf("macro law against homogeneous units: |ΔV|/V %.1e, |Δp|/p %.1e (peak %.2f kPa)\n", dV / V, dp / p,
              1e-3 * p);
  EXPECT_GT(p, 10e3);  // it did beat
  EXPECT_LT(dV / V, 1e-8);
  EXPECT_LT(dp / p, 1e-8);
}

// Several beats whose cells beat once, or at another period, get a warning naming the
// key; cells in step with the circulation, or a single beat, get none.
TEST(CirculationCoupling, CellsOutOfStepWithTheCirculationAreWarnedAbout) {
  const std::string key = "/models/myocardium/material/active/calcium/period";
  EXPECT_TRUE(read_run_spec(lv_beat(8, 0.8), "").warnings.empty());  // one beat
  const RunSpec once = read_run_spec(lv_beat(24, 2.4), "");
  ASSERT_EQ(once.warnings.size(), 1u);
  EXPECT_NE(once.warnings[0].find(key + ": absent (one beat) but the circulation's period is 0.8 s"), std::string::npos)
      << once.warnings[0];
  json j = lv_beat(24, 2.4);
  j["models"]["myocardium"]["material"]["active"]["calcium"] = {{"period", 0.7}};
  const RunSpec fast = read_run_spec(j, "");
  ASSERT_EQ(fast.warnings.size(), 1u);
  EXPECT_NE(fast.warnings[0].find(key + ": 0.7 s"), std::string::npos) << fast.warnings[0];
  j["models"]["myocardium"]["material"]["active"]["calcium"]["period"] = 0.8;
  EXPECT_TRUE(read_run_spec(j, "").warnings.empty());
}

// time.inflation_steps: before the beat the resting wall is inflated to the circulation's
// filling pressure (the preload's 1 kPa), so the beat starts at end-diastole. At t = 0
// exactly the cavity pressure is the filling pressure, the wall is where a plain passive
// inflation by that follower pressure puts it, and the circulation has not moved; the
// beat's figures (summary, circulation.csv) start from that state.
TEST(CirculationCoupling, InflationStartsTheBeatAtEndDiastole) {
  json j = lv_beat(4, 0.04);
  j["time"]["inflation_steps"] = 5;
  const RunSpec spec = read_run_spec(j, "");
  EXPECT_EQ(spec.steps, 9);
  EXPECT_DOUBLE_EQ(spec.t_start, -0.05);
  LocalEvaluator points(spec.models, spec.model_of_points());
  Simulation sim(spec, points);
  const RunResult r = sim.run();
  ASSERT_TRUE(r.converged) << r.error;
  ASSERT_EQ(r.history.size(), 9u);
  const StepRecord& ed = r.history[4];
  EXPECT_EQ(ed.time, 0.0);
  const auto names = spec.circulation->compartment_names();
  const size_t arterial = static_cast<size_t>(std::find(names.begin(), names.end(), "lv.arterial") - names.begin());
  ASSERT_LT(arterial, names.size());
  for (int s = 0; s < 5; ++s) {
    const StepRecord& h = r.history[s];
    EXPECT_EQ(h.circulation.phase[0], "inflation") << "step " << s;
    // The prescribed ramp, met to round-off (the row is linear in p_c).
    EXPECT_NEAR(h.cavity_pressures[0], 1000.0 * (s + 1) / 5.0, 1e-9) << "step " << s;
    // What the inflating wall takes in is reported as its inflow (the blood a cavity with
    // a fluid receives through its inflow ring); nothing leaves.
    EXPECT_GT(h.circulation.Q_in[0], 0.0) << "step " << s;
    EXPECT_EQ(h.circulation.Q_net[0], h.circulation.Q_in[0]);
    EXPECT_EQ(h.circulation.Q_out[0], 0.0);
    // The arteries keep their initial pressure while the wall inflates.
    EXPECT_EQ(h.circulation.pressures[arterial], 9000.0);
  }
  EXPECT_NE(r.history[5].circulation.phase[0], "inflation");

  // The same wall inflated by a follower pressure ramped to 1 kPa over as many steps, no
  // circulation; its cells rest too (excited at 0.1 s, after the ramp).
  json passive = lv_beat(5, 0.05);
  passive.erase("circulation");
  passive["pressure"] = {{{"surface", "endo"}, {"value", 1000.0}}};
  const RunSpec pspec = read_run_spec(passive, "");
  LocalEvaluator ppoints(pspec.models, pspec.model_of_points());
  Simulation psim(pspec, ppoints);
  const RunResult pr = psim.run();
  ASSERT_TRUE(pr.converged) << pr.error;
  const double V_passive = pr.history.back().cavity_volumes[0];
  const double V_ref = sim.cavity_term()->reference_volumes()[0];
  ASSERT_GT(V_passive, 1.05 * V_ref);  // the wall did inflate
  // Viscosity and the cells' rest act alike in both; only the Newton tolerances differ.
  EXPECT_NEAR(ed.cavity_volumes[0], V_passive, 1e-7 * V_passive);

  passive["time"]["inflation_steps"] = 3;  // nothing to inflate to without a circulation
  try {
    read_run_spec(passive, "");
    ADD_FAILURE() << "inflation without a circulation accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/time/inflation_steps: got 3"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace fe2
