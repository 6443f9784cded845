// Fibre fields (common/fibres/): the rule-based (Bayer 2012) frame on a slab whose
// endo/epi/base/apex are box faces (exact answers: φ and ψ are linear there), Bayer's
// bislerp, file-given frames (Gmsh views, CSV) round-tripping bit for bit, nodal frames
// interpolated as rotations (a helix through a thin wall), frames per integration point,
// bad fibre files with their messages, the spec keys and the VTU cell vectors.
#include "common/error.h"
#include "common/fem/quadrature.h"
#include "common/fibres/AnalyticFrame.h"
#include "common/fibres/FileFrame.h"
#include "common/fibres/RuleFrame.h"
#include "common/fibres/frame_interpolation.h"
#include "common/fibres/frame_output.h"
#include "common/fibres/frame_spec.h"
#include "common/io/vtu_writer.h"
#include "common/mesh/box_mesh.h"
#include "common/mesh/gmsh_reader.h"
#include "common/mesh/lv_mesh.h"
#include "common/spec/spec_schemas.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <tuple>
#include <random>
#include <sstream>

namespace fe2 {
namespace {

namespace fs = std::filesystem;

constexpr double kDeg = M_PI / 180.0;

std::string slurp(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

class ScratchDir {
 public:
  ScratchDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = fs::temp_directory_path() / fmt::format("fe2_{}_{}_{}", info->test_suite_name(), info->name(), getpid());
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~ScratchDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  std::string operator/(const std::string& name) const { return (path_ / name).string(); }

 private:
  fs::path path_;
};

void write_text(const std::string& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

template <class F>
std::string input_error(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "nothing thrown";
}

// The slab [0,1]x[0,2]x[0,3]: endo = xmin, epi = xmax, apex = zmin, base = zmax. Then
// φ = x and ψ = z/3 exactly (P1 holds linear fields), so t = e_x, l = e_z, c = l × t = e_y.
TetMesh slab(int order = 1) { return make_box_mesh(Vec3(0, 0, 0), Vec3(1, 2, 3), {3, 4, 5}, -1, 1, order); }

RuleFrameOptions slab_rule() {
  RuleFrameOptions o;
  o.endo = "xmin";
  o.epi = "xmax";
  o.apex = "zmin";
  o.base = "zmax";
  return o;
}

/// Helix angle (degrees) of f against the slab's geometric axes c = e_y, l = e_z.
double helix_deg(const Mat3& Q) { return std::atan2(Q(2, 0), Q(1, 0)) / kDeg; }

/// Points of the faces of the tets lying in the plane x = x0: (element, λ) at the face centroid.
std::vector<std::pair<int, Bary>> face_points(const TetMesh& m, double x0) {
  std::vector<std::pair<int, Bary>> out;
  for (int e = 0; e < m.num_tets(); ++e) {
    Bary l{};
    int on = 0;
    for (int a = 0; a < 4; ++a)
      if (std::abs(m.nodes[m.tets[e][a]][0] - x0) < 1e-12) {
        l[a] = 1.0 / 3.0;
        ++on;
      }
    if (on == 3) out.push_back({e, l});
  }
  return out;
}

Vec3 point(const TetMesh& m, int e, const Bary& l) {
  Vec3 X = Vec3::Zero();
  for (int a = 0; a < 4; ++a) X += l[a] * m.nodes[m.tets[e][a]];
  return X;
}

TEST(RuleFrame, HelixAngleIsAlphaEndoOnEndoAndAlphaEpiOnEpi) {
  const TetMesh m = slab();
  const RuleFrame rule(m, slab_rule());
  const auto endo = face_points(m, 0.0), epi = face_points(m, 1.0);
  ASSERT_EQ(endo.size(), 2u * 4 * 5);  // two triangles per cell face
  ASSERT_EQ(epi.size(), 2u * 4 * 5);
  for (const auto& [e, l] : endo) {
    EXPECT_NEAR(helix_deg(rule.at(e, l, point(m, e, l))), 60.0, 1e-6) << "endo, element " << e;
    EXPECT_EQ(rule.transmural(e, l), 0.0);
  }
  for (const auto& [e, l] : epi) EXPECT_NEAR(helix_deg(rule.at(e, l, point(m, e, l))), -60.0, 1e-6) << "epi, element " << e;
}

TEST(RuleFrame, FibresUnitOrthogonalToTransmuralSheetsWithSheetAngle) {
  const TetMesh m = slab();
  RuleFrameOptions o = slab_rule();
  o.alpha_endo = 50;
  o.alpha_epi = -70;
  const RuleFrame rule(m, o);
  o.beta_endo = 10;
  o.beta_epi = -30;
  const RuleFrame tilted(m, o);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int e = 0; e < m.num_tets(); ++e) {
    Bary l{u(rng), u(rng), u(rng), u(rng)};
    const double sum = l[0] + l[1] + l[2] + l[3];
    for (double& x : l) x /= sum;
    const Vec3 X = point(m, e, l);
    const Mat3 Q = rule.at(e, l, X);
    EXPECT_NEAR((Q.transpose() * Q - Mat3::Identity()).norm(), 0.0, 1e-12) << e;
    EXPECT_NEAR(Q.determinant(), 1.0, 1e-12) << e;
    EXPECT_NEAR(Q.col(1).dot(Vec3::UnitX()), 1.0, 1e-12) << "sheet transmural, element " << e;
    EXPECT_NEAR(helix_deg(Q), 50.0 - 120.0 * X[0], 1e-9) << "α(φ) linear through the wall, element " << e;
    // β tilts the sheet about the fibre, away from the transmural direction by β(φ).
    const Mat3 T = tilted.at(e, l, X);
    EXPECT_NEAR((T.col(0) - Q.col(0)).norm(), 0.0, 1e-12);
    EXPECT_NEAR(std::acos(std::clamp(T.col(1).dot(Vec3::UnitX()), -1.0, 1.0)) / kDeg, std::abs(10.0 - 40.0 * X[0]),
                1e-6);
  }
}

TEST(RuleFrame, ApicoBasalFallbackWhereGradPsiIsParallelToTransmural) {
  // ψ along x as well (apex = endo side, base = epi side): ∇ψ ∥ ∇φ, so l comes from the
  // long axis (apex centroid → base centroid = e_x) made orthogonal to t, and failing
  // that from any direction orthogonal to t: still an orthonormal frame, sheet transmural.
  const TetMesh m = slab();
  RuleFrameOptions o = slab_rule();
  o.apex = "xmin";
  o.base = "xmax";
  const RuleFrame rule(m, o);
  const Mat3 Q = rule.at(0, kCentroid, point(m, 0, kCentroid));
  EXPECT_NEAR((Q.transpose() * Q - Mat3::Identity()).norm(), 0.0, 1e-12);
  EXPECT_NEAR(Q.col(1).dot(Vec3::UnitX()), 1.0, 1e-12);
}

TEST(RuleFrame, MissingOrTouchingSurfacesAreInputErrors) {
  const TetMesh m = slab();
  RuleFrameOptions o = slab_rule();
  o.endo = "endo";
  EXPECT_NE(input_error([&] { RuleFrame r(m, o); }).find("'endo' = \"endo\" is not a named surface or node set of the mesh"),
            std::string::npos);
  o = slab_rule();
  o.epi = "ymin";  // shares the edge x = 0, y = 0 with endo = xmin
  const std::string msg = input_error([&] { RuleFrame r(m, o); });
  EXPECT_NE(msg.find("frame rule, transmural φ: node"), std::string::npos) << msg;
  EXPECT_NE(msg.find("lies on both 'xmin' (value 0) and 'ymin' (value 1)"), std::string::npos) << msg;
}

TEST(RuleFrame, QuadraticMeshGivesTheSameFrames) {
  const TetMesh m1 = slab(1), m2 = slab(2);
  const RuleFrame r1(m1, slab_rule()), r2(m2, slab_rule());
  for (int e = 0; e < m1.num_tets(); e += 7)
    EXPECT_NEAR((r1.at(e, kCentroid, Vec3()) - r2.at(e, kCentroid, Vec3())).norm(), 0.0, 1e-12);
}

Mat3 turn(const Vec3& axis, double deg) { return Eigen::AngleAxisd(deg * kDeg, axis.normalized()).toRotationMatrix(); }

TEST(Bislerp, EndsMidpointAndFrameSymmetries) {
  const Mat3 Q0 = turn(Vec3(1, 2, 3), 40);
  const Mat3 Qa = Q0 * turn(Vec3::UnitZ(), 20), Qb = Q0 * turn(Vec3::UnitZ(), 80);
  EXPECT_NEAR((bislerp(&Qa, &Qb, 0.0) - Qa).norm(), 0.0, 1e-12);
  EXPECT_NEAR((bislerp(&Qa, &Qb, 1.0) - Qb).norm(), 0.0, 1e-12);
  EXPECT_NEAR((bislerp(&Qa, &Qb, 0.5) - Q0 * turn(Vec3::UnitZ(), 50)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((bislerp(&Qa, nullptr, 0.3) - Qa).norm(), 0.0, 0.0);
  // Qb turned by π about its own fibre axis is the same fibre/sheet lines: the
  // interpolation must not swing through 180°, so the fibre line stays near both.
  const Mat3 Qflip = Qb * turn(Vec3::UnitX(), 180);
  const Mat3 mid = bislerp(&Qa, &Qflip, 0.5);
  EXPECT_NEAR(std::abs(mid.col(0).dot((Q0 * turn(Vec3::UnitZ(), 50)).col(0))), 1.0, 1e-12);
  EXPECT_NEAR(std::abs(mid.col(2).dot(Q0.col(2))), 1.0, 1e-12);
}

TEST(RuleFrame, BiventricularFramesAreOrthonormalAndMatchBayerOnTheSurfaces) {
  // A slab with the LV endo at x = 0, the RV endo at x = 2 and the epicardium on the
  // part of y = 1 off those two faces (three Laplace problems need disjoint sets).
  TetMesh m = make_box_mesh(Vec3(0, 0, 0), Vec3(2, 1, 1), {6, 3, 3});
  std::vector<int> epi;
  for (int v : m.node_sets.at("ymax"))
    if (m.nodes[v][0] > 1e-9 && m.nodes[v][0] < 2 - 1e-9) epi.push_back(v);
  m.node_sets["epi"] = epi;
  RuleFrameOptions o;
  o.endo = "xmin";
  o.rv_endo = "xmax";
  o.epi = "epi";
  o.apex = "zmin";
  o.base = "zmax";
  const RuleFrame rule(m, o);
  ASSERT_TRUE(rule.biventricular());
  for (int e = 0; e < m.num_tets(); ++e) {
    const Mat3 Q = rule.at(e, kCentroid, Vec3());
    EXPECT_NEAR((Q.transpose() * Q - Mat3::Identity()).norm(), 0.0, 1e-12) << e;
    EXPECT_NEAR(Q.determinant(), 1.0, 1e-12) << e;
  }
  // On the LV endo face (φ_lv = 1, φ_rv = φ_epi = 0 at its vertices) Bayer's rule gives
  // Q_lv: the fibre at α_endo from the circumferential direction l × t, t = −∇φ_lv
  // (towards −x at x = 0, up to the tilt of ∇φ_lv), in the plane orthogonal to t; the
  // sheet along t. On the RV endo face the helix is mirrored (α_s = −α_endo).
  for (const double x0 : {0.0, 2.0})
    for (const auto& [e, l] : face_points(m, x0)) {
      const Mat3 Q = rule.at(e, l, Vec3());
      const Vec3 t = Q.col(1);
      EXPECT_GT(std::abs(t[0]), 0.9) << "sheet roughly transmural, x = " << x0;
      Vec3 lz = Vec3::UnitZ() - Vec3::UnitZ().dot(t) * t;
      lz.normalize();
      const Vec3 c = lz.cross(t);
      EXPECT_NEAR(std::atan2(Q.col(0).dot(lz), Q.col(0).dot(c)) / kDeg, x0 == 0.0 ? 60.0 : -60.0, 1e-6) << "x = " << x0;
    }
}

/// A point on each triangle of a named face: (element, λ at the triangle's centroid,
/// the triangle's outward unit normal).
struct SurfacePoint {
  int e;
  Bary l;
  Vec3 n;
};
std::vector<SurfacePoint> surface_points(const TetMesh& m, const std::string& face) {
  std::map<std::array<int, 3>, std::pair<int, Bary>> of;
  for (int e = 0; e < m.num_tets(); ++e)
    for (int skip = 0; skip < 4; ++skip) {
      std::array<int, 3> key{};
      Bary l{};
      for (int a = 0, k = 0; a < 4; ++a)
        if (a != skip) {
          key[k++] = m.tets[e][a];
          l[a] = 1.0 / 3.0;
        }
      std::sort(key.begin(), key.end());
      of[key] = {e, l};
    }
  std::vector<SurfacePoint> out;
  for (const auto& t : m.faces.at(face)) {
    std::array<int, 3> key = t;
    std::sort(key.begin(), key.end());
    const auto& [e, l] = of.at(key);
    const Vec3 n = (m.nodes[t[1]] - m.nodes[t[0]]).cross(m.nodes[t[2]] - m.nodes[t[0]]).normalized();
    out.push_back({e, l, n});
  }
  return out;
}

/// |helix angle − alpha| (degrees; modulo 180: a fibre is a line) of f against axes built
/// from the geometry: t along `t_geo`, l = e_z made orthogonal to t, c = l × t.
double geometric_helix_error_deg(const Vec3& f, const Vec3& t_geo, double alpha) {
  const Vec3 t = t_geo.normalized();
  const Vec3 l = (Vec3::UnitZ() - Vec3::UnitZ().dot(t) * t).normalized();
  const double d = std::remainder(std::atan2(f.dot(l), f.dot(l.cross(t))) / kDeg - alpha, 180.0);
  return std::abs(d);
}

TEST(RuleFrame, LeftVentricleHelixAngleOnEndoAndEpi) {
  LvMeshParams p;
  p.transmural = 3;
  const TetMesh m = make_lv_mesh(p);
  const RuleFrame rule(m, RuleFrameOptions{});  // defaults: endo, epi, base; apex found
  double worst_geo = 0;
  for (const auto& [face, alpha, sign] : {std::tuple{"endo", 60.0, -1.0}, std::tuple{"epi", -60.0, 1.0}}) {
    const auto pts = surface_points(m, face);
    ASSERT_GT(pts.size(), 100u);
    for (const auto& [e, l, n] : pts) {
      const Mat3 Q = rule.at(e, l, Vec3());
      const Mat3 A = rule.axes(e, l);  // the rule's own [c l t]
      EXPECT_NEAR(std::atan2(Q.col(0).dot(A.col(1)), Q.col(0).dot(A.col(0))) / kDeg, alpha, 1e-6) << face << " " << e;
      EXPECT_NEAR((Q.transpose() * Q - Mat3::Identity()).norm(), 0.0, 1e-12);
      EXPECT_NEAR((Q.col(1) - A.col(2)).norm(), 0.0, 1e-12) << "sheet transmural";
      EXPECT_EQ(rule.transmural(e, l), face == std::string("endo") ? 0.0 : 1.0);
      // Against the geometry (t = the wall's normal towards the epicardium): the P1
      // gradient of φ is close to, not exactly along, the surface normal.
      const double err = geometric_helix_error_deg(Q.col(0), sign * n, alpha);
      ASSERT_TRUE(std::isfinite(err));
      worst_geo = std::max(worst_geo, err);
      EXPECT_GT(Q.col(1).dot(sign * n), 0.9) << face << " " << e;
    }
  }
  // The generator's mesh is symmetric enough that ∇ψ lies in the meridional plane.
  EXPECT_LT(worst_geo, 0.5);
  std::printf("LV (%d tets): worst helix angle against the surface normals %.3g°\n", m.num_tets(), worst_geo);
}

TEST(RuleFrame, BiventricularMeshHelixAngleOnLvRvEndoAndEpi) {
  const TetMesh m = read_gmsh_tets(std::string(FE2_SOURCE_DIR) + "/configs/meshes/biv_coarse.msh");
  RuleFrameOptions o;
  o.endo = "lv_endo";
  o.rv_endo = "rv_endo";
  const RuleFrame rule(m, o);
  for (int e = 0; e < m.num_tets(); ++e) {
    const Mat3 Q = rule.at(e, kCentroid, Vec3());
    EXPECT_NEAR((Q.transpose() * Q - Mat3::Identity()).norm(), 0.0, 1e-12) << e;
    EXPECT_NEAR(Q.determinant(), 1.0, 1e-12) << e;
  }
  // Epi: Bayer gives Q_epi = orient(axis(∇ψ, ∇φ_epi), α_epi), exactly. LV and RV endo:
  // the right-handed endocardial helix +α_endo with t pointing into the wall (the RV's
  // rule −α_endo about ∇φ_rv, which points out of the wall, is the same fibre line).
  std::vector<double> errors;
  for (const auto& [face, alpha] : {std::pair{"lv_endo", 60.0}, std::pair{"rv_endo", 60.0}, std::pair{"epi", -60.0}}) {
    for (const auto& [e, l, n] : surface_points(m, face)) {
      const Mat3 Q = rule.at(e, l, Vec3());
      if (face == std::string("epi")) {
        const Mat3 A = rule.axes(e, l);
        EXPECT_NEAR(std::atan2(Q.col(0).dot(A.col(1)), Q.col(0).dot(A.col(0))) / kDeg, alpha, 1e-6) << e;
        EXPECT_EQ(rule.transmural(e, l), 1.0);
      }
      const Vec3 into_wall_to_epi = face == std::string("epi") ? n : Vec3(-n);
      errors.push_back(geometric_helix_error_deg(Q.col(0), into_wall_to_epi, alpha));
    }
    std::sort(errors.begin(), errors.end());
    ASSERT_TRUE(std::isfinite(errors.back()));
    // Against e_z as the long axis (∇ψ from the apex point tilts around the RV): most
    // points within 20°, none a reversed helix (120° off).
    EXPECT_LT(errors[errors.size() * 9 / 10], 20.0) << face;
    EXPECT_LT(errors.back(), 60.0) << face;
    std::printf("BiV %s: helix angle against the surface normals: median error %.2f°, 90th percentile %.2f°, max %.2f° (%zu points)\n",
                face, errors[errors.size() / 2], errors[errors.size() * 9 / 10], errors.back(), errors.size());
    errors.clear();
  }
}

// -------------------------------------------------------------------------------------
// File-given frames.

/// Unit, orthogonal (f, s) pairs written with 17 digits, so reading gives the same doubles.
struct Written {
  std::vector<Vec3> f, s;
  std::string csv_rows(const std::vector<long long>& tags) const {
    std::string out;
    for (std::size_t i = 0; i < tags.size(); ++i)
      out += fmt::format("{},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g}\n", tags[i], f[i][0], f[i][1], f[i][2],
                         s[i][0], s[i][1], s[i][2]);
    return out;
  }
};

Written random_frames(std::size_t n, unsigned seed, bool smooth = false) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> g;
  Written w;
  for (std::size_t i = 0; i < n; ++i) {
    Vec3 f(g(rng), g(rng), g(rng)), s(g(rng), g(rng), g(rng));
    if (smooth) {  // near x and y, so nodal interpolation does not cancel
      f = Vec3(1, 0.1 * f[1], 0.1 * f[2]);
      s = Vec3(0.1 * s[0], 1, 0.1 * s[2]);
    }
    Mat3 Q = Mat3::Identity();
    EXPECT_TRUE(orthonormal_frame(f, s, Q));
    w.f.push_back(Q.col(0));
    w.s.push_back(Q.col(1));
  }
  return w;
}

std::string view(const std::string& section, const std::string& name, const std::vector<long long>& tags,
                 const std::vector<Vec3>& v) {
  std::string out = fmt::format("${}\n1\n\"{}\"\n1\n0.0\n3\n0\n3\n{}\n", section, name, tags.size());
  for (std::size_t i = 0; i < tags.size(); ++i) out += fmt::format("{} {:.17g} {:.17g} {:.17g}\n", tags[i], v[i][0], v[i][1], v[i][2]);
  return out + fmt::format("$End{}\n", section);
}

std::string two_tets_msh() { return slurp(std::string(FE2_SOURCE_DIR) + "/tests/data/two_tets.msh"); }

TEST(FileFrame, GmshElementViewsRoundTripBitForBit) {
  ScratchDir dir;
  const std::string mesh_file = dir / "two_tets.msh";
  const Written w = random_frames(2, 1);
  // Tags 6, 7 are the tets; the view also covers triangle 5, which is not ours to read.
  Written w3 = w;
  w3.f.push_back(Vec3::UnitX());
  w3.s.push_back(Vec3::UnitY());
  write_text(mesh_file, two_tets_msh() + view("ElementData", "fibre", {6, 7, 5}, w3.f) +
                            view("ElementData", "sheet", {7, 5, 6}, {w3.s[1], w3.s[2], w3.s[0]}));
  const TetMesh m = read_gmsh_tets(mesh_file);
  FileFrameOptions o;
  o.file = mesh_file;
  o.mesh_file = mesh_file;
  const FileFrame ff(m, o);
  const GmshTags tags = read_gmsh_tags(mesh_file);
  ASSERT_EQ(tags.elements, (std::vector<long long>{6, 7}));
  for (int e = 0; e < 2; ++e) {
    EXPECT_EQ(ff.fibres()[e], w.f[e]) << e;  // bit for bit
    EXPECT_EQ(ff.sheets()[e], w.s[e]) << e;
    const Mat3 Q = ff.at(e, kCentroid, Vec3());
    EXPECT_NEAR((Q.col(0) - w.f[e]).norm(), 0.0, 1e-15);
    EXPECT_NEAR((Q.col(1) - w.s[e]).norm(), 0.0, 1e-15);
  }
  // The same views in a file of their own (no mesh in it), tags mapped via the mesh file.
  const std::string data_file = dir / "fibres.msh";
  write_text(data_file, "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n" + view("ElementData", "f", {7, 6}, {w.f[1], w.f[0]}) +
                            view("ElementData", "s", {6, 7}, w.s));
  o.file = data_file;
  o.fibre_view = "f";
  o.sheet_view = "s";
  const FileFrame separate(m, o);
  EXPECT_EQ(separate.fibres(), w.f);
  EXPECT_EQ(separate.sheets(), w.s);
}

TEST(FileFrame, GmshNodeViewsInterpolateAsRotations) {
  ScratchDir dir;
  const std::string mesh_file = dir / "two_tets.msh";
  const Written w = random_frames(5, 2, /*smooth=*/true);
  const std::vector<long long> node_tags = {11, 12, 13, 14, 15};
  write_text(mesh_file, two_tets_msh() + view("NodeData", "fibre", node_tags, w.f) + view("NodeData", "sheet", node_tags, w.s));
  const TetMesh m = read_gmsh_tets(mesh_file);
  FileFrameOptions o;
  o.file = mesh_file;
  o.mesh_file = mesh_file;
  o.per = FramePer::node;
  const FileFrame ff(m, o);
  const GmshTags tags = read_gmsh_tags(mesh_file);
  for (int i = 0; i < m.num_nodes(); ++i) {
    const auto k = std::find(node_tags.begin(), node_tags.end(), tags.nodes[i]) - node_tags.begin();
    EXPECT_EQ(ff.fibres()[i], w.f[k]);
    EXPECT_EQ(ff.sheets()[i], w.s[k]);
  }
  for (int e = 0; e < m.num_tets(); ++e) {
    for (int a = 0; a < 4; ++a) {  // at a vertex: that node's frame
      Bary l{};
      l[a] = 1;
      const Mat3 Q = ff.at(e, l, Vec3());
      EXPECT_NEAR((Q.col(0) - ff.fibres()[m.tets[e][a]]).norm(), 0.0, 1e-15);
      EXPECT_NEAR((Q.col(1) - ff.sheets()[m.tets[e][a]]).norm(), 0.0, 1e-15);
    }
    // On an edge: Bayer's bislerp of the two nodal frames (frame_mean of two frames is
    // the slerp point), up to a frame symmetry (f, s, n lines compared).
    for (double t : {0.25, 0.5, 0.8}) {
      Bary l{};
      l[1] = 1 - t;
      l[3] = t;
      Mat3 Q1, Q3;
      ASSERT_TRUE(orthonormal_frame(ff.fibres()[m.tets[e][1]], ff.sheets()[m.tets[e][1]], Q1));
      ASSERT_TRUE(orthonormal_frame(ff.fibres()[m.tets[e][3]], ff.sheets()[m.tets[e][3]], Q3));
      const Mat3 B = bislerp(&Q1, &Q3, t), Q = ff.at(e, l, Vec3());
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(std::abs(Q.col(c).dot(B.col(c))), 1.0, 1e-12) << e << " t " << t;
    }
    // Inside: a proper rotation.
    const Mat3 Q = ff.at(e, Bary{0.1, 0.2, 0.3, 0.4}, Vec3());
    EXPECT_NEAR((Q.transpose() * Q - Mat3::Identity()).norm(), 0.0, 1e-12);
    EXPECT_NEAR(Q.determinant(), 1.0, 1e-12);
  }
}

TEST(FileFrame, CsvByElementTagRoundTripsBitForBit) {
  ScratchDir dir;
  const TetMesh m = make_box_mesh(Vec3(0, 0, 0), Vec3(1, 1, 1), {2, 1, 1});  // 12 tets, tags 1..12
  const Written w = random_frames(12, 3);
  std::vector<long long> tags;
  for (long long t = 12; t >= 1; --t) tags.push_back(t);  // any order
  Written rev;
  for (int i = 11; i >= 0; --i) {
    rev.f.push_back(w.f[i]);
    rev.s.push_back(w.s[i]);
  }
  const std::string csv = dir / "fibres.csv";
  write_text(csv, "tag,fx,fy,fz,sx,sy,sz\n# a comment\n\n" + rev.csv_rows(tags));
  FileFrameOptions o;
  o.file = csv;
  o.csv = true;
  const FileFrame ff(m, o);
  EXPECT_EQ(ff.fibres(), w.f);
  EXPECT_EQ(ff.sheets(), w.s);
}

/// The InputError of reading `csv_text` as the fibres of a 2x1x1 box (12 tets).
std::string csv_error(const ScratchDir& dir, const std::string& csv_text) {
  const TetMesh m = make_box_mesh(Vec3(0, 0, 0), Vec3(1, 1, 1), {2, 1, 1});
  const std::string csv = dir / "bad.csv";
  write_text(csv, csv_text);
  FileFrameOptions o;
  o.file = csv;
  o.csv = true;
  return input_error([&] { FileFrame ff(m, o); });
}

std::string good_rows(int skip = 0) {
  std::string rows;
  for (int t = 1; t <= 12; ++t)
    if (t != skip) rows += fmt::format("{},1,0,0,0,1,0\n", t);
  return rows;
}

TEST(FileFrame, BadCsvFilesNameFileTagAndValue) {
  ScratchDir dir;
  const std::string file = dir / "bad.csv";
  std::string msg = csv_error(dir, good_rows(5) + "5,1.01,0,0,0,1,0\n");
  EXPECT_NE(msg.find(fmt::format("fibre file '{}' line 12: element 5: fibre vector (1.01, 0, 0) has length 1.01, "
                                 "expected a unit vector (length within 0.001 of 1)",
                                 file)),
            std::string::npos)
      << msg;
  msg = csv_error(dir, good_rows(3) + "3,1,0,0,0.01,1,0\n");
  EXPECT_NE(msg.find("element 3: fibre and sheet are not orthogonal (f·s = 0.01), expected |f·s| <= 0.001"),
            std::string::npos)
      << msg;
  msg = csv_error(dir, good_rows(7));
  EXPECT_NE(msg.find(fmt::format("fibre file '{}': no fibre and sheet for element 7 (and 0 more), expected one for "
                                 "every element of the mesh (12 elements)",
                                 file)),
            std::string::npos)
      << msg;
  msg = csv_error(dir, good_rows() + "4,0,1,0,1,0,0\n");
  EXPECT_NE(msg.find("line 13: element 4 appears again (first at line 4), expected exactly one fibre and sheet per "
                     "element"),
            std::string::npos)
      << msg;
  msg = csv_error(dir, good_rows() + "13,1,0,0,0,1,0\n");
  EXPECT_NE(msg.find("element 13 is not a element of the mesh"), std::string::npos) << msg;
  msg = csv_error(dir, "1,1,0,0,0,1\n");
  EXPECT_NE(msg.find("line 1: got '1,1,0,0,0,1', expected 7 comma-separated numbers tag,fx,fy,fz,sx,sy,sz"),
            std::string::npos)
      << msg;
}

TEST(FileFrame, BadGmshViewsNameFileViewAndTag) {
  ScratchDir dir;
  const std::string mesh_file = dir / "two_tets.msh";
  const auto read = [&](const std::string& data, const std::string& fibre_view = "fibre") {
    write_text(mesh_file, two_tets_msh() + data);
    const TetMesh m = read_gmsh_tets(mesh_file);
    FileFrameOptions o;
    o.file = o.mesh_file = mesh_file;
    o.fibre_view = fibre_view;
    return input_error([&] { FileFrame ff(m, o); });
  };
  const std::vector<Vec3> x(2, Vec3::UnitX()), y(2, Vec3::UnitY());
  const std::string good = view("ElementData", "fibre", {6, 7}, x) + view("ElementData", "sheet", {6, 7}, y);
  EXPECT_EQ(read(good), "nothing thrown");
  std::string msg = read(good, "fibres");
  EXPECT_NE(msg.find(fmt::format("file '{}': no $ElementData view named \"fibres\", expected one with 3 components "
                                 "per element: one of its views (fibre, sheet); did you mean \"fibre\"?",
                                 mesh_file)),
            std::string::npos)
      << msg;
  msg = read(view("ElementData", "fibre", {6, 7}, {Vec3(0, 0.98, 0), Vec3::UnitX()}) +
             view("ElementData", "sheet", {6, 7}, {Vec3::UnitX(), Vec3::UnitY()}));
  EXPECT_NE(msg.find("element 6: fibre vector (0, 0.98, 0) has length 0.98, expected a unit vector"),
            std::string::npos)
      << msg;
  msg = read(view("ElementData", "fibre", {6, 7}, x) + view("ElementData", "sheet", {6, 7}, {Vec3::UnitY(), Vec3(0.6, 0.8, 0)}));
  EXPECT_NE(msg.find("element 7: fibre and sheet are not orthogonal (f·s = 0.6)"), std::string::npos) << msg;
  msg = read(view("ElementData", "fibre", {6}, {Vec3::UnitX()}) + view("ElementData", "sheet", {6}, {Vec3::UnitY()}));
  EXPECT_NE(msg.find(fmt::format("fibre file '{}': no fibre and sheet for element 7", mesh_file)), std::string::npos)
      << msg;
  msg = read(view("ElementData", "fibre", {6, 7}, x) + view("ElementData", "sheet", {6}, {Vec3::UnitY()}));
  EXPECT_NE(msg.find("element 7 has a \"fibre\" vector but no \"sheet\" vector"), std::string::npos) << msg;
}

// -------------------------------------------------------------------------------------
// Nodal frames as rotations: a helix turning 150° through a wall two elements thick.

/// The angle (degrees) between the lines of a and b (a and −a are one fibre).
double line_deg(const Vec3& a, const Vec3& b) { return std::atan2(a.cross(b).norm(), std::abs(a.dot(b))) / kDeg; }

/// The largest angle between the fibre, sheet and normal lines of two frames.
double frame_deg(const Mat3& P, const Mat3& Q) {
  return std::max({line_deg(P.col(0), Q.col(0)), line_deg(P.col(1), Q.col(1)), line_deg(P.col(2), Q.col(2))});
}

void expect_rotation(const Mat3& Q, const std::string& where) {
  EXPECT_NEAR((Q.transpose() * Q - Mat3::Identity()).norm(), 0.0, 1e-12) << where;
  EXPECT_NEAR(Q.determinant(), 1.0, 1e-12) << where;
}

/// The slab wall x ∈ [0, 1] (transmural x, 2 elements thick), the fibre in the plane of
/// the wall at the helix angle α(x) = 75° − 150° x from e_y towards e_z, the sheet e_x:
/// the frame RuleFrame gives with α_endo = 75, α_epi = −75 on this slab.
Mat3 helix_frame(double x) {
  const double a = (75.0 - 150.0 * x) * kDeg;
  Mat3 Q;
  Q.col(0) = Vec3(0, std::cos(a), std::sin(a));
  Q.col(1) = Vec3::UnitX();
  Q.col(2) = Q.col(0).cross(Q.col(1));
  return Q;
}

TetMesh helix_slab(int order, int through = 2) {
  return make_box_mesh(Vec3(0, 0, 0), Vec3(1, 2, 2), {through, 2, 2}, -1, 1, order);
}

/// The helix frames written per node (tag = index + 1) and read back.
FileFrame helix_per_node(const ScratchDir& dir, const TetMesh& m) {
  std::string csv = "tag,fx,fy,fz,sx,sy,sz\n";
  for (int i = 0; i < m.num_nodes(); ++i) {
    const Mat3 Q = helix_frame(m.nodes[i][0]);
    csv += fmt::format("{},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g}\n", i + 1, Q(0, 0), Q(1, 0), Q(2, 0), Q(0, 1),
                       Q(1, 1), Q(2, 1));
  }
  const std::string file = dir / fmt::format("helix_nodes_p{}_{}.csv", m.order(), m.num_nodes());
  write_text(file, csv);
  FileFrameOptions o;
  o.file = file;
  o.csv = true;
  o.per = FramePer::node;
  return FileFrame(m, o);
}

/// The nodal rule FileFrame had before frames were interpolated as rotations, kept to
/// measure what it got wrong: f = Σ N_a (±f_a), s = Σ N_a (±s_a) with the signs of the
/// element's first node, then Gram–Schmidt.
Mat3 linear_nodal(const FileFrame& ff, const TetMesh& m, int e, const Bary& l) {
  const std::vector<int> n = m.element_nodes(e);
  double N[10];
  const bool p2 = n.size() == 10;
  for (int i = 0; i < 4; ++i) N[i] = p2 ? l[i] * (2 * l[i] - 1) : l[i];
  if (p2)
    for (int k = 0; k < 6; ++k) N[4 + k] = 4 * l[kTetEdges[k][0]] * l[kTetEdges[k][1]];
  Vec3 f = Vec3::Zero(), s = Vec3::Zero();
  const Vec3 &f0 = ff.fibres()[n[0]], &s0 = ff.sheets()[n[0]];
  for (std::size_t a = 0; a < n.size(); ++a) {
    const Vec3 &fa = ff.fibres()[n[a]], &sa = ff.sheets()[n[a]];
    f += N[a] * (fa.dot(f0) < 0 ? Vec3(-fa) : fa);
    s += N[a] * (sa.dot(s0) < 0 ? Vec3(-sa) : sa);
  }
  Mat3 Q = Mat3::Identity();
  EXPECT_TRUE(orthonormal_frame(f, s, Q));
  return Q;
}

/// The points a per-node field is checked at: the centroid and the 4-point rule's.
std::vector<Bary> check_points() {
  std::vector<Bary> out = {kCentroid};
  for (const auto& q : tet_rule(2)) out.push_back({q.bary[0], q.bary[1], q.bary[2], q.bary[3]});
  return out;
}

TEST(FileFrame, NodalHelixTurning150DegreesThroughTwoElementsIsFollowed) {
  // Measured (the largest angle between the fibre, sheet or normal line and the
  // analytic frame at α(x), over the centroid and the 4 points of the degree-2 rule of
  // every element; printed below):
  //   P1, 2 elements through the wall: as rotations 3.3e-14°, old linear rule 2.24°;
  //   P2, 2 elements:                  as rotations 2.9e-14°, old linear rule 0.955°;
  //   P2, 1 element (vertices at ±75°, midside 0°): as rotations 2.7e-14°, old linear
  //   rule 65.5° (the −75° fibre, sign-aligned with +75°, reads as +105°: the helix
  //   turns back, the wrong handedness).
  // The rotations are exact to rounding here (the Karcher mean makes the angle Σ N_a α_a,
  // and α is linear in x); bound 1e-9°. The old rule's error must show, so reverting to
  // it fails; so does nlerp without the Karcher step (~0.5° on P1), and aligning a P2
  // element's nodes to vertex 0 instead of along its edges (the 1-element case).
  ScratchDir dir;
  for (const auto& [order, through, old_at_least] : {std::tuple{1, 2, 2.0}, {2, 2, 0.5}, {2, 1, 45.0}}) {
    const TetMesh m = helix_slab(order, through);
    const FileFrame ff = helix_per_node(dir, m);
    double err = 0, err_linear = 0;
    for (int e = 0; e < m.num_tets(); ++e)
      for (const Bary& l : check_points()) {
        const Vec3 X = point(m, e, l);
        const Mat3 Q = ff.at(e, l, X);
        expect_rotation(Q, fmt::format("P{} element {}", order, e));
        err = std::max(err, frame_deg(Q, helix_frame(X[0])));
        err_linear = std::max(err_linear, frame_deg(linear_nodal(ff, m, e, l), helix_frame(X[0])));
      }
    std::printf("helix 150° through %d P%d element(s): max frame error %.3g° as rotations, %.3g° linear\n", through,
                order, err, err_linear);
    EXPECT_LT(err, 1e-9) << "P" << order << ", " << through;
    EXPECT_GT(err_linear, old_at_least) << "P" << order << ", " << through;
  }
}

TEST(FileFrame, HelixPerNodeIsTheRuleFramePerElementTheCentroidFrame) {
  ScratchDir dir;
  const TetMesh m = helix_slab(1);
  // The rule on this slab (endo xmin, epi xmax, base zmax, apex zmin): c = e_y,
  // l = e_z, t = e_x, so its frame is helix_frame(x); the nodal file interpolated as
  // rotations gives it everywhere.
  RuleFrameOptions ro;
  ro.endo = "xmin";
  ro.epi = "xmax";
  ro.apex = "zmin";
  ro.base = "zmax";
  ro.alpha_endo = 75;
  ro.alpha_epi = -75;
  const RuleFrame rule(m, ro);
  const FileFrame nodal = helix_per_node(dir, m);
  // Per element: the analytic frame at each centroid, written and read back.
  std::string csv;
  for (int e = 0; e < m.num_tets(); ++e) {
    const Mat3 Q = helix_frame(point(m, e, kCentroid)[0]);
    csv += fmt::format("{},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g}\n", e + 1, Q(0, 0), Q(1, 0), Q(2, 0),
                       Q(0, 1), Q(1, 1), Q(2, 1));
  }
  write_text(dir / "helix_elements.csv", csv);
  FileFrameOptions o;
  o.file = dir / "helix_elements.csv";
  o.csv = true;
  const FileFrame per_element(m, o);
  double worst_rule = 0;
  for (int e = 0; e < m.num_tets(); ++e) {
    const Mat3 centroid = rule.at(e, kCentroid, point(m, e, kCentroid));
    for (const Bary& l : check_points()) {
      const Vec3 X = point(m, e, l);
      worst_rule = std::max(worst_rule, frame_deg(nodal.at(e, l, X), rule.at(e, l, X)));
      // Per element: the element's frame wherever in it, the rule's at the centroid.
      const Mat3 Q = per_element.at(e, l, X);
      expect_rotation(Q, fmt::format("element {}", e));
      EXPECT_LT(frame_deg(Q, centroid), 1e-9) << e;
    }
  }
  EXPECT_LT(worst_rule, 1e-6) << "nodal file against RuleFrame (degrees)";
}

TEST(FileFrame, NodalFramesOnAQuadraticMeshAreRotationsAndHitTheNodes) {
  // Random frames near one another on a P2 mesh: the P2 weights are negative near the
  // vertices, the mean is still a proper rotation, and at each node it is that node's.
  ScratchDir dir;
  const TetMesh m = make_box_mesh(Vec3(0, 0, 0), Vec3(1, 1, 1), {1, 1, 1}, -1, 1, 2);
  const Written w = random_frames(static_cast<std::size_t>(m.num_nodes()), 9, /*smooth=*/true);
  std::vector<long long> tags;
  for (int i = 1; i <= m.num_nodes(); ++i) tags.push_back(i);
  write_text(dir / "p2.csv", w.csv_rows(tags));
  FileFrameOptions o;
  o.file = dir / "p2.csv";
  o.csv = true;
  o.per = FramePer::node;
  const FileFrame ff(m, o);
  for (int e = 0; e < m.num_tets(); ++e) {
    for (const Bary& l : check_points()) expect_rotation(ff.at(e, l, Vec3()), fmt::format("element {}", e));
    const std::vector<int> n = m.element_nodes(e);
    for (int a = 0; a < 4; ++a) {
      Bary l{};
      l[a] = 1;
      const Mat3 Q = ff.at(e, l, Vec3());
      EXPECT_NEAR((Q.col(0) - w.f[n[a]]).norm(), 0.0, 1e-14);
      EXPECT_NEAR((Q.col(1) - w.s[n[a]]).norm(), 0.0, 1e-14);
    }
    for (int k = 0; k < 6; ++k) {  // at a midside node: its frame
      Bary l{};
      l[kTetEdges[k][0]] = l[kTetEdges[k][1]] = 0.5;
      const Mat3 Q = ff.at(e, l, Vec3());
      EXPECT_NEAR((Q.col(0) - w.f[n[4 + k]]).norm(), 0.0, 1e-14);
      EXPECT_NEAR((Q.col(1) - w.s[n[4 + k]]).norm(), 0.0, 1e-14);
    }
  }
}

TEST(FrameMean, TwoFramesGiveBislerpAndCoaxialTurnsAddAngles) {
  const Mat3 Q0 = turn(Vec3(1, 2, 3), 40);
  const Mat3 Qa = Q0 * turn(Vec3::UnitZ(), 20), Qb = Q0 * turn(Vec3(0.3, -0.2, 1), 80) * turn(Vec3::UnitX(), 180);
  const Eigen::Quaterniond q[3] = {Eigen::Quaterniond(Qa), Eigen::Quaterniond(Qb),
                                   Eigen::Quaterniond(Q0 * turn(Vec3::UnitZ(), -30))};
  for (double t : {0.0, 0.3, 0.5, 1.0}) {
    const double w[2] = {1 - t, t};
    EXPECT_LT(frame_deg(frame_mean(std::span(q, 2), std::span(w, 2)), bislerp(&Qa, &Qb, t)), 1e-9) << t;
  }
  // Three turns about Q0's z by 20°, 80° (turned by π about x: the same lines) and −30°,
  // with affine weights one negative: the turn by the weighted angle.
  const Eigen::Quaterniond c[3] = {Eigen::Quaterniond(Qa),
                                   Eigen::Quaterniond(Mat3(Q0 * turn(Vec3::UnitZ(), 80) * turn(Vec3::UnitX(), 180))),
                                   q[2]};
  const double w[3] = {-0.25, 0.75, 0.5};
  const Mat3 M = frame_mean(std::span(c, 3), std::span(w, 3));
  expect_rotation(M, "mean");
  EXPECT_LT(frame_deg(M, Q0 * turn(Vec3::UnitZ(), -0.25 * 20 + 0.75 * 80 - 0.5 * 30)), 1e-9);
}

// -------------------------------------------------------------------------------------
// Frames per integration point.

/// Per-point CSV rows "tag,point,f,s" of frames[e·np + k], elements in reverse order.
std::string point_rows(const Written& w, int ne, int np, int skip_tag = 0, int skip_point = -1) {
  std::string out = "tag,point,fx,fy,fz,sx,sy,sz\n";
  for (int e = ne - 1; e >= 0; --e)
    for (int k = 0; k < np; ++k) {
      if (e + 1 == skip_tag && (skip_point < 0 || k == skip_point)) continue;
      const std::size_t i = static_cast<std::size_t>(e * np + k);
      out += fmt::format("{},{},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g}\n", e + 1, k, w.f[i][0], w.f[i][1],
                         w.f[i][2], w.s[i][0], w.s[i][1], w.s[i][2]);
    }
  return out;
}

TEST(FileFrame, PerPointCsvRoundTripsAtTheRulePoints) {
  ScratchDir dir;
  const TetMesh m = make_box_mesh(Vec3(0, 0, 0), Vec3(1, 1, 1), {2, 1, 1});  // 12 tets
  const auto rule = tet_rule(2);
  ASSERT_EQ(rule.size(), 4u);
  const Written w = random_frames(48, 4);
  write_text(dir / "points.csv", point_rows(w, 12, 4));
  FileFrameOptions o;
  o.file = dir / "points.csv";
  o.csv = true;
  o.per = FramePer::point;
  o.quadrature_degree = 2;
  const FileFrame ff(m, o);
  ASSERT_EQ(ff.points_per_element(), 4);
  EXPECT_EQ(ff.fibres(), w.f);  // bit for bit, e·4 + k
  EXPECT_EQ(ff.sheets(), w.s);
  for (int e = 0; e < 12; ++e) {
    for (int k = 0; k < 4; ++k) {
      const Vec4& b = rule[k].bary;
      const Mat3 Q = ff.at(e, Bary{b[0], b[1], b[2], b[3]}, Vec3());
      Mat3 read = Mat3::Zero();  // exactly the frame of the vectors as read
      ASSERT_TRUE(orthonormal_frame(w.f[e * 4 + k], w.s[e * 4 + k], read));
      EXPECT_EQ(Q, read) << e << " " << k;
      EXPECT_NEAR((Q.col(0) - w.f[e * 4 + k]).norm(), 0.0, 1e-15) << e << " " << k;
      EXPECT_NEAR((Q.col(1) - w.s[e * 4 + k]).norm(), 0.0, 4e-15) << e << " " << k;
      expect_rotation(Q, fmt::format("element {} point {}", e, k));
    }
    expect_rotation(ff.at(e, kCentroid, Vec3()), fmt::format("element {} centroid (mean)", e));
  }
  // Off the rule's points: the element's mean frame; of equal frames, that frame.
  Written same;
  for (int i = 0; i < 48; ++i) {
    same.f.push_back(w.f[5]);
    same.s.push_back(w.s[5]);
  }
  write_text(dir / "same.csv", point_rows(same, 12, 4));
  o.file = dir / "same.csv";
  const Mat3 mean = FileFrame(m, o).at(3, kCentroid, Vec3());
  EXPECT_NEAR((mean.col(0) - w.f[5]).norm(), 0.0, 1e-12);
  EXPECT_NEAR((mean.col(1) - w.s[5]).norm(), 0.0, 1e-12);
  // The default rule: degree 2(order − 1), one point (the centroid) on a linear mesh.
  write_text(dir / "one.csv", point_rows(w, 12, 1));
  o.file = dir / "one.csv";
  o.quadrature_degree = -1;
  const FileFrame one(m, o);
  ASSERT_EQ(one.points_per_element(), 1);
  EXPECT_NEAR((one.at(7, kCentroid, Vec3()).col(0) - w.f[7]).norm(), 0.0, 1e-15);
}

TEST(FileFrame, BadPerPointFilesNameFileTagAndPoint) {
  ScratchDir dir;
  const TetMesh m = make_box_mesh(Vec3(0, 0, 0), Vec3(1, 1, 1), {2, 1, 1});
  const std::string file = dir / "bad.csv";
  const Written w = random_frames(48, 5);
  const auto read = [&](const std::string& text, int degree = 2) {
    write_text(file, text);
    FileFrameOptions o;
    o.file = file;
    o.csv = true;
    o.per = FramePer::point;
    o.quadrature_degree = degree;
    return input_error([&] { FileFrame ff(m, o); });
  };
  const std::string rule4 = "the quadrature rule of degree 2 has 4 points per element (0..3)";
  std::string msg = read(point_rows(w, 12, 4, 5, 2));  // element 5 lacks point 2
  EXPECT_NE(msg.find(fmt::format("fibre file '{}': no fibre and sheet for element 5 point 2 (and 0 more points "
                                 "missing); the file gives 3 points for element 5, expected 4: {}",
                                 file, rule4)),
            std::string::npos)
      << msg;
  msg = read(point_rows(w, 12, 1));  // written for the 1-point rule, read with the 4-point one
  EXPECT_NE(msg.find(fmt::format("fibre file '{}': no fibre and sheet for element 1 point 1 (and 35 more points "
                                 "missing); the file gives 1 points for element 1, expected 4: {}",
                                 file, rule4)),
            std::string::npos)
      << msg;
  msg = read(point_rows(w, 12, 4), 0);  // written for the 4-point rule, read with the 1-point one
  EXPECT_NE(msg.find(fmt::format("fibre file '{}' line 3: element 12 point 1: no such point: the quadrature rule of "
                                 "degree 0 has 1 points per element (0..0), got point 1; expected a file written for "
                                 "that rule (formulation.quadrature_degree)",
                                 file)),
            std::string::npos)
      << msg;
  msg = read(point_rows(w, 12, 4) + "7,2,1,0,0,0,1,0\n");
  EXPECT_NE(msg.find("line 50: element 7 point 2 appears again (first at line"), std::string::npos) << msg;
  msg = read(point_rows(w, 12, 4) + "13,0,1,0,0,0,1,0\n");
  EXPECT_NE(msg.find(fmt::format("fibre file '{}' line 50: element 13 point 0 is not a element of the mesh", file)),
            std::string::npos)
      << msg;
  msg = read(point_rows(w, 12, 4, 3, 1) + "3,1.5,1,0,0,0,1,0\n");
  EXPECT_NE(msg.find("element 3 point 1.5: no such point"), std::string::npos) << msg;
  msg = read(point_rows(w, 12, 4, 9, 0) + "9,0,1,0,0,0,0.9,0\n");
  EXPECT_NE(msg.find("element 9 point 0: sheet vector (0, 0.9, 0) has length 0.9, expected a unit vector"),
            std::string::npos)
      << msg;
  msg = read("1,0,1,0,0,0,1\n");
  EXPECT_NE(msg.find("expected 8 comma-separated numbers tag,point,fx,fy,fz,sx,sy,sz"), std::string::npos) << msg;
  // Per point from Gmsh views is not read.
  FileFrameOptions g;
  g.file = file;
  g.per = FramePer::point;
  msg = input_error([&] { FileFrame ff(m, g); });
  EXPECT_NE(msg.find(fmt::format("fibre file '{}': frames per point are read from a CSV", file)), std::string::npos)
      << msg;
}

// -------------------------------------------------------------------------------------
// The spec keys (checked against the schema on every read) and the VTU output.

FrameFieldSpec read_frame_json(const json& frame, const TetMesh& m, const std::string& base_dir = ".") {
  const json j = {{"frame", frame}};
  SpecNode root(j, "", run_spec_schema());
  SpecNode f = root.child("frame");
  FrameFieldSpec spec = read_frame_field_spec(f, m, base_dir, "");
  f.finish();
  return spec;
}

TEST(FrameSpecKeys, RuleAndFileKindsReadTheirKeysWithDefaults) {
  const TetMesh m = slab();
  const FrameFieldSpec rule = read_frame_json(
      {{"kind", "rule"}, {"endo", "xmin"}, {"epi", "xmax"}, {"base", "zmax"}, {"apex", "zmin"}, {"beta_epi", -20}}, m);
  ASSERT_EQ(rule.kind, FrameFieldSpec::Kind::rule);
  EXPECT_EQ(rule.rule.alpha_endo, 60.0);
  EXPECT_EQ(rule.rule.alpha_epi, -60.0);
  EXPECT_EQ(rule.rule.beta_endo, 0.0);
  EXPECT_EQ(rule.rule.beta_epi, -20.0);
  EXPECT_EQ(rule.rule.rv_endo, "");
  const auto field = make_frame_field(rule, m);
  EXPECT_NEAR(helix_deg(field->at(0, kCentroid, Vec3())), helix_deg(RuleFrame(m, rule.rule).at(0, kCentroid, Vec3())),
              0.0);

  const std::string msg = input_error([&] {
    read_frame_json({{"kind", "rule"}, {"endo", "xmn"}, {"epi", "xmax"}, {"base", "zmax"}, {"apex", "zmin"}}, m);
  });
  EXPECT_NE(msg.find("/frame/endo: got \"xmn\", expected a named surface or node set of the mesh (xmax, xmin, ymax, "
                     "ymin, zmax, zmin); did you mean \"xmin\"?"),
            std::string::npos)
      << msg;

  ScratchDir dir;
  const TetMesh box = make_box_mesh(Vec3(0, 0, 0), Vec3(1, 1, 1), {2, 1, 1});
  write_text(dir / "f.csv", good_rows());
  const FrameFieldSpec file =
      read_frame_json({{"kind", "file"}, {"file", "f.csv"}, {"format", "csv"}}, box, dir / "");
  ASSERT_EQ(file.kind, FrameFieldSpec::Kind::file);
  EXPECT_EQ(file.file.per, FramePer::element);
  EXPECT_EQ(file.file.fibre_view, "fibre");
  ASSERT_TRUE(file.loaded);
  EXPECT_EQ(make_frame_field(file, box)->at(3, kCentroid, Vec3()), Mat3::Identity());
  // Constant and rotating frames: the rule FrameSpec::at applied (moved to AnalyticFrame).
  const FrameFieldSpec rot = read_frame_json(
      {{"kind", "rotating"}, {"axis", {1, 0, 0}}, {"coordinate", {0, 1, 0}}, {"from", {0, -60}}, {"to", {1, 60}}}, m);
  const Mat3 Q = make_frame_field(rot, m)->at(0, kCentroid, Vec3(0, 0.75, 0));
  EXPECT_NEAR((Q.col(0) - Vec3::UnitX()).norm(), 0.0, 1e-15);
  EXPECT_NEAR((Q.col(1) - Vec3(0, std::cos(30 * kDeg), std::sin(30 * kDeg))).norm(), 0.0, 1e-15);
  const std::string unknown = input_error([&] {
    read_frame_json({{"kind", "rule"}, {"endo", "xmin"}, {"epi", "xmax"}, {"base", "zmax"}, {"apex", "zmin"},
                     {"fibre", {1, 0, 0}}},
                    m);
  });
  EXPECT_NE(unknown.find("unknown key 'fibre' in /frame"), std::string::npos) << unknown;
}

TEST(FrameSpecKeys, PerPointNeedsCsvAndNumbersPointsByTheQuadratureDegree) {
  ScratchDir dir;
  const TetMesh box = make_box_mesh(Vec3(0, 0, 0), Vec3(1, 1, 1), {2, 1, 1});
  write_text(dir / "p.csv", point_rows(random_frames(48, 6), 12, 4));
  const json frame = {{"kind", "file"}, {"file", "p.csv"}, {"format", "csv"}, {"per", "point"}};
  const json j = {{"frame", frame}};
  SpecNode root(j, "", run_spec_schema());
  SpecNode f = root.child("frame");
  const FrameFieldSpec spec = read_frame_field_spec(f, box, dir / "", "", 2);
  f.finish();
  EXPECT_EQ(spec.file.per, FramePer::point);
  EXPECT_EQ(spec.file.quadrature_degree, 2);
  ASSERT_TRUE(spec.loaded);
  // The default degree on a linear mesh is 0 (one point): this file has four.
  std::string msg = input_error([&] { read_frame_json(frame, box, dir / ""); });
  EXPECT_NE(msg.find("element 12 point 1: no such point: the quadrature rule of degree 0 has 1 points"),
            std::string::npos)
      << msg;
  json gmsh = frame;
  gmsh["format"] = "gmsh";
  msg = input_error([&] { read_frame_json(gmsh, box, dir / ""); });
  EXPECT_NE(msg.find("/frame/format: got \"gmsh\", expected \"csv\" for frames per point"), std::string::npos) << msg;
}

TEST(FrameOutput, VtuCellVectorsAreTheCentroidFrames) {
  ScratchDir dir;
  const TetMesh m = slab();
  const RuleFrame rule(m, slab_rule());
  const auto Q = frames_at_centroids(rule, m);
  ASSERT_EQ(Q.size(), static_cast<std::size_t>(m.num_tets()));
  EXPECT_NEAR(helix_deg(Q[0]), 60.0 - 120.0 * point(m, 0, kCentroid)[0], 1e-9);
  VtuFields cells;
  add_frame_cell_fields(cells, Q);
  ASSERT_EQ(cells.fields().size(), 2u);
  EXPECT_EQ(cells.fields()[0].name, "fibre");
  EXPECT_EQ(cells.fields()[1].name, "sheet");
  EXPECT_EQ(cells.fields()[1].values[3 * 5], Q[5](0, 1));
  write_vtu(dir / "fibres.vtu", m, {}, cells);
  const std::string text = slurp(dir / "fibres.vtu");
  EXPECT_NE(text.find("Name=\"fibre\" NumberOfComponents=\"3\""), std::string::npos);
  EXPECT_NE(text.find("Name=\"sheet\" NumberOfComponents=\"3\""), std::string::npos);
}

}  // namespace
}  // namespace fe2
