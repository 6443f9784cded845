// The shipped idealized biventricular mesh (configs/meshes/biv_coarse.msh, made by
// `tools/meshes/biv_mesh.py configs/meshes/biv_coarse.msh --size 2.5 --order 2`) reads with the repo's Gmsh reader, has the named surfaces,
// and its wall and cavity volumes agree with the ellipsoids it was built from.
#include "common/fem/lagrange_tet.h"
#include "common/mesh/cavity_volume.h"
#include "common/mesh/gmsh_reader.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

namespace fe2 {
namespace {

// The ellipsoids of tools/meshes/biv_mesh.py (keep in step): centre x, semi-axes x, y, z.
struct Ellipsoid {
  double cx, ax, ay, az;
  bool inside(double x, double y, double z) const {
    return ((x - cx) / ax) * ((x - cx) / ax) + (y / ay) * (y / ay) + (z / az) * (z / az) < 1.0;
  }
};
constexpr double kBaseZ = 5.0;
constexpr Ellipsoid kLvEndo{0, 7, 7, 17}, kLvEpi{0, 10, 10, 20}, kRvEndo{4, 12, 10, 15}, kRvEpi{4, 15, 13, 18};

/// Midpoint-rule volumes on a 0.2 mm grid of the wall and of the RV cavity, from the
/// definition solid = (LV_epi ∪ RV_epi) − LV_endo − (RV_endo − LV_epi), z < base.
void reference_volumes(double& wall, double& rv_cavity) {
  const double h = 0.2;
  wall = rv_cavity = 0.0;
  for (double z = -20.0 + h / 2; z < kBaseZ; z += h)
    for (double y = -13.0 + h / 2; y < 13.0; y += h)
      for (double x = -10.0 + h / 2; x < 19.0; x += h) {
        const bool lv_epi = kLvEpi.inside(x, y, z), rv_cav = kRvEndo.inside(x, y, z) && !lv_epi;
        rv_cavity += rv_cav;
        wall += (lv_epi || kRvEpi.inside(x, y, z)) && !kLvEndo.inside(x, y, z) && !rv_cav;
      }
  wall *= h * h * h;
  rv_cavity *= h * h * h;
}

TEST(BivMesh, ShippedMeshReadsWithNamedSurfacesAndSaneVolumes) {
  const std::filesystem::path file = std::filesystem::path(FE2_SOURCE_DIR) / "configs/meshes/biv_coarse.msh";
  EXPECT_LT(std::filesystem::file_size(file), 1000000u);
  const TetMesh m = read_gmsh_tets(file.string());
  for (const char* name : {"lv_endo", "rv_endo", "epi", "base"}) {
    ASSERT_TRUE(m.faces.count(name)) << name;
    EXPECT_GE(m.faces.at(name).size(), 20u) << name;
  }
  ASSERT_EQ(m.region_names.size(), 1u);
  EXPECT_EQ(m.region_names.begin()->second, "myocardium");

  double wall = 0.0, min_tet = 1e300;
  for (int e = 0; e < m.num_tets(); ++e) {
    wall += tet_signed_volume(m, e);
    min_tet = std::min(min_tet, tet_signed_volume(m, e));
  }
  EXPECT_GT(min_tet, 0.0);
  for (const auto& tri : m.faces.at("base")) {  // flat and outward: +z
    const Vec3 n = (m.nodes[tri[1]] - m.nodes[tri[0]]).cross(m.nodes[tri[2]] - m.nodes[tri[0]]);
    ASSERT_GT(n.normalized().z(), 1.0 - 1e-9);
  }

  double ref_wall = 0.0, ref_rv = 0.0;
  reference_volumes(ref_wall, ref_rv);
  // LV cavity: the truncated ellipsoid π a² [(z_b + c) − (z_b³ + c³)/(3c²)], a = 7, c = 17.
  const double ref_lv = M_PI * 49.0 * ((kBaseZ + 17.0) - (std::pow(kBaseZ, 3) + std::pow(17.0, 3)) / (3 * 289.0));
  const Eigen::VectorXd u = Eigen::VectorXd::Zero(3 * m.num_nodes());
  const double lv = cavity_volume(m, "lv_endo", u).volume, rv = cavity_volume(m, "rv_endo", u).volume;
  std::printf("biv_coarse: %d nodes, %d tets; wall %.1f (reference %.1f), LV cavity %.1f (%.1f), "
              "RV cavity %.1f (%.1f) mm^3\n",
              m.num_nodes(), m.num_tets(), wall, ref_wall, lv, ref_lv, rv, ref_rv);
  ASSERT_EQ(m.order(), 2);
  // The cavities use the curved 6-node triangles (within the grid reference's ~0.2 %);
  // the wall sums straight-sided tets, which misses the curvature by a little more.
  EXPECT_NEAR(lv / ref_lv, 1.0, 0.003);
  EXPECT_NEAR(rv / ref_rv, 1.0, 0.005);
  EXPECT_NEAR(wall / ref_wall, 1.0, 0.02);

  // Curved (quadratic) elements must not fold: det J > 0 at every point the solver
  // integrates at (the 4 unit points, and the degree-4 rule of mass and pressure terms).
  // Without Gmsh's high-order untangling a septal element did (det J = −1.2).
  Eigen::VectorXd N;
  Eigen::Matrix<double, 3, Eigen::Dynamic> dN;
  double worst = 1e300;
  for (int e = 0; e < m.num_tets(); ++e) {
    const auto nodes = m.element_nodes(e);
    for (int degree : {2, 4})
      for (const auto& q : tet_rule(degree)) {
        tet_shape(2, q.bary, N, dN);
        Mat3 J = Mat3::Zero();
        for (size_t a = 0; a < nodes.size(); ++a) J += m.nodes[nodes[a]] * dN.col(a).transpose();
        worst = std::min(worst, J.determinant() / (6.0 * tet_signed_volume(m, e)));
      }
  }
  std::printf("biv_coarse: smallest det J / straight-sided det J at a quadrature point: %.3f\n", worst);
  EXPECT_GT(worst, 0.05);
}

}  // namespace
}  // namespace fe2
