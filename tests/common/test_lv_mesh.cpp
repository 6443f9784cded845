// The LV generator (common/mesh/lv_mesh.h): topology, named faces and apex sets, curved
// quadratic geometry, and the wall volume against the analytic truncated-ellipsoid shell.
#include "common/error.h"
#include "common/mesh/cavity_volume.h"
#include "common/mesh/element_quality.h"
#include "common/mesh/lv_mesh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>

namespace fe2 {
namespace {

/// Analytic volume of the prolate ellipsoid (x² + y²)/a² + z²/c² <= 1 below z = z_cut:
/// ∫_{-c}^{z_cut} π a² (1 - z²/c²) dz = π a² [(z_cut + c) - (z_cut³ + c³)/(3c²)].
double cap_volume(double a, double c, double z_cut) {
  return M_PI * a * a * ((z_cut + c) - (z_cut * z_cut * z_cut + c * c * c) / (3 * c * c));
}

LvMeshParams lv(int nc, int nl, int nt, int order) {
  LvMeshParams p;
  p.circumferential = nc;
  p.longitudinal = nl;
  p.transmural = nt;
  p.order = order;
  return p;
}

// (x² + y²)/a² + z²/c² - 1: zero on the ellipsoid, its gradient points outward.
double level(const Vec3& x, double a, double c) {
  return (x.x() * x.x() + x.y() * x.y()) / (a * a) + x.z() * x.z() / (c * c) - 1.0;
}
Vec3 level_gradient(const Vec3& x, double a, double c) {
  return {2 * x.x() / (a * a), 2 * x.y() / (a * a), 2 * x.z() / (c * c)};
}

/// Volume of a 10-node tet: ∫ det J over the reference tet, exactly (det J is cubic),
/// with Stroud's 5-point degree-3 rule; also the smallest det J met (at the points and
/// the 4 vertices) in min_det.
double quadratic_tet_volume(const TetMesh& m, int e, double& min_det) {
  const auto n = m.element_nodes(e);
  std::array<Vec3, 10> X;
  for (int a = 0; a < 10; ++a) X[a] = m.nodes[n[a]];
  const auto jac_det = [&](double r, double s, double t) {
    const double L[4] = {1 - r - s - t, r, s, t};
    const double dL[4][3] = {{-1, -1, -1}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    Eigen::Matrix3d J = Eigen::Matrix3d::Zero();
    for (int a = 0; a < 4; ++a)
      for (int d = 0; d < 3; ++d) J.col(d) += (4 * L[a] - 1) * dL[a][d] * X[a];
    for (int k = 0; k < 6; ++k) {
      const int a = kTetEdges[k][0], b = kTetEdges[k][1];
      for (int d = 0; d < 3; ++d) J.col(d) += 4 * (dL[a][d] * L[b] + L[a] * dL[b][d]) * X[4 + k];
    }
    return J.determinant();
  };
  double v = -0.8 * jac_det(0.25, 0.25, 0.25) / 6.0;
  min_det = jac_det(0.25, 0.25, 0.25);
  const double p[4][3] = {{1. / 6, 1. / 6, 1. / 6}, {0.5, 1. / 6, 1. / 6}, {1. / 6, 0.5, 1. / 6}, {1. / 6, 1. / 6, 0.5}};
  for (const auto& q : p) {
    const double d = jac_det(q[0], q[1], q[2]);
    v += 0.45 * d / 6.0;
    min_det = std::min(min_det, d);
  }
  for (const auto& q : {std::array<double, 3>{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}})
    min_det = std::min(min_det, jac_det(q[0], q[1], q[2]));
  return v;
}

double wall_volume(const TetMesh& m) {
  double v = 0.0, min_det = 0.0;
  for (int e = 0; e < m.num_tets(); ++e) v += m.order() == 1 ? tet_signed_volume(m, e) : quadratic_tet_volume(m, e, min_det);
  return v;
}

TEST(LvMesh, CountsConformityAndPositiveTets) {
  const int nc = 12, nl = 5, nt = 3;
  const TetMesh m = make_lv_mesh(lv(nc, nl, nt, 1));
  EXPECT_EQ(m.num_nodes(), (nt + 1) * (1 + nc * nl));
  // 6 tets per cell, 3 of them flat (dropped) in each apex cell.
  EXPECT_EQ(m.num_tets(), 6 * nc * nl * nt - 3 * nc * nt);
  for (int e = 0; e < m.num_tets(); ++e) ASSERT_GT(tet_signed_volume(m, e), 1e-6) << "tet " << e;
  // Conforming: every face has 1 or 2 tets, and those with 1 are exactly the named faces.
  std::map<std::array<int, 3>, int> count;
  for (const auto& t : m.tets)
    for (int opp = 0; opp < 4; ++opp) {
      std::array<int, 3> f{};
      for (int a = 0, k = 0; a < 4; ++a)
        if (a != opp) f[k++] = t[a];
      std::sort(f.begin(), f.end());
      ++count[f];
    }
  int boundary = 0;
  for (const auto& [f, c] : count) {
    ASSERT_LE(c, 2);
    boundary += c == 1;
  }
  EXPECT_EQ(boundary, static_cast<int>(m.faces.at("endo").size() + m.faces.at("epi").size() +
                                       m.faces.at("base").size()));
  EXPECT_EQ(m.faces.at("endo").size(), std::size_t(2 * nc * nl - nc));
  EXPECT_EQ(m.faces.at("base").size(), std::size_t(2 * nc * nt));
  // Deterministic: a second call gives the same mesh bit for bit.
  const TetMesh again = make_lv_mesh(lv(nc, nl, nt, 1));
  EXPECT_EQ(again.tets, m.tets);
  EXPECT_EQ(again.nodes, m.nodes);
}

TEST(LvMesh, NamedFacesAreOutwardAndOnTheirSurfaces) {
  for (int order : {1, 2}) {
    SCOPED_TRACE(order);
    const LvMeshParams p = lv(10, 6, 2, order);
    const TetMesh m = make_lv_mesh(p);
    ASSERT_EQ(m.order(), order);
    // Normals: endo into the cavity (against the ellipsoid's outward gradient), epi outward, base +z.
    for (const auto& [name, sign] : std::map<std::string, double>{{"endo", -1}, {"epi", 1}, {"base", 0}})
      for (const auto& tri : m.faces.at(name)) {
        const Vec3 &x0 = m.nodes[tri[0]], &x1 = m.nodes[tri[1]], &x2 = m.nodes[tri[2]];
        const Vec3 n = (x1 - x0).cross(x2 - x0).normalized(), mid = (x0 + x1 + x2) / 3.0;
        if (name == "base")
          ASSERT_NEAR(n.z(), 1.0, 1e-12);
        else
          ASSERT_GT(sign * n.dot(level_gradient(mid, name == "endo" ? p.endo_short : p.epi_short,
                                                name == "endo" ? p.endo_long : p.epi_long).normalized()),
                    0.5);
      }
    // Every node of a face set (edge nodes too) lies on its surface: the quadratic mesh is curved.
    const auto& endo = m.node_sets.at("endo");
    const auto& epi = m.node_sets.at("epi");
    for (int n : endo) ASSERT_NEAR(level(m.nodes[n], p.endo_short, p.endo_long), 0.0, 1e-12) << "node " << n;
    for (int n : epi) ASSERT_NEAR(level(m.nodes[n], p.epi_short, p.epi_long), 0.0, 1e-12) << "node " << n;
    for (int n : m.node_sets.at("base")) ASSERT_EQ(m.nodes[n].z(), p.base_z) << "node " << n;
    // Face sets hold the edge nodes for order 2: vertices + edges of the endo triangulation.
    const std::size_t vertices = 1 + 10 * 6, edges = 3 * (2 * 10 * 6 - 10) / 2 + 10 / 2;
    EXPECT_EQ(endo.size(), order == 1 ? vertices : vertices + edges);
    // Apex sets: one node each, at the apex of its ellipsoid.
    ASSERT_EQ(m.node_sets.at("apex_endo").size(), 1u);
    ASSERT_EQ(m.node_sets.at("apex_epi").size(), 1u);
    EXPECT_EQ(m.nodes[m.node_sets.at("apex_endo")[0]], Vec3(0, 0, -p.endo_long));
    EXPECT_EQ(m.nodes[m.node_sets.at("apex_epi")[0]], Vec3(0, 0, -p.epi_long));
  }
}

TEST(LvMesh, QuadraticTetsHavePositiveJacobiansEverywhere) {
  const TetMesh m = make_lv_mesh(lv(8, 4, 1, 2));
  for (int e = 0; e < m.num_tets(); ++e) {
    double min_det = 0.0;
    const double v = quadratic_tet_volume(m, e, min_det);
    ASSERT_GT(min_det, 0.0) << "tet " << e;
    ASSERT_GT(v, 0.0) << "tet " << e;
  }
}

TEST(LvMesh, WallVolumeConvergesToTheAnalyticShell) {
  const LvMeshParams d;
  const double exact = cap_volume(d.epi_short, d.epi_long, d.base_z) - cap_volume(d.endo_short, d.endo_long, d.base_z);
  for (int order : {1, 2}) {
    std::vector<double> err;
    for (int r : {1, 2, 4}) err.push_back(std::abs(wall_volume(make_lv_mesh(lv(8 * r, 4 * r, r, order))) - exact) / exact);
    const double p1 = std::log2(err[0] / err[1]), p2 = std::log2(err[1] / err[2]);
    std::printf("wall volume, order %d: relative errors %.3e %.3e %.3e, observed orders %.2f %.2f\n", order,
                err[0], err[1], err[2], p1, p2);
    if (order == 1) {
      EXPECT_NEAR(p2, 2.0, 0.15);
    } else {
      EXPECT_GT(p2, 3.7);
      EXPECT_LT(err[2], 1e-5);
    }
  }
}

/// The default LV with its cavity meshed in `layers` layers, rings as in
/// tools/meshes/lv_cavity_mesh.py scaled to this LV's base cap (radius 6.69).
LvMeshParams lv_with_cavity(int nc, int nl, int nt, int layers, int order) {
  LvMeshParams p = lv(nc, nl, nt, order);
  p.cavity_layers = layers;
  p.rings = {{"mitral", -2.5, 0.0, 3.1}, {"aortic", 4.1, 0.0, 1.9}};
  return p;
}

double region_volume(const TetMesh& m, int region) {
  double v = 0.0, min_det = 0.0;
  for (int e = 0; e < m.num_tets(); ++e)
    if (m.region[e] == region) v += m.order() == 1 ? tet_signed_volume(m, e) : quadratic_tet_volume(m, e, min_det);
  return v;
}

/// Sorted vertex triples of every tet face -> the tets that have it.
std::map<std::array<int, 3>, std::vector<int>> face_owners(const TetMesh& m) {
  std::map<std::array<int, 3>, std::vector<int>> owners;
  for (int e = 0; e < m.num_tets(); ++e)
    for (int opp = 0; opp < 4; ++opp) {
      std::array<int, 3> f{};
      for (int a = 0, k = 0; a < 4; ++a)
        if (a != opp) f[k++] = m.tets[e][a];
      std::sort(f.begin(), f.end());
      owners[f].push_back(e);
    }
  return owners;
}

std::array<int, 3> sorted(std::array<int, 3> f) {
  std::sort(f.begin(), f.end());
  return f;
}

// The cavity continues the wall's grid: the wall is the mesh without a cavity, node for
// node and tet for tet; the blood shares the endocardium's nodes (no node twice in
// space), and the blood is closed by the endocardium and the base plane alone.
TEST(LvMesh, CavityConformsToTheWallOnSharedNodes) {
  for (int order : {1, 2}) {
    SCOPED_TRACE(order);
    const int nc = 10, nl = 5, nt = 2, nb = 3;
    const TetMesh wall = make_lv_mesh(lv(nc, nl, nt, order));
    const TetMesh m = make_lv_mesh(lv_with_cavity(nc, nl, nt, nb, order));
    ASSERT_EQ(m.order(), order);
    EXPECT_EQ(m.region_names.at(1), "myocardium");
    EXPECT_EQ(m.region_names.at(2), "blood");
    // The wall unchanged: its tets in the same order, with the same (edge) node positions.
    std::vector<std::vector<Vec3>> wall_tets, kept;
    const auto positions = [](const TetMesh& mesh, int e) {
      std::vector<Vec3> x;
      for (int a : mesh.element_nodes(e)) x.push_back(mesh.nodes[a]);
      return x;
    };
    for (int e = 0; e < wall.num_tets(); ++e) wall_tets.push_back(positions(wall, e));
    for (int e = 0; e < m.num_tets(); ++e)
      if (m.region[e] == 1) kept.push_back(positions(m, e));
    ASSERT_TRUE(kept == wall_tets) << "the wall's tets changed";
    // Counts: the cavity's cells are 6 tets each, less the flat ones at the apex and the
    // axis (apex cells: 3 left per cell, as the wall's, 2 on the axis; axis cells: 3 left).
    const int blood = static_cast<int>(std::count(m.region.begin(), m.region.end(), 2));
    EXPECT_EQ(blood, nc * (nl - 1) * (6 * (nb - 1) + 3) + nc * (3 * (nb - 1) + 2));
    // No two nodes at one point: the blood and the wall share the endocardium's nodes.
    std::vector<std::array<double, 3>> xs;
    for (const Vec3& x : m.nodes) xs.push_back({x.x(), x.y(), x.z()});
    std::sort(xs.begin(), xs.end());
    for (std::size_t a = 1; a < xs.size(); ++a) {
      const double d = std::hypot(xs[a][0] - xs[a - 1][0], xs[a][1] - xs[a - 1][1], xs[a][2] - xs[a - 1][2]);
      ASSERT_GT(d, 1e-6) << "two nodes at (" << xs[a][0] << ", " << xs[a][1] << ", " << xs[a][2] << ")";
    }
    // Every face has one or two tets; the endocardium's have one of each region, and the
    // blood's boundary faces are exactly the base cap and the rings.
    const auto owners = face_owners(m);
    ASSERT_TRUE(m.interfaces.count("endo"));
    ASSERT_FALSE(m.faces.count("endo"));
    std::map<std::array<int, 3>, std::string> named;
    for (const char* f : {"base_cap", "mitral", "aortic"})
      for (const auto& tri : m.faces.at(f)) named[sorted(tri)] = f;
    std::size_t blood_boundary = 0;
    for (const auto& [f, tets] : owners) {
      ASSERT_LE(tets.size(), 2u);
      if (tets.size() == 1 && m.region[tets[0]] == 2) {
        ++blood_boundary;
        ASSERT_TRUE(named.count(f)) << "a boundary face of the blood off the base plane";
      }
    }
    EXPECT_EQ(blood_boundary, named.size());
    for (const auto& tri : m.interfaces.at("endo")) {
      const auto& tets = owners.at(sorted(tri));
      ASSERT_EQ(tets.size(), 2u);
      EXPECT_EQ(m.region[tets[0]] + m.region[tets[1]], 3);
    }
    EXPECT_EQ(m.interfaces.at("endo").size(), wall.faces.at("endo").size());
    // Every element positive everywhere (validate_mesh checks the vertex volume only).
    double worst_ratio = 1.0, worst_shape = 1.0;
    for (int e = 0; e < m.num_tets(); ++e)
      if (m.region[e] == 2) {
        const ElementQuality q = element_quality(m, e);
        worst_ratio = std::min(worst_ratio, q.jacobian_ratio);
        worst_shape = std::min(worst_shape, q.shape);
      }
    std::printf("order %d: %d blood tets, worst Jacobian ratio %.3f, worst shape %.3f\n", order, blood,
                worst_ratio, worst_shape);
    // The wall's worst is 0.27 here. The blood's worst (0.29) are the tets on the strongly
    // curved endocardium next to the apex; with every cavity shell through the endocardial
    // apex they were slivers there (0.14), which the beating wall's apex folded.
    EXPECT_GT(worst_ratio, 0.25);
    EXPECT_GT(worst_shape, 0.05);
  }
}

// The blood fills exactly what the endocardium and the base plane enclose (the lumped
// cavity volume of the same surface), and converges to the analytic truncated ellipsoid.
TEST(LvMesh, CavityFillsTheEndocardium) {
  const LvMeshParams d;
  const double exact = cap_volume(d.endo_short, d.endo_long, d.base_z);
  for (int order : {1, 2}) {
    std::vector<double> err;
    for (int r : {1, 2, 4}) {
      TetMesh m = make_lv_mesh(lv_with_cavity(8 * r, 4 * r, r, 2 * r, order));
      const double blood = region_volume(m, 2);
      m.faces["endo"] = m.interfaces.at("endo");  // normals out of the wall, into the cavity
      const double lumped = cavity_volume(m, "endo", Eigen::VectorXd::Zero(3 * m.num_nodes())).volume;
      EXPECT_NEAR(blood / lumped, 1.0, 1e-12) << "order " << order << ", refinement " << r;
      err.push_back(std::abs(blood - exact) / exact);
    }
    const double p2 = std::log2(err[1] / err[2]);
    std::printf("cavity volume, order %d: relative errors %.3e %.3e %.3e, observed order %.2f\n", order, err[0],
                err[1], err[2], p2);
    EXPECT_GT(p2, order == 1 ? 1.85 : 3.7);
  }
}

// The base cap and the rings tile the cavity's base disc in the base plane (normals +z);
// each ring is the triangles whose centroid lies in its disc, which approaches the disc.
TEST(LvMesh, CavityRingsAreDiscsOfTheBaseCap) {
  const LvMeshParams d;
  const double R = d.endo_short * std::sqrt(1.0 - d.base_z * d.base_z / (d.endo_long * d.endo_long));
  for (int r : {1, 4}) {
    const LvMeshParams p = lv_with_cavity(16 * r, 4, 1, 4 * r, 1);
    const TetMesh m = make_lv_mesh(p);
    std::map<std::string, double> area;
    for (const char* f : {"base_cap", "mitral", "aortic"})
      for (const auto& tri : m.faces.at(f)) {
        const Vec3 &x0 = m.nodes[tri[0]], &x1 = m.nodes[tri[1]], &x2 = m.nodes[tri[2]];
        const Vec3 n = (x1 - x0).cross(x2 - x0);
        ASSERT_GT(n.z(), 0.0) << f;
        for (const Vec3* x : {&x0, &x1, &x2}) ASSERT_EQ(x->z(), d.base_z) << f;
        area[f] += 0.5 * n.norm();
      }
    // The cap is the regular polygon of the endocardium's base ring: area n R² sin(2π/n)/2.
    const int n = 16 * r;
    EXPECT_NEAR(area["base_cap"] + area["mitral"] + area["aortic"], 0.5 * n * R * R * std::sin(2 * M_PI / n), 1e-12 * R * R);
    for (const LvBaseRing& ring : p.rings) {
      const double disc = M_PI * ring.radius * ring.radius;
      std::printf("divisions %d x %d layers: ring %s area %.3f (disc %.3f)\n", n, 4 * r, ring.name.c_str(),
                  area[ring.name], disc);
      // Ragged: whole triangles in or out; within a quarter on 64 x 16, a half on 16 x 4.
      EXPECT_NEAR(area[ring.name] / disc, 1.0, r == 1 ? 0.5 : 0.25) << ring.name;
      for (int a : m.node_sets.at(ring.name)) ASSERT_EQ(m.nodes[a].z(), d.base_z);
    }
  }
}

TEST(LvMesh, BadCavityRingsNameTheRing) {
  const auto message = [](const LvMeshParams& p) {
    try {
      make_lv_mesh(p);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("nothing thrown");
  };
  const auto has = [&](const LvMeshParams& p, const std::string& text) {
    const std::string m = message(p);
    EXPECT_NE(m.find(text), std::string::npos) << m;
  };
  LvMeshParams p = lv_with_cavity(16, 4, 1, 4, 1);
  p.rings[1].x = 5.5;  // 5.5 + 1.9 > 6.69
  has(p, "ring 'aortic' centre distance + radius = 7.4: expected a disc inside the cavity's base cap (radius 6.69");
  p = lv_with_cavity(16, 4, 1, 4, 1);
  p.rings[1].x = 1.0;
  has(p, "ring 'aortic' and ring 'mitral': gap");
  p = lv_with_cavity(16, 4, 1, 4, 1);
  p.rings[1].name = "base_cap";
  has(p, "ring name 'base_cap' is the generator's own set");
  p = lv_with_cavity(16, 4, 1, 4, 1);
  p.rings[1].radius = 0.05;
  has(p, "ring 'aortic' (radius 0.05) holds no base-cap triangle");
  p = lv_with_cavity(16, 4, 1, 4, 1);
  p.cavity_layers = 0;
  has(p, "ring 'mitral' given without a cavity");
}

TEST(LvMesh, BadParametersNameTheParameter) {
  const auto message = [](LvMeshParams p) {
    try {
      make_lv_mesh(p);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("nothing thrown");
  };
  LvMeshParams p;
  p.epi_short = 6;
  EXPECT_NE(message(p).find("epi_short = 6: expected a semi-axis > endo_short = 7"), std::string::npos) << message(p);
  p = {};
  p.base_z = 18;
  EXPECT_NE(message(p).find("base_z = 18"), std::string::npos) << message(p);
  p = {};
  p.circumferential = 2;
  EXPECT_NE(message(p).find("circumferential = 2: expected an integer in [3, 10000]"), std::string::npos);
  p = {};
  p.order = 3;
  EXPECT_NE(message(p).find("order = 3"), std::string::npos);
}

}  // namespace
}  // namespace fe2
