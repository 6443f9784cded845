// The element kernel (worker/micro_kernel.cpp) and the unit assembly into the fixed
// pattern (MicroUnit::assemble_at) against the straightforward reference they
// replaced: the explicit 9×24 B̃ of each Gauss point, K = Σ ω B̃ᵀ𝔸B̃ etc. as dense
// products, and K assembled from element triplets with setFromTriplets.
#include "common/materials/Myocardium.h"
#include "common/materials/NeoHookean.h"
#include "tests/worker/unit_fixtures.h"
#include "worker/micro_kernel.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <random>

namespace fe2 {
namespace {

using Mat9x24 = Eigen::Matrix<double, 9, 24>;

/// B̃ at Gauss point q: (B̃w)_iJ = Σ_a w_ai ∂N_a/∂X_J, rows iJ = i + 3J, columns 8i + a.
Mat9x24 b_tilde(const HexGeometry& geo, int q) {
  Mat9x24 B = Mat9x24::Zero();
  for (int i = 0; i < 3; ++i)
    for (int J = 0; J < 3; ++J)
      for (int a = 0; a < 8; ++a) B(index9(i, J), hex_local(i, a)) = geo.grad[q](J, a);
  return B;
}

/// The reference kernel: dense products of B̃ (no symmetry, no reordering).
HexContribution reference(const HexGeometry& geo, double inv_volume,
                          const Eigen::Matrix<double, 3, 8>& w_e, const Vec9& Zbar,
                          const Material& m, const HexPointContext* point) {
  HexContribution out;
  out.K.setZero();
  out.r.setZero();
  out.H.setZero();
  out.G.setZero();
  out.Abar.setZero();
  out.Pbar.setZero();
  Eigen::Matrix<double, 24, 1> w;
  for (int i = 0; i < 3; ++i)
    for (int a = 0; a < 8; ++a) w[hex_local(i, a)] = w_e(i, a);
  for (int q = 0; q < 8; ++q) {
    const Mat9x24 B = b_tilde(geo, q);
    const double omega = geo.weight[q] * inv_volume;
    const Vec9 Z = Zbar + B * w;
    Vec9 Pi;
    Mat9 A, A_rate = Mat9::Zero(), A_Z;
    if (point) {
      Eigen::Matrix<double, 24, 1> wdot;
      for (int i = 0; i < 3; ++i)
        for (int a = 0; a < 8; ++a) wdot[hex_local(i, a)] = point->w_dot_e(i, a);
      const MaterialPointContext context{point->time, point->dt, point->Zbar_dot + B * wdot,
                                         point->activation_time};
      m.stress_and_tangent_at(Z, context, PointHistory{}, Pi, A, A_rate);
      A_Z = A + point->Zbar_dot_coefficient * A_rate;
      A += A_rate / point->dt;
    } else {
      m.stress_and_tangent(Z, Pi, A);
      A_Z = A;
    }
    out.K += omega * B.transpose() * A * B;
    out.r += omega * B.transpose() * Pi;
    out.H += omega * A * B;
    out.G += omega * B.transpose() * A_Z;
    out.Abar += omega * A_Z;
    out.Pbar += omega * Pi;
  }
  return out;
}

/// A hexahedron with its nodes moved off the grid, so that ∇N differs at every point.
HexGeometry distorted_hex() {
  HexMesh mesh;
  const double x[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                          {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-0.15, 0.15);
  for (const auto& p : x) mesh.nodes.push_back(Vec3(0.3 * (p[0] + u(rng)), 0.2 * (p[1] + u(rng)), 0.25 * (p[2] + u(rng))));
  mesh.hexes.push_back({0, 1, 2, 3, 4, 5, 6, 7});
  mesh.region.push_back(0);
  return hex_geometry(mesh, 0);
}

double rel(const Eigen::Ref<const Eigen::MatrixXd>& a, const Eigen::Ref<const Eigen::MatrixXd>& b) {
  return (a - b).cwiseAbs().maxCoeff() / b.cwiseAbs().maxCoeff();
}

constexpr double kTol = 1e-13;  // relative to the largest entry: round-off of ≈ 100 terms

struct KernelCase {
  Eigen::Matrix<double, 3, 8> w_e;
  Vec9 Zbar;
};

KernelCase random_state(unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  KernelCase c;
  for (int i = 0; i < 3; ++i)
    for (int a = 0; a < 8; ++a) c.w_e(i, a) = 0.01 * u(rng);
  for (int k = 0; k < 9; ++k) c.Zbar[k] = 0.05 * u(rng);
  return c;
}

TEST(MicroKernel, SymmetricPathMatchesDenseReference) {
  const HexGeometry geo = distorted_hex();
  const NeoHookean law(2.0e4, 0.45);
  for (unsigned seed : {1u, 2u, 3u}) {
    const KernelCase s = random_state(seed);
    HexContribution c;
    hex_contribution(geo, 1.7, s.w_e, s.Zbar, law, /*need_G=*/false, c);
    const HexContribution ref = reference(geo, 1.7, s.w_e, s.Zbar, law, nullptr);
    EXPECT_LT(rel(c.K, ref.K), kTol) << "seed " << seed;
    EXPECT_LT(rel(c.r, ref.r), kTol);
    EXPECT_LT(rel(c.H, ref.H), kTol);
    EXPECT_LT(rel(c.Abar, ref.Abar), kTol);
    EXPECT_LT(rel(c.Pbar, ref.Pbar), kTol);
    // The mirrored blocks are exact transposes; the reference K is symmetric to round-off.
    const Eigen::Matrix<double, 8, 8> lower = c.K.block<8, 8>(16, 0), upper = c.K.block<8, 8>(0, 16);
    EXPECT_TRUE(lower == upper.transpose());
    EXPECT_GT(ref.K.norm(), 1.0);  // the comparison is about something
  }
}

TEST(MicroKernel, UnsymmetricPathWithContextMatchesDenseReference) {
  // Kelvin–Voigt viscosity: a law that reads Ż and Δt, whose 𝔸 toward w and toward Z̄
  // differ, through the path that computes all nine K blocks and G.
  const HexGeometry geo = distorted_hex();
  const Myocardium law(std::make_shared<NeoHookean>(2.0e4, 0.45), MyocardiumOptions{nullptr, 0.0, 30.0});
  ASSERT_TRUE(law.rate_dependent());
  const KernelCase s = random_state(11);
  HexPointContext point;
  point.time = 0.2;
  point.dt = 5e-3;
  point.Zbar_dot = random_state(12).Zbar;
  point.Zbar_dot_coefficient = 150.0;
  point.w_dot_e = random_state(13).w_e;
  HexContribution c;
  hex_contribution(geo, 0.9, s.w_e, s.Zbar, law, /*need_G=*/true, c, &point);
  const HexContribution ref = reference(geo, 0.9, s.w_e, s.Zbar, law, &point);
  EXPECT_LT(rel(c.K, ref.K), kTol);
  EXPECT_LT(rel(c.G, ref.G), kTol);
  EXPECT_LT(rel(c.H, ref.H), kTol);
  EXPECT_LT(rel(c.r, ref.r), kTol);
  EXPECT_LT(rel(c.Abar, ref.Abar), kTol);
  EXPECT_LT(rel(c.Pbar, ref.Pbar), kTol);
  EXPECT_GT(rel(ref.G, Eigen::MatrixXd(ref.H.transpose())), 1e-3);  // G ≠ Hᵀ here
}

TEST(MicroKernel, AssemblyMatchesTripletReference) {
  // assemble_at scatters through the model's element-to-nonzero map (with the pinned
  // node's entries skipped); the reference assembles the reference kernel's element
  // matrices as triplets, the pinned equations dropped.
  const MicroModelPtr model = test::two_cell_model({}, {5, 3, 3});
  MicroUnit unit(model);
  const int n = model->num_dofs();
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Vec w(n);
  for (int k = 0; k < n; ++k) w[k] = 1e-3 * u(rng);
  const Vec9 Zbar = test::gradient({0.04, 0.01, -0.01, 0.02, -0.02, 0.0, 0.01, 0.0, -0.03});
  MicroUnit::System sys;
  sys.K = model->zero_matrix();  // what units assemble into
  unit.assemble_at(w, Zbar, sys);

  std::vector<Eigen::Triplet<double>> trip;
  Vec r = Vec::Zero(n);
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(9, n);
  int pinned_elements = 0;
  for (int e = 0; e < model->num_elements(); ++e) {
    const auto& eq = model->element_equations(e);
    Eigen::Matrix<double, 3, 8> w_e;
    for (int i = 0; i < 3; ++i)
      for (int a = 0; a < 8; ++a) w_e(i, a) = eq[hex_local(i, a)] >= 0 ? w[eq[hex_local(i, a)]] : 0.0;
    const HexContribution c = reference(model->geometry(e), model->inv_volume(), w_e, Zbar,
                                        model->material_of(e), nullptr);
    pinned_elements += std::count(eq.begin(), eq.end(), -1) > 0;
    for (int l = 0; l < 24; ++l) {
      if (eq[l] < 0) continue;
      r[eq[l]] += c.r[l];
      H.col(eq[l]) += c.H.col(l);
      for (int k = 0; k < 24; ++k)
        if (eq[k] >= 0) trip.emplace_back(eq[l], eq[k], c.K(l, k));
    }
  }
  EXPECT_EQ(pinned_elements, 8);  // the pinned node's branch was exercised
  SparseMatrix K(n, n);
  K.setFromTriplets(trip.begin(), trip.end());
  const Eigen::MatrixXd Kd = K, Kunit = sys.K;
  EXPECT_EQ(sys.K.nonZeros(), K.nonZeros());
  EXPECT_LT(rel(Kunit, Kd), kTol);
  EXPECT_LT(rel(sys.r, r), kTol);
  EXPECT_LT(rel(sys.H, H), kTol);
  EXPECT_LT(rel(sys.G, Eigen::MatrixXd(H.transpose())), kTol);
}

TEST(MicroKernel, AssemblyIsBitForBitRepeatable) {
  // Same inputs, same bits: a second assembly into a fresh system, and into the same
  // system again (nothing left over from the previous values).
  const MicroModelPtr model = test::two_cell_model({}, {5, 3, 3});
  MicroUnit unit(model);
  Vec w = Vec::LinSpaced(model->num_dofs(), -1e-3, 2e-3);
  const Vec9 Zbar = test::gradient({0.05, 0, 0, 0, 0, 0, 0, 0, 0});
  MicroUnit::System a, b;
  a.K = model->pattern();
  b.K = model->pattern();
  unit.assemble_at(w, Zbar, a);
  unit.assemble_at(w, Zbar, b);
  unit.assemble_at(w, Zbar, b);
  EXPECT_EQ(0, std::memcmp(a.K.valuePtr(), b.K.valuePtr(), sizeof(double) * a.K.nonZeros()));
  EXPECT_EQ(a.r, b.r);
  EXPECT_EQ(a.H, b.H);
  EXPECT_EQ(a.G, b.G);
  EXPECT_EQ(a.Pbar, b.Pbar);
}

}  // namespace
}  // namespace fe2
