// Womersley flow (J Physiol 127:553, 1955): the exact oscillating flow in a rigid pipe of
// radius R under the pressure gradient −∂p/∂z = Re[Ĝ e^{iωt}], with Λ = i^{3/2} α and
// α = R √(ωρ/μ) (the Womersley number):
//   v_z(r, t) = Re[ Ĝ/(iωρ) (1 − J0(Λ r/R)/J0(Λ)) e^{iωt} ]
//   Q(t)      = Re[ Ĝ πR²/(iωρ) (1 − 2 J1(Λ)/(Λ J0(Λ))) e^{iωt} ]
// on the shipped tube (configs/meshes/tube.msh: R = 1 mm, L = 6 mm, quadratic), blood,
// period 0.2 s (α = 3.1), started from the exact profile, one period of 40 BDF2 steps:
// the flux's amplitude and phase against the Bessel-function solution.
#include "tests/coordinator/fluid_fixtures.h"
#include "tests/coordinator/scene_fixtures.h"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>

namespace fe2 {
namespace {

using cd = std::complex<double>;

/// J_n(z) for n = 0, 1 by the power series (|z| up to ~10: plenty of terms).
cd bessel_j(int n, cd z) {
  const cd q = -z * z / 4.0;
  cd term = n == 0 ? cd(1.0) : z / 2.0, sum = term;
  for (int k = 1; k < 60; ++k) {
    term *= q / (static_cast<double>(k) * (k + n));
    sum += term;
  }
  return sum;
}

struct Womersley {
  double rho = 1.06e-3, mu = 3.5e-3, R = 1.0, L = 6.0, period = 0.2, dP = 20.0;
  double omega() const { return 2 * M_PI / period; }
  double alpha() const { return R * std::sqrt(omega() * rho / mu); }
  cd Lambda() const { return std::pow(cd(0, 1), 1.5) * alpha(); }
  cd G() const { return dP / L; }  // inlet pressure dP cos ωt, outlet 0
  double vz(double r, double t) const {
    const cd v = G() / (cd(0, 1) * omega() * rho) * (1.0 - bessel_j(0, Lambda() * r / R) / bessel_j(0, Lambda()));
    return (v * std::exp(cd(0, omega() * t))).real();
  }
  cd Q_hat() const {
    const cd L0 = Lambda();
    return G() * M_PI * R * R / (cd(0, 1) * omega() * rho) * (1.0 - 2.0 * bessel_j(1, L0) / (L0 * bessel_j(0, L0)));
  }
};

// 23 s on one core: label long (`ctest -L long -R Womersley`), outside CI's budget.
TEST(LongFluidWomersley, OscillatingPipeFlowHasTheBesselSolutionsAmplitudeAndPhase) {
  const Womersley w;
  const int steps = 40;
  const json j = {
      {"mesh", {{"kind", "gmsh"}, {"file", std::string(FE2_SOURCE_DIR) + "/configs/meshes/tube.msh"},
                {"wall_regions", {"wall"}}}},
      {"models", {{"wall", {{"kind", "macro_law"}, {"material", test::nh(1e6, 0.3)}}}}},
      {"dirichlet", {{{"set", "wall_inlet"}}, {{"set", "wall_outlet"}}}},
      {"time", {{"t_end", w.period}, {"steps", steps}}},
      {"newton", {{"rtol", 1e-10}, {"max_iterations", 12}}},
      {"output", {{"vtu", false}}}};
  RunSpec spec = read_run_spec(j, "");
  FluidSetup s;
  for (const auto& [tag, name] : spec.mesh.region_names)
    if (name == "blood") s.regions = {tag};
  ASSERT_EQ(s.regions.size(), 1u);
  s.fluid = {w.rho, w.mu};
  s.element = FluidElementKind::taylor_hood;
  s.time = TimeScheme::bdf2;
  s.rtol = 1e-10;
  s.initial_velocity = [w](const Vec3& X) { return Vec3(0, 0, w.vz(std::hypot(X.x(), X.y()), 0.0)); };
  s.boundaries.push_back(FluidBoundary::no_slip("lumen"));
  s.boundaries.push_back(FluidBoundary::no_slip("inlet", {true, true, false}));
  s.boundaries.push_back(FluidBoundary::no_slip("outlet", {true, true, false}));
  s.boundaries.push_back(FluidBoundary::pressure("inlet", [w](double t) { return w.dP * std::cos(w.omega() * t); }));
  s.boundaries.push_back(FluidBoundary::pressure("outlet", [](double) { return 0.0; }));
  test::FluidSimulation f(spec, s);
  const RunResult r = f.sim.run();
  ASSERT_TRUE(r.converged) << r.error;
  // Least squares Q_h(t) ≈ a cos ωt + b sin ωt over the period: Q̂_h = a − i b.
  Eigen::MatrixXd A(steps, 2);
  Eigen::VectorXd q(steps);
  for (int k = 0; k < steps; ++k) {
    const StepRecord& h = r.history[static_cast<size_t>(k)];
    A(k, 0) = std::cos(w.omega() * h.time);
    A(k, 1) = std::sin(w.omega() * h.time);
    q[k] = -1.0;
    for (const auto& [name, value] : h.observables)
      if (name == "flux:outlet") q[k] = value;
  }
  const Eigen::Vector2d ab = A.colPivHouseholderQr().solve(q);
  const cd Q_h(ab[0], -ab[1]), Q = w.Q_hat();
  std::printf("Womersley α = %.2f: |Q̂| %.3f (exact %.3f), phase %.4f rad (exact %.4f); fit residual %.2e\n",
              w.alpha(), std::abs(Q_h), std::abs(Q), std::arg(Q_h), std::arg(Q), (A * ab - q).norm() / q.norm());
  // 40 BDF2 steps a period (ωΔt = 0.16) and the polygonal lumen: 2 % and 0.03 rad.
  EXPECT_NEAR(std::abs(Q_h) / std::abs(Q), 1.0, 0.02);
  EXPECT_NEAR(std::arg(Q_h), std::arg(Q), 0.03);
  // The flow lags the pressure (inertia): by more than a tenth of a radian at α = 3.
  EXPECT_LT(std::arg(Q), -0.1);
}

}  // namespace
}  // namespace fe2
