// The 0D circulation (common/circulation/): the Windkessel against its exact
// solutions, blood conservation of the closed loop, the valves and phases of a beat, the
// exact Jacobian ∂Q_net/∂p the wall coupling uses, a periodic physiological beat, and
// refused input. Units: Pa, mm³, s.
#include "common/circulation/Circulation.h"
#include "common/circulation/ElastanceVentricle.h"
#include "common/circulation/beat_summary.h"
#include "common/circulation/circulation_factory.h"
#include "common/circulation/circulation_keys.h"
#include "common/circulation/circulation_run.h"
#include "common/circulation/circulation_run_spec.h"
#include "common/circulation/circulation_schema.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>

namespace fe2 {
namespace {

using circulation_keys::kMmHg;
using circulation_keys::kMl;

CirculationPtr make(const json& j) {
  SpecNode node(j, "/circulation", *circulation_schema());
  return make_circulation(node);
}

int index_of(const std::vector<std::string>& names, const std::string& name) {
  const auto it = std::find(names.begin(), names.end(), name);
  EXPECT_NE(it, names.end()) << name;
  return static_cast<int>(it - names.begin());
}

/// An LV Windkessel whose valves are ideal when closed (R_closed = 1e30: no leak), so the
/// compliance sees only what the test puts through the outflow valve.
json ideal_windkessel(double p0) {
  return {{"kind", "windkessel"},
          {"cavities",
           {{"lv",
             {{"preload", {{"pressure", 0.0}}},
              {"inflow_valve", {{"R_closed", 1e30}}},
              {"outflow_valve", {{"R_closed", 1e30}}},
              {"windkessel", {{"p0", p0}}}}}}}};
}

/// Pressure of the Windkessel compliance after `steps` steps of dt with the cavity at 0 Pa
/// (outflow valve closed: the diastolic decay).
double decay(const Circulation& c, double dt, int steps) {
  std::vector<double> a(c.state_size()), b(c.state_size());
  c.initial_state(a);
  const int C = index_of(c.compartment_names(), "lv.arterial");
  const double p_cav[1] = {0.0};
  double p = 0.0;
  for (int k = 1; k <= steps; ++k) {
    p = c.step(k * dt, dt, p_cav, a, b).pressures[C];
    a.swap(b);
  }
  return p;
}

// Diastole: with the outflow valve closed the compliance drains through R_p,
// p(t) = p_d + (p0 − p_d) e^{−t/(R_p C)}. Backward Euler is exact for its own recursion
// p_n = p_d + (p0 − p_d)(1 + Δt/τ)^{−n} (checked to 1e-12), and first order in Δt towards
// the exponential: the Richardson value 2 p(Δt/2) − p(Δt) matches it to 1e-8.
TEST(Circulation, WindkesselDiastolicDecayIsExponential) {
  const double p0 = 80 * kMmHg;
  const auto c = make(ideal_windkessel(p0));
  const auto wk = circulation_keys::lv_windkessel();
  const double tau = wk.Rp * wk.C, pd = wk.p_distal;
  ASSERT_NEAR(tau, 1.2, 1e-4);  // 0.8 mmHg s/mL × 1.5 mL/mmHg

  const double dt = 0.01;
  const int n = 150;
  const double recursion = pd + (p0 - pd) * std::pow(1.0 + dt / tau, -n);
  EXPECT_NEAR(decay(*c, dt, n), recursion, 1e-12 * recursion);

  const int N = 10000;  // Δt/τ = 1e-4 over one τ
  const double coarse = decay(*c, tau / N, N), fine = decay(*c, tau / (2 * N), 2 * N);
  const double exact = pd + (p0 - pd) * std::exp(-1.0);
  EXPECT_NEAR((coarse - exact) / (fine - exact), 2.0, 1e-3);  // first order
  EXPECT_GT(std::abs(coarse - exact), 1e-6 * exact);          // so the next line is no accident
  EXPECT_NEAR(2.0 * fine - coarse, exact, 1e-8 * exact);
}

// A constant outflow Q into the Windkessel (the cavity pressure solved each step so that
// Q_out = Q, by Newton on dQ_net/dp): the compliance reaches p_d + Q R_p and the
// proximal (aortic root) pressure p_d + Q (R_p + Z_c).
TEST(Circulation, WindkesselUnderConstantInflowReachesSteadyPressures) {
  const auto c = make(ideal_windkessel(80 * kMmHg));
  const auto wk = circulation_keys::lv_windkessel();
  const double Q = 100 * kMl;  // 100 mL/s
  std::vector<double> a(c->state_size()), b(c->state_size());
  c->initial_state(a);
  const int C = index_of(c->compartment_names(), "lv.arterial");
  const int prox = index_of(c->compartment_names(), "lv.proximal");
  double p = 100 * kMmHg;
  CavityFlows f;
  const double dt = 0.5;  // τ = 1.2 s: the error falls by 1/(1 + Δt/τ) = 0.71 per step
  for (int k = 1; k <= 200; ++k) {
    for (int it = 0; it < 30; ++it) {
      f = c->step(k * dt, dt, {&p, 1}, a, b);
      if (std::abs(f.Q_net[0] + Q) <= 1e-12 * Q) break;
      p -= (f.Q_net[0] + Q) / f.dQ(0, 0);
    }
    ASSERT_NEAR(f.Q_out[0], Q, 1e-9 * Q);
    a.swap(b);
  }
  EXPECT_NEAR(f.pressures[C], wk.p_distal + Q * wk.Rp, 1e-8 * f.pressures[C]);
  EXPECT_NEAR(f.pressures[prox], wk.p_distal + Q * (wk.Rp + wk.Zc), 1e-8 * f.pressures[prox]);
  EXPECT_GT(p, f.pressures[prox]);  // the open valve needs a forward gradient
}

json closed_loop_spec(int beats) {
  return {{"circulation", {{"kind", "closed_loop"}, {"cavities", {{"lv", json::object()}, {"rv", json::object()}}}}},
          {"time", {{"beats", beats}, {"steps_per_beat", 400}}}};
}

// The closed loop holds its blood: compartments + both cavities, every step, to 1e-10
// relative, over one beat and over five (the final volume update is conservative by
// construction; the coupling's volume is V_n + Δt Q_net exactly).
TEST(Circulation, ClosedLoopConservesBloodVolume) {
  for (int beats : {1, 5}) {
    SCOPED_TRACE(beats);
    const auto spec = read_circulation_run_spec(closed_loop_spec(beats), "closed_loop");
    const auto run = run_circulation(spec);
    ASSERT_EQ(run.size(), 400u * beats + 1);
    const double V0 = run.front().blood_volume;
    EXPECT_NEAR(V0, (65 + 120 + 65 + 145) * kMl + 1.2 * 80 * kMl + 60 * 30 * kMl + 10 * 35 * kMl +
                        16 * 24 * kMl, 1e-6 * V0);  // Regazzoni 2022's initial state
    double worst = 0.0, ejected = 0.0;
    for (const auto& s : run) {
      worst = std::max(worst, std::abs(s.blood_volume - V0));
      if (!s.flows.Q_out.empty()) ejected += spec.dt() * s.flows.Q_out[0];
    }
    EXPECT_LE(worst, 1e-10 * V0) << worst;
    EXPECT_GT(ejected, 40 * kMl * beats);  // blood did move: > 40 mL per beat through the aorta
  }
}

json lv_windkessel_spec(int beats) {
  return {{"circulation", {{"kind", "windkessel"}, {"cavities", {{"lv", json::object()}}}}},
          {"time", {{"beats", beats}, {"steps_per_beat", 400}}}};
}

/// The run's phases over samples [first, last], consecutive repeats merged.
std::vector<std::string> phases(const std::vector<CirculationSample>& run, size_t first, size_t last, int c) {
  std::vector<std::string> out;
  for (size_t i = first; i <= last; ++i)
    if (out.empty() || out.back() != run[i].flows.phase[c]) out.push_back(run[i].flows.phase[c]);
  return out;
}

// An elastance LV into the Windkessel (defaults): mitral and aortic valves are never open
// together, and the last beat goes filling → isovolumic contraction → ejection →
// isovolumic relaxation → filling, each phase once.
TEST(Circulation, ValvesNeverBothOpenAndPhasesInOrder) {
  for (const json& j : {lv_windkessel_spec(3), closed_loop_spec(3)}) {
    const auto spec = read_circulation_run_spec(j, "phases");
    const auto run = run_circulation(spec);
    for (int c = 0; c < spec.circulation->cavities(); ++c) {
      SCOPED_TRACE(spec.circulation->kind() + " " + spec.circulation->cavity_names()[c]);
      int both = 0;
      for (size_t i = 1; i < run.size(); ++i)
        both += run[i].flows.inflow_open[c] && run[i].flows.outflow_open[c];
      EXPECT_EQ(both, 0);
      const auto seq = phases(run, run.size() - 400, run.size() - 1, c);
      const std::vector<std::string> expected = {"filling", "isovolumic contraction", "ejection",
                                                 "isovolumic relaxation", "filling"};
      EXPECT_EQ(seq, expected) << fmt::format("{}", fmt::join(seq, " → "));
    }
  }
}

// ∂Q_net/∂p (implicit function theorem through the internal Newton) equals central
// differences of Q_net to 1e-6, at a step of every phase, for the Windkessel and for the
// closed loop with two cavities (off-diagonal terms included).
TEST(Circulation, JacobianMatchesFiniteDifferencesInEveryPhase) {
  for (const json& j : {lv_windkessel_spec(2), closed_loop_spec(2)}) {
    const auto spec = read_circulation_run_spec(j, "jacobian");
    const Circulation& circ = *spec.circulation;
    const int n = circ.cavities();
    std::vector<double> committed(circ.state_size()), current(circ.state_size());
    circ.initial_state(committed);
    std::vector<double> p(n), V(n);
    for (int c = 0; c < n; ++c) {
      V[c] = spec.ventricles[c].initial_volume();
      p[c] = spec.ventricles[c].pressure(0.0, V[c]);
    }
    std::set<std::string> checked;
    const double dt = spec.dt();
    for (int k = 1; k <= spec.steps; ++k) {
      const std::vector<double> V_n = V;
      const CavityFlows f = couple_step(circ, spec.ventricles, k * dt, dt, committed, current, p, V);
      for (int c = 0; c < n; ++c) {
        const std::string key = circ.cavity_names()[c] + ": " + f.phase[c];
        if (checked.count(key)) continue;
        checked.insert(key);
        SCOPED_TRACE(circ.kind() + " " + key);
        std::vector<double> scratch(circ.state_size());
        for (int jj = 0; jj < n; ++jj) {
          const double h = 1e-2;  // Pa; valve width 10 Pa
          std::vector<double> pp = p, pm = p;
          pp[jj] += h, pm[jj] -= h;
          const double Qp = circ.step(k * dt, dt, pp, committed, scratch).Q_net[c];
          const double Qm = circ.step(k * dt, dt, pm, committed, scratch).Q_net[c];
          const double fd = (Qp - Qm) / (2 * h);
          EXPECT_NEAR(f.dQ(c, jj), fd, 1e-6 * std::abs(fd) + 1e-12)
              << "d Q_net[" << c << "] / d p[" << jj << "]";
        }
      }
      committed.swap(current);
    }
    const std::vector<std::string> want = {"filling", "isovolumic contraction", "ejection",
                                           "isovolumic relaxation"};
    for (const auto& name : circ.cavity_names())
      for (const auto& ph : want) EXPECT_TRUE(checked.count(name + ": " + ph)) << name << ": " << ph;
  }
}

// The elastance LV into the Windkessel settles into a periodic beat: after 8 beats EDV
// changes by less than 1e-5 relative from beat to beat; SV, EF and pressures with the
// defaults are human (EF 40–70 %, peak LV pressure 12–20 kPa).
TEST(Circulation, ElastanceVentricleReachesPeriodicPhysiologicalBeat) {
  const int beats = 8, per = 400;
  const auto spec = read_circulation_run_spec(lv_windkessel_spec(beats), "periodic");
  const auto run = run_circulation(spec);
  std::vector<double> t, p, V;
  for (const auto& s : run) t.push_back(s.t), p.push_back(s.p[0]), V.push_back(s.V[0]);
  std::vector<BeatFigures> b;
  for (int k = 0; k < beats; ++k) b.push_back(beat_figures(t, p, V, k * per, (k + 1) * per));
  const BeatFigures& last = b.back();
  const double change = std::abs(last.EDV - b[beats - 2].EDV) / last.EDV;
  EXPECT_LT(change, 1e-5);
  EXPECT_GT(std::abs(b[1].EDV - b[0].EDV) / b[0].EDV, 10 * change);  // it did settle
  EXPECT_GT(last.EF, 0.40);
  EXPECT_LT(last.EF, 0.70);
  EXPECT_GT(last.peak_pressure, 12e3);
  EXPECT_LT(last.peak_pressure, 20e3);
  EXPECT_GT(last.SV, 50 * kMl);
  EXPECT_LT(last.SV, 110 * kMl);
  EXPECT_GT(last.ESV, 0.0);
  EXPECT_GT(last.dpdt_max, 0.0);
  EXPECT_LT(last.dpdt_min, 0.0);
  // The loop encloses the stroke work: more than SV × 60 mmHg.
  EXPECT_GT(last.stroke_work, last.SV * 60 * kMmHg);
}

// The same inputs give the same bits (the owner may replay a step after a cut-back).
TEST(Circulation, StepIsDeterministic) {
  const auto c = make({{"kind", "closed_loop"}, {"cavities", {{"lv", json::object()}}}});
  std::vector<double> s(c->state_size()), a(c->state_size()), b(c->state_size());
  c->initial_state(s);
  const double p[1] = {1e3};
  const CavityFlows fa = c->step(0.3, 1e-3, p, s, a), fb = c->step(0.3, 1e-3, p, s, b);
  EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(double)), 0);
  EXPECT_EQ(std::memcmp(&fa.Q_net[0], &fb.Q_net[0], sizeof(double)), 0);
  EXPECT_EQ(std::memcmp(&fa.dQ_dp[0], &fb.dQ_dp[0], sizeof(double)), 0);
}

// The internal Newton reports a failure naming the compartment.
TEST(Circulation, NonFiniteCavityPressureIsANumericalError) {
  const auto c = make({{"kind", "windkessel"}, {"cavities", {{"lv", json::object()}}}});
  std::vector<double> s(c->state_size()), a(c->state_size());
  c->initial_state(s);
  const double p[1] = {std::nan("")};
  try {
    c->step(0.1, 1e-3, p, s, a);
    FAIL() << "no error";
  } catch (const NumericalError& e) {
    EXPECT_NE(std::string(e.what()).find("cavity 'lv'"), std::string::npos) << e.what();
  }
}

std::string input_error(const json& circulation) {
  try {
    make(circulation);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(accepted)";
}

TEST(Circulation, BadInputIsRefusedNamingTheKey) {
  const json lv_wk = {{"kind", "windkessel"}, {"cavities", {{"lv", {{"windkessel", {{"C", -1.0}}}}}}}};
  EXPECT_EQ(input_error(lv_wk),
            "/circulation/cavities/lv/windkessel/C: got -1.0, expected a number > 0 (arterial "
            "compliance C (mm^3/Pa); default lv 1.5 mL/mmHg (Westerhof 2009), rv 10 mL/mmHg "
            "(Regazzoni 2022 C_AR pulmonary))");
  EXPECT_NE(input_error({{"kind", "closed_loop"}, {"cavities", {{"lv", json::object()}}},
                         {"systemic", {{"R_ar", 0}}}})
                .find("/circulation/systemic/R_ar: got 0, expected a number > 0"),
            std::string::npos);
  EXPECT_NE(input_error({{"kind", "windkessel"},
                         {"cavities", {{"lv", {{"outflow_valve", {{"R_open", 1.0}, {"R_closed", 0.5}}}}}}}})
                .find("/circulation/cavities/lv/outflow_valve/R_closed: got 0.5, expected a "
                      "resistance above R_open = 1"),
            std::string::npos);
  EXPECT_NE(input_error({{"kind", "closed_loop"}, {"period", 0.3}, {"cavities", {{"lv", json::object()}}}})
                .find("/circulation/left_atrium/onset: got nothing (key missing), expected an "
                      "onset below the period 0.3 s"),
            std::string::npos);
  EXPECT_NE(input_error({{"kind", "closed_loop"},
                         {"period", 0.8},
                         {"cavities", {{"lv", json::object()}}},
                         {"right_ventricle", {{"contraction", 0.6}, {"relaxation", 0.3}}}})
                .find("beat period is shorter than the activation window"),
            std::string::npos);
  EXPECT_NE(input_error({{"kind", "closed_loop"}, {"cavities", {{"lv", json::object()}, {"rv", json::object()}}},
                         {"right_ventricle", json::object()}})
                .find("/circulation/right_ventricle"),
            std::string::npos);
  EXPECT_NE(input_error({{"kind", "windkessel"}, {"cavities", {{"lv", {{"windkesel", json::object()}}}}}})
                .find("unknown key 'windkesel' in /circulation/cavities/lv; did you mean 'windkessel'?"),
            std::string::npos);
  EXPECT_NE(input_error({{"kind", "windkessel"}, {"cavities", json::object()}})
                .find("/circulation/cavities/lv: got nothing (key missing), expected an object"),
            std::string::npos);
}

TEST(Circulation, RunSpecRefusesAVentricleWithoutItsCavity) {
  const json j = {{"circulation", {{"kind", "windkessel"}, {"cavities", {{"lv", json::object()}}}}},
                  {"ventricles", {{"rv", json::object()}}},
                  {"time", {{"beats", 1}}}};
  try {
    read_circulation_run_spec(j, "spec.json");
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("spec.json: /ventricles/rv: got {}, expected no rv ventricle"),
              std::string::npos)
        << e.what();
  }
}

// The reader reads every key of every branch by the schema (SpecNode throws an internal
// error on a key it lacks), and the description names the parameters.
TEST(Circulation, ReaderAgreesWithSchemaAndDescribes) {
  const json specs[] = {
      {{"kind", "windkessel"},
       {"period", 0.9},
       {"cavities",
        {{"lv", {{"preload", {{"kind", "atrium"}, {"E_max", 0.03}, {"p_venous", 1200.0}}},
                 {"inflow_valve", {{"width", 5.0}}},
                 {"windkessel", {{"Zc", 0.01}, {"Rp", 0.1}, {"C", 1e4}, {"p_distal", 0.0}, {"p0", 1e4}}}}},
         {"rv", {{"preload", {{"pressure", 500.0}}}}}}}},
      {{"kind", "closed_loop"},
       {"cavities", {{"lv", {{"outflow_valve", {{"R_open", 2e-3}}}}}}},
       {"systemic", {{"L_ar", 0.0}}},
       {"right_ventricle", {{"E_max", 0.1}}}}};
  for (const json& j : specs) {
    SpecDoc doc;
    SpecNode node(j, "/circulation", *circulation_schema(), &doc);
    const auto c = make_circulation(node);
    EXPECT_GT(doc.visited.size(), 10u);
    EXPECT_NE(c->description().find(c->kind()), std::string::npos);
  }
  const auto wk = make(specs[0]);
  EXPECT_EQ(wk->cavity_names(), (std::vector<std::string>{"lv", "rv"}));
  EXPECT_NE(wk->description().find("atrium E"), std::string::npos) << wk->description();
  EXPECT_FALSE(wk->closed());
  const auto loop = make(specs[1]);
  EXPECT_EQ(loop->cavity_names(), std::vector<std::string>{"lv"});
  EXPECT_TRUE(loop->closed());
}

/// Paths of schema nodes under `n` that no read visited.
void unvisited(const SchemaNode& n, const std::string& path, const SpecDoc& doc,
               std::vector<std::string>& out) {
  auto key = [&](const std::string& p, const SchemaNode& k) {
    if (!doc.visited.count(&k)) out.push_back(p);
    unvisited(k, p, doc, out);
  };
  for (const auto& [name, k] : n.keys) key(path + "/" + name, *k);
  for (const auto& b : n.branches)
    for (const auto& [name, k] : b.keys) key(path + "/" + name + " (" + b.value + ")", *k);
}

// The shipped circulation configs and exemplars together read every key of the
// circulation spec schema (what spec-doc lists is what the reader accepts), and each
// passes the reader checked against that schema.
TEST(Circulation, ShippedSpecsReadEveryKeyOfTheSchema) {
  namespace fs = std::filesystem;
  const fs::path src = FE2_SOURCE_DIR;
  SpecDoc doc;
  int read = 0;
  for (const fs::path& dir : {src / "configs", src / "tests/data/schema"})
    for (const auto& e : fs::directory_iterator(dir)) {
      if (e.path().extension() != ".json") continue;
      const json j = read_json_file(e.path().string());
      if (!is_circulation_run_spec(j)) continue;
      SCOPED_TRACE(e.path().string());
      read_circulation_run_spec(j, e.path().string(), &doc);
      ++read;
    }
  EXPECT_GE(read, 4);
  std::vector<std::string> missing;
  unvisited(circulation_run_schema(), "", doc, missing);
  EXPECT_TRUE(missing.empty()) << fmt::format("{}", fmt::join(missing, ", "));
}

}  // namespace
}  // namespace fe2
