// Cell models (common/cellmodels/): each isometric twitch against an independent
// high-accuracy integration of the published equations written here (Land 2017 in the
// paper's ms/kPa units, Dormand–Prince 5(4) at rtol 1e-10), force–velocity of Land 2017,
// dT_a/dλ and dT_a/dλ̇ against central differences of the step, the calcium template's
// analytic peak, the prescribed tables, and the spec reader against its schema.
#include "common/cellmodels/BestelClementSorine.h"
#include "common/cellmodels/CalciumTransient.h"
#include "common/cellmodels/Land2017.h"
#include "common/cellmodels/PrescribedTension.h"
#include "common/cellmodels/cell_model_factory.h"
#include "common/cellmodels/cell_model_schema.h"
#include "common/error.h"
#include "common/spec/SchemaNode.h"
#include "common/spec/json_schema.h"
#include "common/spec/spec_reference.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

namespace fe2 {
namespace {

// ---------------------------------------------------------------- reference integrator

/// Adaptive Dormand–Prince 5(4) from t0 to t1 (local extrapolation, error per component
/// against atol + rtol |y|).
template <std::size_t N, class F>
void dormand_prince(const F& f, double t0, double t1, std::array<double, N>& y, double rtol,
                    double atol) {
  using V = std::array<double, N>;
  static constexpr double c[7] = {0, 1.0 / 5, 3.0 / 10, 4.0 / 5, 8.0 / 9, 1, 1};
  static constexpr double a[7][6] = {
      {},
      {1.0 / 5},
      {3.0 / 40, 9.0 / 40},
      {44.0 / 45, -56.0 / 15, 32.0 / 9},
      {19372.0 / 6561, -25360.0 / 2187, 64448.0 / 6561, -212.0 / 729},
      {9017.0 / 3168, -355.0 / 33, 46732.0 / 5247, 49.0 / 176, -5103.0 / 18656},
      {35.0 / 384, 0, 500.0 / 1113, 125.0 / 192, -2187.0 / 6784, 11.0 / 84}};
  static constexpr double b5[7] = {35.0 / 384, 0, 500.0 / 1113, 125.0 / 192, -2187.0 / 6784,
                                   11.0 / 84, 0};
  static constexpr double b4[7] = {5179.0 / 57600,    0,          7571.0 / 16695, 393.0 / 640,
                                   -92097.0 / 339200, 187.0 / 2100, 1.0 / 40};
  double t = t0, h = std::min(1e-3 * (t1 - t0), t1 - t0);
  std::array<V, 7> k;
  while (t < t1) {
    if (t + h > t1) h = t1 - t;
    for (int s = 0; s < 7; ++s) {
      V z = y;
      for (int j = 0; j < s; ++j)
        for (std::size_t i = 0; i < N; ++i) z[i] += h * a[s][j] * k[j][i];
      f(t + c[s] * h, z, k[s]);
    }
    V y5 = y;
    double err = 0.0;
    for (std::size_t i = 0; i < N; ++i) {
      double e = 0.0;
      for (int s = 0; s < 7; ++s) {
        y5[i] += h * b5[s] * k[s][i];
        e += h * (b5[s] - b4[s]) * k[s][i];
      }
      err = std::max(err, std::abs(e) / (atol + rtol * std::max(std::abs(y[i]), std::abs(y5[i]))));
    }
    if (err <= 1.0) {
      t += h;
      y = y5;
    }
    h *= std::clamp(0.9 * std::pow(std::max(err, 1e-30), -0.2), 0.2, 5.0);
  }
}

/// The calcium template written out here, in ms and µM.
struct RefCalcium {
  double rest, peak, rise, decay;  // µM, µM, ms, ms
  double operator()(double s) const {
    if (s < 0.0) return rest;
    const double sp = rise * decay * std::log(decay / rise) / (decay - rise);
    const double n = std::exp(-sp / decay) - std::exp(-sp / rise);
    return rest + (peak - rest) * (std::exp(-s / decay) - std::exp(-s / rise)) / n;
  }
};

/// Land et al. 2017 as published: ms, µM, kPa; Appendix B's intact column.
struct RefLand {
  double ktrpn = 0.1, ntrpn = 2, ca50 = 0.805, ku = 1.0, ntm = 5, trpn50 = 0.35, kuw = 0.182,
         kws = 0.012, rw = 0.5, rs = 0.25, gs = 0.0085, gw = 0.615, phi = 2.23, Aeff = 25,
         b0 = 2.3, b1 = -2.4, Tref = 120;
  // y = CaTRPN, B, XS, XW, zeta_s, zeta_w; lam and dlam (per ms) of time t (ms).
  void rhs(double ca, double lam, double dlam, const std::array<double, 6>& y,
           std::array<double, 6>& dy) const {
    const double C = std::max(y[0], 0.0), B = y[1], S = std::max(y[2], 0.0),
                 W = std::max(y[3], 0.0), zs = y[4], zw = y[5];
    const double kwu = kuw * (1 / rw - 1) - kws, ksu = kws * rw * (1 / rs - 1);
    const double A = Aeff * rs / ((1 - rs) * rw + rs);
    const double cw = phi * kuw * ((1 - rs) * (1 - rw)) / ((1 - rs) * rw);
    const double cs = phi * kws * ((1 - rs) * rw) / rs;
    const double kb = ku * std::pow(trpn50, ntm) / (1 - rs - (1 - rs) * rw);
    const double U = 1 - B - S - W;
    const double cat50 = ca50 + b1 * (std::min(lam, 1.2) - 1);
    dy[0] = ktrpn * (std::pow(ca / cat50, ntrpn) * (1 - C) - C);
    const double unblock = C > 0 ? std::min(100.0, std::pow(C, -ntm / 2)) : 100.0;
    dy[1] = kb * unblock * U - ku * std::pow(C, ntm / 2) * B;
    const double gsu = gs * (zs > 0 ? zs : (zs < -1 ? -zs - 1 : 0.0));
    const double gwu = gw * std::abs(zw);
    dy[2] = kws * W - ksu * S - gsu * S;
    dy[3] = kuw * U - kwu * W - kws * W - gwu * W;
    dy[4] = A * dlam - cs * zs;
    dy[5] = A * dlam - cw * zw;
  }
  double tension(double lam, const std::array<double, 6>& y) const {  // kPa
    const double lm = std::min(lam, 1.2);
    const double h = std::max(0.0, 1 + b0 * (lm + std::min(lm, 0.87) - 1.87));
    return h * (Tref / rs) * ((y[4] + 1) * std::max(y[2], 0.0) + y[5] * std::max(y[3], 0.0));
  }
};

const RefCalcium kCa{0.1, 1.0, 20.0, 110.0};  // the defaults, in ms

/// A point's state stepped through a model with the step a beat would use.
struct Stepper {
  const CellModel& m;
  std::vector<double> committed, current;
  explicit Stepper(const CellModel& model)
      : m(model), committed(model.state_size()), current(model.state_size()) {
    m.rest_state(committed);
  }
  ActiveTension step(double t, double dt, double lam = 1.0, double rate = 0.0, bool commit = true) {
    const ActiveTension a = m.advance({t, dt, 0.0, lam, rate}, committed, current);
    if (commit) committed = current;
    return a;
  }
};

constexpr double kDt = 1e-3;  // 1 ms
constexpr int kSteps = 1000;  // 0 to 1 s

std::vector<double> model_twitch(const CellModel& m) {
  Stepper p(m);
  std::vector<double> Ta{p.step(0.0, 0.0).Ta};
  for (int k = 1; k <= kSteps; ++k) Ta.push_back(p.step(k * kDt, kDt).Ta);
  return Ta;
}

struct TwitchFigures {
  double peak;
  int at;
};
TwitchFigures peak_of(const std::vector<double>& Ta) {
  const auto it = std::max_element(Ta.begin(), Ta.end());
  return {*it, static_cast<int>(it - Ta.begin())};
}

void expect_trace_matches(const std::vector<double>& model, const std::vector<double>& ref) {
  const TwitchFigures r = peak_of(ref);
  EXPECT_NEAR(model[r.at], r.peak, 1e-6 * r.peak) << "at the peak, t = " << r.at << " ms";
  double worst = 0.0;
  int where = 0;
  for (size_t k = 0; k < ref.size(); ++k)
    if (std::abs(model[k] - ref[k]) > worst) worst = std::abs(model[k] - ref[k]), where = static_cast<int>(k);
  EXPECT_LT(worst, 1e-3 * r.peak) << "worst at t = " << where << " ms";
  std::printf("  peak %.6g Pa at %d ms; peak error %.2e relative; trace error %.2e of the peak\n",
              r.peak, r.at, std::abs(model[r.at] - r.peak) / r.peak, worst / r.peak);
}

// ------------------------------------------------------------------------- Land 2017

Land2017 default_land() { return Land2017(Land2017Parameters::intact(), CalciumParameters{}, 1e-4); }

TEST(Land2017, RestStateIsTheEquilibriumOfThePublishedEquations) {
  const Land2017 m = default_land();
  std::array<double, 6> y, dy;
  m.rest_state(y);
  RefLand().rhs(kCa(-1.0), 1.0, 0.0, y, dy);
  for (int i = 0; i < 6; ++i) EXPECT_NEAR(dy[i], 0.0, 1e-14) << "state " << i;
  EXPECT_NEAR(y[0] + 0.0, 0.0152, 2e-4);  // CaTRPN = r/(1+r), r = (0.1/0.805)^2
  EXPECT_GT(y[1], 0.99);                  // nearly every site blocked at rest
}

/// T_a (Pa) of the isometric twitch every 1 ms, integrated by Dormand–Prince from the
/// model's rest state.
std::vector<double> land_reference_twitch(const Land2017& m, const RefLand& ref = RefLand()) {
  std::array<double, 6> y;
  m.rest_state(y);
  std::vector<double> Tref{1e3 * ref.tension(1.0, y)};
  auto f = [&](double t, const std::array<double, 6>& z, std::array<double, 6>& dz) {
    ref.rhs(kCa(t), 1.0, 0.0, z, dz);
  };
  for (int k = 1; k <= kSteps; ++k) {
    dormand_prince(f, k - 1.0, k, y, 1e-10, 1e-14);  // ms
    Tref.push_back(1e3 * ref.tension(1.0, y));       // kPa -> Pa
  }
  return Tref;
}

TEST(Land2017, IsometricTwitchEqualsAnIndependentAccurateIntegration) {
  const Land2017 m = default_land();
  const std::vector<double> Ta = model_twitch(m);
  const std::vector<double> Tref = land_reference_twitch(m);
  expect_trace_matches(Ta, Tref);

  // A physiological twitch of the intact set: submaximal activation (a twitch does
  // not saturate troponin) between 30 % and 90 % of T_ref = 120 kPa, peak 80–200 ms
  // after onset (human intact myocardium at 37 °C), relaxed below 5 % of the peak
  // before the next beat at 60 bpm, and a resting tension below 1 % of the peak.
  const TwitchFigures p = peak_of(Ta);
  EXPECT_GT(p.peak, 0.3 * 120e3);
  EXPECT_LT(p.peak, 0.9 * 120e3);
  EXPECT_GE(p.at, 80);
  EXPECT_LE(p.at, 200);
  EXPECT_LT(Ta.back(), 0.05 * p.peak);
  EXPECT_LT(Ta.front(), 0.01 * p.peak);
}

TEST(Land2017, SkinnedTwitchEqualsAnIndependentAccurateIntegration) {
  // The skinned column is stiffer (k_b min(100, ·) ≈ 27 /ms at rest), still within RK4's
  // stability interval at the default 0.1 ms substep. Its calcium sensitivity (2.5 µM)
  // needs more calcium than the default transient.
  CalciumParameters ca;
  ca.peak = 4.0;
  const Land2017 m(Land2017Parameters::skinned(), ca, 1e-4);
  RefLand ref;
  ref.ca50 = 2.5, ref.ntm = 2.2, ref.kuw = 0.026, ref.kws = 0.004, ref.Tref = 40.5;
  const RefCalcium rc{0.1, 4.0, 20.0, 110.0};
  std::array<double, 6> y;
  m.rest_state(y);
  std::vector<double> Tref{1e3 * ref.tension(1.0, y)};
  auto f = [&](double t, const std::array<double, 6>& z, std::array<double, 6>& dz) {
    ref.rhs(rc(t), 1.0, 0.0, z, dz);
  };
  for (int k = 1; k <= kSteps; ++k) {
    dormand_prince(f, k - 1.0, k, y, 1e-10, 1e-14);
    Tref.push_back(1e3 * ref.tension(1.0, y));
  }
  expect_trace_matches(model_twitch(m), Tref);
}

/// T_a after a 20 ms ramp at rate `rate` starting near the peak (t = 0.1 s) from the
/// isometric twitch; `pass_rate` false hands the model λ̇ = 0 along the same λ path
/// (only the length effect).
double after_ramp(const Land2017& m, double rate, bool pass_rate = true) {
  Stepper p(m);
  for (int k = 1; k <= 100; ++k) p.step(k * kDt, kDt);
  double Ta = 0.0;
  for (int k = 1; k <= 20; ++k)
    Ta = p.step((100 + k) * kDt, kDt, 1.0 + rate * k * kDt, pass_rate ? rate : 0.0).Ta;
  return Ta;
}

TEST(Land2017, ForceVelocityShorteningLowersLengtheningRaises) {
  const Land2017 m = default_land();
  const std::vector<double> iso = model_twitch(m);
  // λ̇ = 0 reproduces the isometric trace bit for bit.
  EXPECT_EQ(after_ramp(m, 0.0), iso[120]);

  const std::vector<double> rates = {-2.0, -1.0, -0.5, -0.1, 0.0, 0.1, 0.5, 1.0, 2.0};  // 1/s
  std::vector<double> Ta;
  for (double r : rates) Ta.push_back(after_ramp(m, r));
  for (size_t i = 0; i + 1 < rates.size(); ++i)
    EXPECT_LT(Ta[i], Ta[i + 1]) << "between rates " << rates[i] << " and " << rates[i + 1];
  EXPECT_LT(Ta.front(), 0.8 * iso[120]);  // shortening at 2 lengths/s: well below isometric
  EXPECT_GT(Ta.back(), 1.2 * iso[120]);

  // The rate itself (cross-bridge distortion), not only the length the ramp reaches:
  // against the same λ path stepped with λ̇ = 0.
  for (double r : {-1.0, -0.1, 0.1, 1.0}) {
    const double with = after_ramp(m, r), without = after_ramp(m, r, false);
    if (r < 0)
      EXPECT_LT(with, 0.99 * without) << "rate " << r;
    else
      EXPECT_GT(with, 1.01 * without) << "rate " << r;
  }
}

/// dT_a/dλ and dT_a/dλ̇ of one step against central differences of the same step.
void expect_sensitivities(const CellModel& m, const std::vector<double>& state, CellStep s,
                          double h_lambda, double h_rate) {
  std::vector<double> out(state.size());
  const ActiveTension a = m.advance(s, state, out);
  auto Ta = [&](double dl, double dr) {
    CellStep q = s;
    q.lambda += dl;
    q.lambda_dot += dr;
    return m.advance(q, state, out).Ta;
  };
  const double fd_l = (Ta(h_lambda, 0) - Ta(-h_lambda, 0)) / (2 * h_lambda);
  const double fd_r = (Ta(0, h_rate) - Ta(0, -h_rate)) / (2 * h_rate);
  EXPECT_NEAR(a.dTa_dlambda, fd_l, 1e-6 * std::abs(fd_l)) << "lambda " << s.lambda;
  EXPECT_NEAR(a.dTa_dlambda_dot, fd_r, 1e-6 * std::abs(fd_r)) << "lambda " << s.lambda;
  std::printf("  lambda %.3f rate %.2f: Ta %.6g, dTa/dlambda %.9g (fd %.9g), dTa/dlambda_dot "
              "%.9g (fd %.9g)\n",
              s.lambda, s.lambda_dot, a.Ta, a.dTa_dlambda, fd_l, a.dTa_dlambda_dot, fd_r);
}

TEST(Land2017, SensitivitiesEqualCentralDifferencesAtSystole) {
  const Land2017 m = default_land();
  for (double rate : {0.5, -0.8}) {
    // Near the peak, after 5 ms of stretching so the distortions are far from zero.
    Stepper p(m);
    for (int k = 1; k <= 100; ++k) p.step(k * kDt, kDt);
    for (int k = 1; k <= 5; ++k) p.step((100 + k) * kDt, kDt, 1.0 + rate * k * kDt, rate);
    ASSERT_GT(std::abs(p.committed[4]), 1e-3);  // ζs
    const double lam = 1.0 + rate * 6 * kDt;
    expect_sensitivities(m, p.committed, {0.106, kDt, 0.0, lam, rate}, 1e-6, 1e-4);
    // The other branches of h(λ): below 0.87 (slope 2 β0), and a step without time.
    expect_sensitivities(m, p.committed, {0.106, kDt, 0.0, 0.85, rate}, 1e-6, 1e-4);
    const ActiveTension still = m.advance({0.105, 0.0, 0.0, lam, rate}, p.committed, p.current);
    EXPECT_EQ(p.current, p.committed);
    EXPECT_EQ(still.dTa_dlambda_dot, 0.0);
    expect_sensitivities(m, p.committed, {0.105, 0.0, 0.0, lam, rate}, 1e-6, 1e-4);
  }
}

TEST(Land2017, ParameterSetsAndDescription) {
  const Land2017Parameters in = Land2017Parameters::intact(), sk = Land2017Parameters::skinned();
  EXPECT_EQ(in.T_ref, 120e3);
  EXPECT_EQ(in.k_uw, 182.0);  // 0.182 /ms
  EXPECT_EQ(sk.T_ref, 40.5e3);
  EXPECT_EQ(sk.ca50_ref, 2.5);
  EXPECT_EQ(sk.k_ws, 4.0);
  const json j{{"model", "land2017"}, {"parameter_set", "skinned"}, {"k_u", 500}};
  SpecNode node(j, "/active", *cell_model_schema());
  const CellModelPtr m = make_cell_model(node);
  const std::string d = m->description();
  EXPECT_NE(d.find("skinned parameter set with k_u overridden"), std::string::npos) << d;
  EXPECT_NE(d.find("T_ref = 40.5 kPa"), std::string::npos) << d;
  EXPECT_EQ(static_cast<const Land2017&>(*m).parameters().k_u, 500.0);
  EXPECT_TRUE(m->rate_dependent());
  EXPECT_EQ(m->state_size(), 6);
}

TEST(Land2017, CostOfOneAdvance) {
  const Land2017 m = default_land();
  Stepper p(m);
  for (int k = 1; k <= 100; ++k) p.step(k * kDt, kDt);
  const int n = 20000;
  double sink = 0.0;
  const auto t0 = std::chrono::steady_clock::now();
  for (int i = 0; i < n; ++i) sink += p.step(0.101, kDt, 1.0 + 1e-9 * i, 0.1, false).Ta;
  const double us =
      std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count() / n;
  std::printf("  Land2017 advance(), dt = 1 ms (10 RK4 substeps with sensitivities): %.2f us\n", us);
  EXPECT_GT(sink, 0.0);
}

// --------------------------------------------------------------- Bestel–Clément–Sorine

TEST(BestelClementSorine, IsometricTwitchEqualsAnIndependentAccurateIntegration) {
  const BestelClementSorine m(BestelClementSorineParameters{}, CalciumParameters{}, 1e-4);
  const std::vector<double> Ta = model_twitch(m);
  // τ̇ = −|u| τ + σ0 |u|+, u = α_max f + α_min (1 − f), in s and Pa.
  const double sigma0 = 9e4, amax = 5.0, amin = -30.0;
  auto f = [&](double t, const std::array<double, 1>& z, std::array<double, 1>& dz) {
    const double a = (kCa(1e3 * t) - kCa.rest) / (kCa.peak - kCa.rest);
    const double u = amax * a + amin * (1 - a);
    dz[0] = -std::abs(u) * z[0] + sigma0 * std::max(u, 0.0);
  };
  std::array<double, 1> y{0.0};
  std::vector<double> Tref{0.0};
  for (int k = 1; k <= kSteps; ++k) {
    dormand_prince(f, (k - 1) * kDt, k * kDt, y, 1e-10, 1e-9);
    Tref.push_back(y[0]);
  }
  expect_trace_matches(Ta, Tref);
  // Contraction only while f > 6/7 (u > 0): a short, submaximal twitch below σ0,
  // peaking 50–150 ms after onset, relaxed before the next beat.
  const TwitchFigures p = peak_of(Ta);
  EXPECT_GT(p.peak, 5e3);
  EXPECT_LT(p.peak, 0.5 * sigma0);
  EXPECT_GE(p.at, 50);
  EXPECT_LE(p.at, 150);
  EXPECT_LT(Ta.back(), 0.05 * p.peak);
}

TEST(BestelClementSorine, NoStretchDependence) {
  const BestelClementSorine m(BestelClementSorineParameters{}, CalciumParameters{}, 1e-4);
  Stepper p(m);
  for (int k = 1; k <= 70; ++k) p.step(k * kDt, kDt);
  ASSERT_GT(p.committed[0], 1e3);
  const ActiveTension a = p.step(0.071, kDt, 1.1, 0.5, false);
  EXPECT_EQ(a.dTa_dlambda, 0.0);
  EXPECT_EQ(a.dTa_dlambda_dot, 0.0);
  // Central differences of T_a are exactly zero as well.
  EXPECT_EQ(p.step(0.071, kDt, 1.1 + 1e-6, 0.5, false).Ta, p.step(0.071, kDt, 1.1 - 1e-6, 0.5, false).Ta);
  EXPECT_EQ(p.step(0.071, kDt, 1.1, 0.5 + 1e-4, false).Ta, p.step(0.071, kDt, 1.1, 0.5 - 1e-4, false).Ta);
  EXPECT_FALSE(m.rate_dependent());
}

// ------------------------------------------------------------------- calcium, tables

TEST(CalciumTransient, AnalyticPeakPeriodicRepeatAndRest) {
  CalciumParameters cp;
  cp.rest = 0.12;
  cp.peak = 1.3;
  cp.rise = 0.015;
  cp.decay = 0.09;
  cp.period = 0.8;
  const CalciumTransient ca(cp);
  const double t_act = 0.037;
  const double s_star = 0.015 * 0.09 * std::log(0.09 / 0.015) / (0.09 - 0.015);
  EXPECT_NEAR(ca.peak_time(), s_star, 1e-12);
  EXPECT_NEAR(ca.value(t_act + s_star, t_act), 1.3, 1e-12);
  EXPECT_NEAR(ca.activation(t_act + s_star, t_act), 1.0, 1e-12);
  // It is the maximum: a fine grid never exceeds it, and its best point is at s*.
  double best = 0.0, at = 0.0;
  for (int i = 0; i <= 100000; ++i) {
    const double s = 0.2 * i / 100000;
    if (ca.value(t_act + s, t_act) > best) best = ca.value(t_act + s, t_act), at = s;
  }
  EXPECT_LE(best, 1.3 + 1e-15);
  EXPECT_NEAR(at, s_star, 2e-6);
  // Rest before activation, beats repeat every period.
  EXPECT_EQ(ca.value(t_act - 1e-3, t_act), 0.12);
  EXPECT_EQ(ca.value(t_act, t_act), 0.12);
  for (double s : {0.001, 0.02, 0.3, 0.79})
    for (int k : {1, 2, 5})
      EXPECT_NEAR(ca.value(t_act + s + k * 0.8, t_act), ca.value(t_act + s, t_act), 1e-12);
  EXPECT_EQ(ca.next_onset(0.0, t_act), t_act);
  EXPECT_NEAR(ca.next_onset(t_act + 0.1, t_act), t_act + 0.8, 1e-15);
  // One beat without a period: back towards rest, never below it.
  cp.period = 0.0;
  const CalciumTransient once(cp);
  EXPECT_LT(once.value(t_act + 1.6, t_act) - 0.12, 1e-6);
  EXPECT_GE(once.value(t_act + 1.6, t_act), 0.12);
}

TEST(PrescribedTension, TableInterpolatesAndHoldsItsEnds) {
  const json j = json::parse(R"({"model": "table", "table": [[0, 0], [0.1, 60e3], [0.4, 0]]})");
  SpecNode node(j, "/active", *cell_model_schema());
  const CellModelPtr m = make_cell_model(node);
  EXPECT_EQ(m->state_size(), 0);
  std::vector<double> none;
  auto Ta = [&](double t, double t_act) { return m->advance({t, kDt, t_act, 1.0, 0.0}, none, none).Ta; };
  EXPECT_DOUBLE_EQ(Ta(0.25, 0.0), 30e3);
  EXPECT_DOUBLE_EQ(Ta(0.05, 0.0), 30e3);
  EXPECT_DOUBLE_EQ(Ta(0.35, 0.1), 30e3);  // s = t − t_act
  EXPECT_EQ(Ta(0.1, 0.0), 60e3);
  EXPECT_EQ(Ta(-5.0, 0.0), 0.0);  // held before the first entry
  EXPECT_EQ(Ta(9.0, 0.0), 0.0);   // and after the last
  const json jh = json::parse(R"({"model": "table", "table": [[0.1, 5], [0.2, 7]]})");
  SpecNode held(jh, "/a", *cell_model_schema());
  const CellModelPtr h = make_cell_model(held);
  EXPECT_EQ(h->advance({0.0, kDt, 0.0, 1.0, 0.0}, none, none).Ta, 5.0);
  EXPECT_EQ(h->advance({0.3, kDt, 0.0, 1.0, 0.0}, none, none).Ta, 7.0);
  const json jc{{"model", "constant"}, {"Ta", 2.5e4}};
  SpecNode c(jc, "/a", *cell_model_schema());
  const ActiveTension k = make_cell_model(c)->advance({0.3, kDt, 0.0, 1.2, 3.0}, none, none);
  EXPECT_EQ(k.Ta, 2.5e4);
  EXPECT_EQ(k.dTa_dlambda, 0.0);
}

// ------------------------------------------------------------------------ the spec

/// make_cell_model's InputError text for `spec` at "/active" ("" if none).
std::string error_of(const std::string& spec) {
  try {
    const json j = json::parse(spec);  // SpecNode only points at it
    SpecNode node(j, "/active", *cell_model_schema());
    make_cell_model(node);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(CellModelSpec, BadValuesAreRefusedNamingTheKey) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {R"({"model": "land2017", "calcium": {"rise": 0.2, "decay": 0.1}})", "/active/calcium/rise"},
      {R"({"model": "bestel_clement_sorine", "calcium": {"rest": 0.5, "peak": 0.3}})",
       "/active/calcium/peak"},
      {R"({"model": "land2017", "calcium": {"decay": -0.1}})", "/active/calcium/decay"},
      {R"({"model": "land2017", "calcium": {"period": -1}})", "/active/calcium/period"},
      {R"({"model": "land2017", "calcium": {"peek": 1}})", "did you mean 'peak'"},
      {R"({"model": "land2017", "parameter_set": "frozen"})", "/active/parameter_set"},
      {R"({"model": "land2017", "k_u": -1})", "/active/k_u"},
      {R"({"model": "land2017", "k_ws": 500})", "/active/k_ws"},
      {R"({"model": "land2017", "r_s": 1.5})", "/active/r_s"},
      {R"({"model": "land2017", "k_TRPM": 100})", "did you mean 'k_TRPN'"},
      {R"({"model": "land2017", "max_substep": 0})", "/active/max_substep"},
      {R"({"model": "bestel_clement_sorine", "alpha_min": 3})", "/active/alpha_min"},
      {R"({"model": "bestel_clement_sorine", "alpha_max": -1})", "/active/alpha_max"},
      {R"({"model": "huxley"})", "/active/model"},
      {R"({"model": "constant"})", "/active/Ta"},
      {R"({"model": "constant", "Ta": -4})", "/active/Ta"},
      {R"({"model": "table"})", "/active/table"},
      {R"({"model": "table", "table": []})", "/active/table"},
      {R"({"model": "table", "table": [[0, 1], [0, 2]]})", "entry 1 has s = 0 not above"},
      {R"({"model": "table", "table": [[0, 1], [0.1]]})", "entry 1 is not a pair"},
      {R"({"model": "table", "table": [[0, 1], [0.1, -2]]})", "entry 1 has T_a < 0"},
      {R"({"model": "table", "table": [[0, 1]], "period": 1})", "unknown key 'period'"},
  };
  for (const auto& [spec, expected] : cases) {
    const std::string e = error_of(spec);
    EXPECT_NE(e.find(expected), std::string::npos) << spec << " gave: " << e;
  }
  EXPECT_NE(error_of(R"({"model": "land2017", "calcium": {"rise": 0.2, "decay": 0.1}})")
                .find("got 0.2"),
            std::string::npos);
}

TEST(CellModelSpec, ReaderAndSchemaAgreeOnEveryKey) {
  const Schema schema = cell_model_schema();
  const std::vector<std::string> specs = {
      R"({"model": "land2017", "parameter_set": "skinned", "T_ref": 4e4, "ca50_ref": 2.4,
          "TRPN_50": 0.35, "n_TRPN": 2, "k_TRPN": 100, "n_tm": 2.2, "k_u": 1000, "r_s": 0.25,
          "r_w": 0.5, "k_uw": 26, "k_ws": 4, "gamma_s": 8.5, "gamma_w": 615, "phi": 2.23,
          "A_eff": 25, "beta_0": 2.3, "beta_1": -2.4,
          "calcium": {"rest": 0.1, "peak": 1, "rise": 0.02, "decay": 0.11, "period": 1},
          "max_substep": 5e-5})",
      R"({"model": "bestel_clement_sorine", "sigma_0": 1e5, "alpha_max": 5, "alpha_min": -30,
          "calcium": {"rest": 0.1, "peak": 1, "rise": 0.02, "decay": 0.11, "period": 1},
          "max_substep": 1e-4})",
      R"({"model": "constant", "Ta": 1e4, "transverse_fraction": 0.2})",
      R"({"model": "table", "table": [[0, 0], [0.1, 1e4]]})"};
  SpecDoc doc;
  std::vector<json> held;  // the nodes point into these
  held.reserve(specs.size());
  for (const auto& s : specs) {
    held.push_back(json::parse(s));
    SpecNode node(held.back(), "/active", *schema, &doc);
    EXPECT_NO_THROW(read_active_stress(node)) << s;
  }
  // Every key of every branch (and of each calcium object) was read by some spec.
  int keys = 0;
  auto check = [&](const SchemaKeys& ks, const std::string& where) {
    for (const auto& [k, s] : ks) {
      ++keys;
      EXPECT_TRUE(doc.visited.count(s.get())) << where << "/" << k;
      for (const auto& [kk, ss] : s->keys) {
        ++keys;
        EXPECT_TRUE(doc.visited.count(ss.get())) << where << "/" << k << "/" << kk;
      }
    }
  };
  check(schema->keys, "");
  for (const auto& b : schema->branches) check(b.keys, b.value);
  EXPECT_EQ(keys, 2 + (1 + 17 + 1 + 5 + 1) + (3 + 1 + 5 + 1) + 1 + 1);
  EXPECT_EQ(schema->branches.size(), cell_model_names().size());

  // The reference and the JSON Schema render it (as the lead's spec-doc will).
  const std::string doc_text = spec_reference({{"active", schema.get()}});
  EXPECT_NE(doc_text.find("tau_rise"), std::string::npos);
  EXPECT_NE(doc_text.find("default: intact 120000, skinned 40500"), std::string::npos);
  const std::string js = to_json_schema(*schema, "x", "cell model").dump();
  EXPECT_NE(js.find("land2017"), std::string::npos);
  EXPECT_NE(js.find("prefixItems"), std::string::npos);
}

}  // namespace
}  // namespace fe2
