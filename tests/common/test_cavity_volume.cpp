// Cavity volume of a deformed endocardium (common/mesh/cavity_volume.h): exact on boxes,
// convergent on the LV, translation invariant, and its derivative against finite differences.
#include "common/error.h"
#include "common/mesh/box_mesh.h"
#include "common/mesh/cavity_volume.h"
#include "common/mesh/lv_mesh.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace fe2 {
namespace {

/// Analytic volume of the prolate ellipsoid (x² + y²)/a² + z²/c² <= 1 below z = z_cut:
/// ∫_{-c}^{z_cut} π a² (1 - z²/c²) dz = π a² [(z_cut + c) - (z_cut³ + c³)/(3c²)].
double cap_volume(double a, double c, double z_cut) {
  return M_PI * a * a * ((z_cut + c) - (z_cut * z_cut * z_cut + c * c * c) / (3 * c * c));
}

TetMesh lv_mesh(int nc, int nl, int order) {
  LvMeshParams p;
  p.circumferential = nc;
  p.longitudinal = nl;
  p.transmural = 1;
  p.order = order;
  return make_lv_mesh(p);
}

Eigen::VectorXd random_displacement(int num_nodes, double scale, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uni(-scale, scale);
  Eigen::VectorXd u(3 * num_nodes);
  for (Eigen::Index i = 0; i < u.size(); ++i) u[i] = uni(rng);
  return u;
}

Eigen::VectorXd dense(const CavityVolume& cv, int num_nodes) {
  Eigen::VectorXd g = Eigen::VectorXd::Zero(3 * num_nodes);
  int last = -1;
  for (const auto& [dof, value] : cv.dV_du) {
    EXPECT_GT(dof, last) << "dofs ascending, each once";
    last = dof;
    g[dof] = value;
  }
  return g;
}

TEST(CavityVolume, ABoxSurfaceEnclosesMinusTheBoxVolumeClosedOrCapped) {
  for (int order : {1, 2}) {
    TetMesh m = make_box_mesh(Vec3(0, 0, 0), Vec3(2, 3, 4), {2, 3, 2}, -1, 1, order);
    // Faces point out of the box, so the "cavity" they wrap is the box turned inside out.
    auto& all = m.faces["all"];
    auto& open = m.faces["open"];
    for (const auto& [name, tris] : m.faces)
      if (name != "all" && name != "open") {
        all.insert(all.end(), tris.begin(), tris.end());
        if (name != "zmax") open.insert(open.end(), tris.begin(), tris.end());
      }
    // Shifted off the origin and sheared: the result must not depend on where the body is.
    Eigen::VectorXd u(3 * m.num_nodes());
    for (int n = 0; n < m.num_nodes(); ++n) u.segment<3>(3 * n) = Vec3(5 + 0.1 * m.nodes[n].z(), -7, 11);
    EXPECT_NEAR(cavity_volume(m, "all", u).volume, -24.0, 1e-12);
    EXPECT_NEAR(cavity_volume(m, "open", u).volume, -24.0, 1e-12);  // capped by the fan at zmax
  }
}

TEST(CavityVolume, UndeformedLvConvergesToTheTruncatedEllipsoid) {
  const LvMeshParams d;
  const double exact = cap_volume(d.endo_short, d.endo_long, d.base_z);
  for (int order : {1, 2}) {
    std::vector<double> err;
    for (int r : {1, 2, 4}) {
      const TetMesh m = lv_mesh(8 * r, 4 * r, order);
      err.push_back(std::abs(cavity_volume(m, "endo", Eigen::VectorXd::Zero(3 * m.num_nodes())).volume - exact) /
                    exact);
    }
    const double p1 = std::log2(err[0] / err[1]), p2 = std::log2(err[1] / err[2]);
    std::printf("cavity volume (exact %.6f mm^3), order %d: relative errors %.3e %.3e %.3e, observed orders %.2f %.2f\n",
                exact, order, err[0], err[1], err[2], p1, p2);
    if (order == 1) {
      EXPECT_NEAR(p2, 2.0, 0.15);
    } else {
      EXPECT_GT(p2, 3.7);
      EXPECT_LT(err[2], 1e-5);
    }
  }
}

TEST(CavityVolume, DerivativeEqualsCentralDifferences) {
  for (int order : {1, 2}) {
    SCOPED_TRACE(order);
    const TetMesh m = lv_mesh(8, 4, order);
    const Eigen::VectorXd u = random_displacement(m.num_nodes(), 0.5, 17);
    const CavityVolume cv = cavity_volume(m, "endo", u);
    EXPECT_GT(cv.volume, 500.0);
    const Eigen::VectorXd g = dense(cv, m.num_nodes());
    const double h = 1e-4, scale = g.cwiseAbs().maxCoeff();
    double worst = 0.0;
    for (Eigen::Index i = 0; i < u.size(); ++i) {
      Eigen::VectorXd up = u, um = u;
      up[i] += h;
      um[i] -= h;
      const double fd = (cavity_volume(m, "endo", up).volume - cavity_volume(m, "endo", um).volume) / (2 * h);
      worst = std::max(worst, std::abs(fd - g[i]) / scale);
    }
    std::printf("dV/du, order %d: max |FD - analytic| / max |dV/du| = %.2e (max |dV/du| = %.3f)\n", order, worst,
                scale);
    EXPECT_LT(worst, 1e-7);
  }
}

TEST(CavityVolume, InvariantToARigidTranslation) {
  for (int order : {1, 2}) {
    SCOPED_TRACE(order);
    const TetMesh m = lv_mesh(8, 4, order);
    const Eigen::VectorXd u = random_displacement(m.num_nodes(), 0.5, 5);
    Eigen::VectorXd shifted = u;
    for (int n = 0; n < m.num_nodes(); ++n) shifted.segment<3>(3 * n) += Vec3(3.0, -40.0, 12.5);
    const CavityVolume a = cavity_volume(m, "endo", u), b = cavity_volume(m, "endo", shifted);
    EXPECT_NEAR(b.volume, a.volume, 1e-12 * a.volume);
    // The derivative form of the same fact: Σ_nodes ∂V/∂u_i = 0 for each direction i.
    const Eigen::VectorXd g = dense(a, m.num_nodes());
    for (int i = 0; i < 3; ++i) {
      double sum = 0.0;
      for (int n = 0; n < m.num_nodes(); ++n) sum += g[3 * n + i];
      EXPECT_NEAR(sum, 0.0, 1e-12 * g.cwiseAbs().sum()) << "direction " << i;
    }
  }
}

TEST(CavityVolume, BadInputNamesTheFaceOrTheSize) {
  const TetMesh m = lv_mesh(4, 2, 1);
  try {
    cavity_volume(m, "lv_endo", Eigen::VectorXd::Zero(3 * m.num_nodes()));
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("face 'lv_endo': expected a named face of the mesh (base, endo, epi)"),
              std::string::npos)
        << e.what();
  }
  EXPECT_THROW(cavity_volume(m, "endo", Eigen::VectorXd::Zero(5)), InputError);
}

}  // namespace
}  // namespace fe2
