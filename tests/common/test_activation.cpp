// Activation times (common/activation/): the eikonal solver reproduces planar fronts
// exactly (isotropic and anisotropic, on regular and perturbed tets), converges for a
// point source, activates the LV wall from its endocardium; the field interpolates;
// file-given times round-trip and bad files are refused; the spec reader agrees with
// its schema and names bad keys.
#include "common/activation/ActivationField.h"
#include "common/activation/activation_file.h"
#include "common/activation/activation_schema.h"
#include "common/activation/activation_spec.h"
#include "common/activation/eikonal.h"
#include "common/error.h"
#include "common/fibres/AnalyticFrame.h"
#include "common/fibres/RuleFrame.h"
#include "common/mesh/box_mesh.h"
#include "common/mesh/gmsh_reader.h"
#include "common/mesh/lv_mesh.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

namespace fe2 {
namespace {

namespace fs = std::filesystem;

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
  std::string str() const { return path_.string(); }

 private:
  fs::path path_;
};

void write_text(const std::string& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

template <class F>
std::string input_error(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "nothing thrown";
}

/// Moves every interior vertex of a box mesh by up to `fraction` of the cell size h in
/// each direction (fixed seed); every tet stays positive (checked by the caller).
void perturb_interior(TetMesh& m, const Vec3& lo, const Vec3& hi, double h, double fraction) {
  std::mt19937 gen(20240917);
  std::uniform_real_distribution<double> u(-fraction * h, fraction * h);
  for (Vec3& p : m.nodes) {
    const bool interior = ((p - lo).array() > 1e-9).all() && ((hi - p).array() > 1e-9).all();
    const Vec3 d(u(gen), u(gen), u(gen));
    if (interior) p += d;
  }
}

bool all_positive(const TetMesh& m) {
  for (int e = 0; e < m.num_tets(); ++e)
    if (!(tet_signed_volume(m, e) > 0)) return false;
  return true;
}

/// The vertices of a named face (not its quadratic edge nodes), each a source.
std::vector<EikonalSource> face_sources(const TetMesh& m, const std::string& face, double time) {
  std::vector<int> vs;
  for (const auto& tri : m.faces.at(face)) vs.insert(vs.end(), tri.begin(), tri.end());
  std::sort(vs.begin(), vs.end());
  vs.erase(std::unique(vs.begin(), vs.end()), vs.end());
  std::vector<EikonalSource> out;
  for (int v : vs) out.push_back({v, time});
  return out;
}

std::vector<int> boundary_vertices(const TetMesh& m) {
  std::vector<int> out;
  for (const char* f : {"xmin", "xmax", "ymin", "ymax", "zmin", "zmax"})
    for (int v : m.node_sets.at(f)) out.push_back(v);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

// ---- planar fronts: exact on any tet mesh --------------------------------------------

TEST(Eikonal, IsotropicPlanarFrontFromAFaceIsExact) {
  const double v = 437.0;  // mesh units per second
  const Vec3 lo(0, 0, 0), hi(2, 1, 1.5);
  for (const bool perturbed : {false, true}) {
    TetMesh m = make_box_mesh(lo, hi, {10, 6, 7});
    if (perturbed) perturb_interior(m, lo, hi, 1.0 / 7, 0.2);
    ASSERT_TRUE(all_positive(m));
    const std::vector<Mat3> D(m.num_tets(), conduction_metric(Mat3::Identity(), v, v, v));
    EikonalStats st;
    const std::vector<double> t = solve_eikonal(m, D, face_sources(m, "xmin", 0.0), {}, &st);
    double worst = 0;
    for (int i = 0; i < m.num_nodes(); ++i) {
      const double exact = m.nodes[i][0] / v;
      if (exact == 0) {
        EXPECT_EQ(t[i], 0.0) << i;
        continue;
      }
      worst = std::max(worst, std::abs(t[i] - exact) / exact);
    }
    EXPECT_LE(worst, 1e-12) << (perturbed ? "perturbed" : "regular");
    std::printf("isotropic planar front (%s): max relative error %.3g, %lld pops for %d vertices\n",
                perturbed ? "perturbed" : "regular", worst, st.pops, m.num_nodes());
  }
}

TEST(Eikonal, QuadraticEdgeNodesGetTheMeanOfTheirEdge) {
  const double v = 250.0;
  const TetMesh m = make_box_mesh(Vec3(0, 0, 0), Vec3(1, 1, 1), {3, 3, 3}, -1, 1, /*order=*/2);
  const std::vector<Mat3> D(m.num_tets(), conduction_metric(Mat3::Identity(), v, v, v));
  const std::vector<double> t = solve_eikonal(m, D, face_sources(m, "xmin", 0.01));
  ASSERT_FALSE(m.edge_nodes.empty());
  for (const auto& [edge, node] : m.edge_nodes) {
    EXPECT_EQ(t[node], 0.5 * (t[edge.first] + t[edge.second])) << node;
    EXPECT_NEAR(t[node], 0.01 + m.nodes[node][0] / v, 1e-15) << node;  // a linear front: the midpoint is exact
  }
}

/// A frame whose fibre makes the angle θ with the front normal n (the sheet completes
/// the plane of f and n, the sheet normal is n-free), its metric, and the planar front
/// speed along n: t = g·x with g ∥ n and gᵀDg = 1 gives g = n / sqrt(nᵀDn), so the
/// front moves along n at v_n = sqrt(nᵀDn) = sqrt(v_f² cos²θ + v_s² sin²θ).
struct TiltedMedium {
  Vec3 n;
  Mat3 Q, D;
  double vf = 610, vs = 230, vn = 140, speed;
  explicit TiltedMedium(double theta) {
    n = Vec3(1.0, 0.3, -0.2).normalized();
    const Vec3 u = n.cross(Vec3::UnitZ()).normalized();  // ⟂ n
    const Vec3 f = std::cos(theta) * n + std::sin(theta) * u;
    const Vec3 s = -std::sin(theta) * n + std::cos(theta) * u;
    Q.col(0) = f;
    Q.col(1) = s;
    Q.col(2) = f.cross(s);
    D = conduction_metric(Q, vf, vs, vn);
    speed = std::sqrt(n.dot(D * n));
  }
};

TEST(Eikonal, AnisotropicPlanarFrontIsExact) {
  const double theta = 35.0 * M_PI / 180.0;
  const TiltedMedium med(theta);
  // The analytic speed from the metric equals the closed form in θ.
  ASSERT_NEAR(med.speed, std::sqrt(std::pow(med.vf * std::cos(theta), 2) + std::pow(med.vs * std::sin(theta), 2)),
              1e-9);
  const Vec3 lo(0, 0, 0), hi(1.2, 1, 0.8);
  for (const bool perturbed : {false, true}) {
    TetMesh m = make_box_mesh(lo, hi, {9, 8, 6});
    if (perturbed) perturb_interior(m, lo, hi, 0.8 / 6, 0.2);
    ASSERT_TRUE(all_positive(m));
    // The planar front on the whole boundary (its back-characteristics leave the box
    // through the side faces, so a single face would not carry a plane wave); the
    // interior follows from the local solver alone.
    const auto exact = [&](int i) { return 0.002 + med.n.dot(m.nodes[i] - lo) / med.speed; };
    const std::vector<int> boundary = boundary_vertices(m);
    std::vector<EikonalSource> src;
    for (int v : boundary) src.push_back({v, exact(v)});
    const std::vector<double> t = solve_eikonal(m, std::vector<Mat3>(m.num_tets(), med.D), src);
    double worst = 0;
    int interior = 0;
    for (int i = 0; i < m.num_nodes(); ++i) {
      worst = std::max(worst, std::abs(t[i] - exact(i)) / exact(i));
      interior += !std::binary_search(boundary.begin(), boundary.end(), i);
    }
    EXPECT_GT(interior, 200);
    EXPECT_LE(worst, 1e-10) << (perturbed ? "perturbed" : "regular");
    std::printf("anisotropic planar front (%s, v_n = %.6g): max relative error %.3g over %d interior vertices\n",
                perturbed ? "perturbed" : "regular", med.speed, worst, interior);
    // The same front in an isotropic medium at the fibre speed arrives earlier: the
    // metric matters (a solver that drops it fails the test above).
    const std::vector<double> iso =
        solve_eikonal(m, std::vector<Mat3>(m.num_tets(), conduction_metric(Mat3::Identity(), 610, 610, 610)), src);
    const int mid = m.num_nodes() / 2;
    EXPECT_GT(std::abs(iso[mid] - t[mid]), 1e-5);
  }
}

TEST(Eikonal, LocalUpdateIsExactForAPlaneWaveAndFallsBackToEdges) {
  const TiltedMedium med(0.6);
  const Mat3 M = med.D.inverse();
  const Vec3 g = med.n / med.speed;
  // A face well upwind of x, the characteristic D g through x crossing its interior.
  const Vec3 x(0.3, 0.2, 0.1);
  const Vec3 foot = x - 0.5 * (med.D * g);
  Vec3 y[3] = {foot + Vec3(0.1, 0.05, 0.0), foot + Vec3(-0.07, 0.1, 0.02), foot + Vec3(-0.03, -0.15, -0.02)};  // foot: centroid
  double t[3];
  for (int i = 0; i < 3; ++i) t[i] = g.dot(y[i]);
  EXPECT_NEAR(eikonal_simplex_update(x, y, t, 3, M), g.dot(x), 1e-15);
  // Move the face so the characteristic passes just outside one edge: the value is then
  // larger than the plane wave's (the neighbouring tet gives that) and is the minimum on
  // that edge, in its interior (below both its end points).
  const Vec3 c = med.D * g;
  const Vec3 e1 = c.cross(Vec3::UnitZ()).normalized(), e2 = c.cross(e1).normalized();
  y[0] = foot - 0.1 * e1 + 0.02 * e2;
  y[1] = foot + 0.1 * e1 + 0.02 * e2;
  y[2] = foot + 0.03 * e1 + 0.2 * e2;
  for (int i = 0; i < 3; ++i) t[i] = g.dot(y[i]);
  const double face = eikonal_simplex_update(x, y, t, 3, M);
  EXPECT_GT(face, g.dot(x) + 1e-9);
  const double edge01 = eikonal_simplex_update(x, y, t, 2, M);
  EXPECT_EQ(face, edge01);
  EXPECT_LT(edge01, std::min(eikonal_simplex_update(x, y, t, 1, M), eikonal_simplex_update(x, y + 1, t + 1, 1, M)) - 1e-9);
}

// ---- curved fronts: convergence -------------------------------------------------------

/// Max and mean error (length units) of a point source at the box centre on n³ cells.
/// start_radius > 0: the vertices within it start at their exact times (a spherical
/// front of that radius, the usual way to keep the source's singularity out of a
/// convergence study); 0: the source is the centre vertex alone.
std::pair<double, double> point_source_error(int n, double start_radius) {
  const double v = 600.0;
  const Vec3 x0(0.5, 0.5, 0.5);
  const TetMesh m = make_box_mesh(Vec3(0, 0, 0), Vec3(1, 1, 1), {n, n, n});
  std::vector<EikonalSource> src;
  for (int i = 0; i < m.num_nodes(); ++i) {
    const double r = (m.nodes[i] - x0).norm();
    if (r < 1e-12 || r <= start_radius) src.push_back({i, r / v});
  }
  const std::vector<double> t =
      solve_eikonal(m, std::vector<Mat3>(m.num_tets(), conduction_metric(Mat3::Identity(), v, v, v)), src);
  double max = 0, sum = 0;
  for (int i = 0; i < m.num_nodes(); ++i) {
    const double exact = (m.nodes[i] - x0).norm() / v;
    EXPECT_GE(t[i], exact * (1 - 1e-12)) << i;  // a discrete path is never shorter than the straight one
    max = std::max(max, (t[i] - exact) * v);
    sum += (t[i] - exact) * v;
  }
  return {max, sum / m.num_nodes()};
}

TEST(Eikonal, PointSourceConvergesUnderRefinement) {
  // From a single vertex the error is O(h log 1/h) (the front's curvature is 1/r, and
  // the first-order local errors h²/r add up along a ray): observed orders about 0.6
  // here. Started on a sphere of radius 0.2 the front is smooth and the error O(h).
  for (const double radius : {0.0, 0.2}) {
    std::vector<double> max_errors;
    for (const int n : {8, 16, 32}) {
      const auto [max, mean] = point_source_error(n, radius);
      max_errors.push_back(max);
      std::printf("point source (start radius %.1f), %d^3 cells: max error %.4g, mean error %.4g (length units)\n",
                  radius, n, max, mean);
    }
    for (std::size_t k = 1; k < max_errors.size(); ++k) {
      const double order = std::log2(max_errors[k - 1] / max_errors[k]);
      std::printf("  observed order %.3f\n", order);
      EXPECT_GE(order, radius > 0 ? 0.8 : 0.55) << "radius " << radius << ", refinement " << k;
    }
  }
}

// ---- the LV wall from its endocardium --------------------------------------------------

/// Distance from (ρ, z) to the ellipse ρ²/a² + z²/c² = 1 (the spheroid's meridian), by
/// a fine scan of the ellipse's angle and golden-section refinement.
double distance_to_spheroid(const Vec3& p, double a, double c) {
  const double rho = std::hypot(p[0], p[1]), z = p[2];
  const auto d2 = [&](double u) { return std::pow(rho - a * std::sin(u), 2) + std::pow(z - c * std::cos(u), 2); };
  const int samples = 2000;
  int best = 0;
  for (int i = 1; i <= samples; ++i)
    if (d2(M_PI * i / samples) < d2(M_PI * best / samples)) best = i;
  double lo = M_PI * std::max(0, best - 1) / samples, hi = M_PI * std::min(samples, best + 1) / samples;
  const double r = 0.5 * (std::sqrt(5.0) - 1);
  for (int it = 0; it < 100; ++it) {
    const double m1 = hi - r * (hi - lo), m2 = lo + r * (hi - lo);
    (d2(m1) < d2(m2) ? hi : lo) = d2(m1) < d2(m2) ? m2 : m1;
  }
  return std::sqrt(d2(0.5 * (lo + hi)));
}

struct LvRun {
  double epi_mean = 0, exact_mean = 0, max_error = 0, seconds = 0;
  int vertices = 0;
};

LvRun activate_lv_from_endo(const LvMeshParams& p, double v, bool check_lines) {
  const TetMesh m = make_lv_mesh(p);
  std::vector<EikonalSource> src;
  for (const auto& tri : m.faces.at("endo"))
    for (int n : tri) src.push_back({n, 0.0});
  const std::vector<Mat3> D(m.num_tets(), conduction_metric(Mat3::Identity(), v, v, v));
  const auto start = std::chrono::steady_clock::now();
  const std::vector<double> t = solve_eikonal(m, D, src);
  LvRun r;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  r.vertices = static_cast<int>(m.vertices().size());
  for (const auto& tri : m.faces.at("endo"))
    for (int n : tri) EXPECT_EQ(t[n], 0.0) << n;
  if (check_lines) {
    // Transmural lines: node (nt+1) + i + (nt+1)(k + nc(j−1)) is shell i of ring j,
    // azimuth k (lv_mesh.cpp), i = 0 on endo; times rise strictly along every line.
    const int nt = p.transmural, nc = p.circumferential;
    int lines = 0;
    for (int j = 1; j <= p.longitudinal; ++j)
      for (int k = 0; k < nc; ++k, ++lines)
        for (int i = 1; i <= nt; ++i) {
          const int a = (nt + 1) + (i - 1) + (nt + 1) * (k + nc * (j - 1)), b = a + 1;
          EXPECT_GT(t[b], t[a]) << "ring " << j << " azimuth " << k << " shell " << i;
        }
    EXPECT_EQ(lines, p.longitudinal * nc);
  }
  // The exact time at an epi vertex is its distance to the endocardial spheroid over v
  // (the wall's convexity keeps the straight path inside the wall; the base plane is
  // above every nearest point, the spheroid's normal leaning toward the base there).
  std::vector<int> epi;
  for (const auto& tri : m.faces.at("epi"))
    for (int n : tri) epi.push_back(n);
  std::sort(epi.begin(), epi.end());
  epi.erase(std::unique(epi.begin(), epi.end()), epi.end());
  for (int n : epi) {
    const double exact = distance_to_spheroid(m.nodes[n], p.endo_short, p.endo_long) / v;
    r.epi_mean += t[n] / epi.size();
    r.exact_mean += exact / epi.size();
    r.max_error = std::max(r.max_error, std::abs(t[n] - exact));
  }
  return r;
}

TEST(Eikonal, LvFromEndoReachesEpiAtWallThicknessOverVelocity) {
  const double v = 600.0;  // mm/s
  // Refinements in all three directions at once; the error of the epicardial mean is
  // first order (a curved front; the polyhedral endocardium adds O(h²)).
  std::vector<LvRun> runs;
  for (const int r : {1, 2, 4}) {
    LvMeshParams p;
    p.circumferential = 16 * r;
    p.longitudinal = 8 * r;
    p.transmural = 2 * r;
    runs.push_back(activate_lv_from_endo(p, v, true));
    const LvRun& x = runs.back();
    std::printf("LV %dx%dx%d (%d vertices): epi mean %.6g ms, exact (wall thickness / v) %.6g ms, "
                "mean error %.3g ms, max error %.3g ms, solve %.3f s\n",
                p.circumferential, p.longitudinal, p.transmural, x.vertices, 1e3 * x.epi_mean, 1e3 * x.exact_mean,
                1e3 * (x.epi_mean - x.exact_mean), 1e3 * x.max_error, x.seconds);
  }
  // The exact transit: the wall is 3 mm thick at the apex and the equator and thinner
  // in between (the two ellipsoids are not parallel): a mean of 2.91 mm, 4.85 ms.
  EXPECT_GT(runs[2].exact_mean * v, 2.8);
  EXPECT_LT(runs[2].exact_mean * v, 3.0);
  // Measured error of the epicardial mean (printed above): 0.109, 0.059, 0.031 ms, i.e.
  // 2.3 %, 1.2 %, 0.64 % of the transit, halving with h: the first-order error of a
  // curved (expanding) front, discrete paths being longer than straight ones (the
  // polyhedral endocardium adds O(h²)). Bound: 1 % of the transit at the finest mesh
  // (1.5 x the measured error), and a factor >= 1.6 per refinement.
  const double e0 = runs[0].epi_mean - runs[0].exact_mean;
  const double e1 = runs[1].epi_mean - runs[1].exact_mean;
  const double e2 = runs[2].epi_mean - runs[2].exact_mean;
  EXPECT_GT(e2, 0.0);
  EXPECT_LE(e2, 0.01 * runs[2].exact_mean);
  EXPECT_GE(e0 / e1, 1.6);
  EXPECT_GE(e1 / e2, 1.6);
}

// Not run by default: solve times at a fine LV, isotropic and with rule-based fibres
// (Bayer 2012, ±60°) at the default orthotropic velocities (for the report).
TEST(Eikonal, DISABLED_LvSolveTimeFine) {
  for (const int r : {4, 8}) {
    LvMeshParams p;
    p.circumferential = 16 * r;
    p.longitudinal = 8 * r;
    p.transmural = 2 * r;
    const LvRun x = activate_lv_from_endo(p, 600.0, false);
    std::printf("LV %dx%dx%d isotropic (%d vertices): epi mean error %.3g ms, solve %.3f s\n", p.circumferential,
                p.longitudinal, p.transmural, x.vertices, 1e3 * (x.epi_mean - x.exact_mean), x.seconds);
    const TetMesh m = make_lv_mesh(p);
    const RuleFrame frames(m, RuleFrameOptions{});
    std::vector<Mat3> D(m.num_tets());
    for (int e = 0; e < m.num_tets(); ++e)
      D[e] = conduction_metric(frames.at(e, kCentroid, Vec3()), kDefaultVelocityFibre, kDefaultVelocitySheet,
                               kDefaultVelocityNormal);
    const auto start = std::chrono::steady_clock::now();
    EikonalStats st;
    const std::vector<double> t = solve_eikonal(m, D, face_sources(m, "endo", 0.0), {}, &st);
    const double sec = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    double tmax = 0;
    for (int v : m.vertices()) tmax = std::max(tmax, t[v]);
    std::printf("LV %dx%dx%d rule fibres (%d vertices): latest %.4g ms, %.2f pops per vertex, solve %.3f s\n",
                p.circumferential, p.longitudinal, p.transmural, x.vertices, 1e3 * tmax,
                double(st.pops) / x.vertices, sec);
  }
}

// ---- robustness ------------------------------------------------------------------------

TEST(Eikonal, TwoSolvesGiveTheSameBits) {
  const TiltedMedium med(1.1);
  TetMesh m = make_box_mesh(Vec3(0, 0, 0), Vec3(1, 1, 1), {7, 7, 7});
  perturb_interior(m, Vec3(0, 0, 0), Vec3(1, 1, 1), 1.0 / 7, 0.2);
  std::vector<Mat3> D(m.num_tets());
  for (int e = 0; e < m.num_tets(); ++e)  // element-wise varying fibres
    D[e] = conduction_metric(Eigen::AngleAxisd(0.1 * e, Vec3(0.2, 0.5, 1).normalized()).toRotationMatrix() * med.Q,
                             600 + e % 7, 200, 150);
  const std::vector<EikonalSource> src = {{0, 0.0}, {m.num_nodes() - 1, 0.0005}, {m.num_nodes() / 2, 0.001}};
  EikonalStats st;
  const std::vector<double> a = solve_eikonal(m, D, src, {}, &st), b = solve_eikonal(m, D, src);
  std::printf("varying anisotropic medium: %lld pops, %lld updates for %d vertices\n", st.pops, st.updates,
              m.num_nodes());
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(double)), 0);
}

TEST(Eikonal, UnreachableVerticesAndTheIterationCapAreErrors) {
  // Two boxes that share no vertex: the second never activates.
  TetMesh m = make_box_mesh(Vec3(0, 0, 0), Vec3(1, 1, 1), {2, 2, 2});
  const TetMesh other = make_box_mesh(Vec3(3, 0, 0), Vec3(4, 1, 1), {1, 1, 1});
  const int off = m.num_nodes();
  for (const Vec3& p : other.nodes) m.nodes.push_back(p);
  for (auto t : other.tets) {
    for (int& v : t) v += off;
    m.tets.push_back(t);
  }
  const std::vector<Mat3> D(m.num_tets(), Mat3::Identity());
  std::string msg = input_error([&] { solve_eikonal(m, D, {{0, 0.0}}); });
  EXPECT_NE(msg.find("8 of 35 mesh vertices are not reachable from any source (e.g. node 27 at (3, 0, 0))"),
            std::string::npos)
      << msg;
  msg = input_error([&] { solve_eikonal(m, D, {{35, 0.0}}); });
  EXPECT_NE(msg.find("eikonal source at node 35: not a vertex"), std::string::npos) << msg;
  // A cap too small for the solve: a clear error, not a hang.
  EikonalOptions opt;
  opt.max_pops_per_vertex = 0;
  try {
    solve_eikonal(m, D, {{0, 0.0}}, opt);
    ADD_FAILURE() << "nothing thrown";
  } catch (const NumericalError& e) {
    EXPECT_NE(std::string(e.what()).find("eikonal solve did not converge: 0 vertex evaluations for 35 vertices"),
              std::string::npos)
        << e.what();
  }
}

// ---- the field ---------------------------------------------------------------------------

TEST(ActivationField, InterpolatesVertexTimesAndKeepsElementTimes) {
  const double v = 300.0;
  const TetMesh m = make_box_mesh(Vec3(0, 0, 0), Vec3(1, 1, 1), {3, 2, 2});
  const std::vector<Mat3> D(m.num_tets(), conduction_metric(Mat3::Identity(), v, v, v));
  const ActivationField f = ActivationField::per_vertex(m, solve_eikonal(m, D, face_sources(m, "xmin", 0.0)));
  const Bary l = {0.1, 0.2, 0.3, 0.4};
  for (int e = 0; e < m.num_tets(); ++e) {
    Vec3 X = Vec3::Zero();
    for (int i = 0; i < 4; ++i) X += l[i] * m.nodes[m.tets[e][i]];
    EXPECT_NEAR(f.at(e, l), X[0] / v, 1e-15) << e;
  }
  EXPECT_EQ(f.node_times(m).size(), m.nodes.size());
  EXPECT_EQ(ActivationField::uniform(0.25).at(3, l), 0.25);
  const ActivationField pe = ActivationField::per_element({0.1, 0.2, 0.3});
  EXPECT_EQ(pe.at(1, l), 0.2);
  EXPECT_THROW(pe.at(3, l), Error);
}

// ---- file kind ---------------------------------------------------------------------------

TEST(ActivationFile, CsvRoundTripsBitForBit) {
  ScratchDir dir;
  const TetMesh m = make_box_mesh(Vec3(0, 0, 0), Vec3(1, 1, 1), {2, 1, 1});  // 12 tets
  std::vector<double> times;
  std::string csv = "# activation times\ntag,time\n";
  for (int e = m.num_tets() - 1; e >= 0; --e) {  // any order
    const double t = 0.001 * std::sqrt(2.0 + e) + 1.0 / 3.0;
    csv += fmt::format("{},{:.17g}\n", e + 1, t);
  }
  for (int e = 0; e < m.num_tets(); ++e) times.push_back(0.001 * std::sqrt(2.0 + e) + 1.0 / 3.0);
  write_text(dir / "act.csv", csv);
  const json j = {{"kind", "file"}, {"file", "act.csv"}, {"format", "csv"}};
  SpecNode node(j, "/activation", *activation_schema());
  const auto f = read_activation(node, m, nullptr, dir.str(), "");
  ASSERT_EQ(f->kind(), ActivationField::Kind::per_element);
  for (int e = 0; e < m.num_tets(); ++e) EXPECT_EQ(f->at(e, kCentroid), times[e]) << e;
  EXPECT_EQ(f->element_times(m), times);
}

TEST(ActivationFile, BadCsvFilesAreRefusedNamingFileAndTag) {
  ScratchDir dir;
  const TetMesh m = make_box_mesh(Vec3(0, 0, 0), Vec3(1, 1, 1), {1, 1, 1});  // 6 tets
  const std::string file = dir / "a.csv";
  const auto read = [&](const std::string& text) {
    write_text(file, text);
    ActivationFileOptions o;
    o.file = file;
    o.csv = true;
    return input_error([&] { read_activation_file(m, o); });
  };
  EXPECT_EQ(read("1,0\n2,0\n3,0\n4,0\n5,0\n6,0.5\n"), "nothing thrown");
  std::string msg = read("1,0\n2,0\n3,0\n5,0\n6,0\n");
  EXPECT_NE(msg.find(fmt::format("activation file '{}': no time for element 4 (and 0 more), expected one for every "
                                 "element of the mesh (6 elements)",
                                 file)),
            std::string::npos)
      << msg;
  msg = read("1,0\n2,0\n3,0\n4,0\n5,0\n6,0\n2,0.1\n");
  EXPECT_NE(msg.find(fmt::format("activation file '{}' line 7: element 2 appears again (first at line 2)", file)),
            std::string::npos)
      << msg;
  msg = read("1,0\n2,0\n3,abc\n4,0\n5,0\n6,0\n");
  EXPECT_NE(msg.find(fmt::format("activation file '{}' line 3: got '3,abc', expected 2 comma-separated numbers "
                                 "tag,time",
                                 file)),
            std::string::npos)
      << msg;
  msg = read("1,0\n2,0\n3,0\n4,-0.5\n5,0\n6,0\n");
  EXPECT_NE(msg.find(fmt::format("activation file '{}' line 4: element 4: time -0.5, expected a finite activation "
                                 "time >= 0 (s)",
                                 file)),
            std::string::npos)
      << msg;
  msg = read("1,0\n2,0\n3,0\n4,0\n5,0\n6,0\n9,0\n");
  EXPECT_NE(msg.find("line 7: element 9 is not an element of the mesh (6 elements, tags 1..6)"), std::string::npos)
      << msg;
}

TEST(ActivationFile, GmshElementViewRoundTrips) {
  ScratchDir dir;
  const std::string mesh_file = dir / "two_tets.msh";
  // Tags 6, 7 are the tets; triangle 5 is in the view too and is not ours to read.
  write_text(mesh_file, slurp(std::string(FE2_SOURCE_DIR) + "/tests/data/two_tets.msh") +
                            "$ElementData\n1\n\"activation\"\n1\n0.0\n3\n0\n1\n3\n7 0.0123456789012345678\n"
                            "5 9\n6 0.25\n$EndElementData\n");
  const TetMesh m = read_gmsh_tets(mesh_file);
  const json j = {{"kind", "file"}, {"file", "two_tets.msh"}};
  SpecNode node(j, "/activation", *activation_schema());
  const auto f = read_activation(node, m, nullptr, dir.str(), mesh_file);
  EXPECT_EQ(f->at(0, kCentroid), 0.25);
  EXPECT_EQ(f->at(1, kCentroid), 0.0123456789012345678);
  // A view of another name is refused, listing the views there are.
  const json k = {{"kind", "file"}, {"file", "two_tets.msh"}, {"view", "t_act"}};
  SpecNode other(k, "/activation", *activation_schema());
  const std::string msg = input_error([&] { read_activation(other, m, nullptr, dir.str(), mesh_file); });
  EXPECT_NE(msg.find("no $ElementData view named \"t_act\", expected one with 1 components per element: one of "
                     "its views (activation)"),
            std::string::npos)
      << msg;
}

// ---- the spec ---------------------------------------------------------------------------

std::shared_ptr<const ActivationField> read_with_schema(const json& j, const TetMesh& m, const FrameField* frames) {
  SpecNode node(j, "/activation", *activation_schema());
  return read_activation(node, m, frames, ".", "");
}

TEST(ActivationSpec, EveryKindReadsAgainstItsSchema) {
  LvMeshParams p;
  const TetMesh lv = make_lv_mesh(p);
  const auto u = read_with_schema(json::object(), lv, nullptr);
  EXPECT_EQ(u->kind(), ActivationField::Kind::uniform);
  EXPECT_EQ(u->at(0, kCentroid), 0.0);
  EXPECT_EQ(read_with_schema({{"kind", "uniform"}, {"time", 0.125}}, lv, nullptr)->at(5, kCentroid), 0.125);

  // Eikonal from endo at 600 mm/s plus a later point source at the apex.
  const json j = {{"kind", "eikonal"},
                  {"sources", {{{"surface", "endo"}}, {{"point", {0.0, 0.0, -20.0}}, {"time", 0.001}}}},
                  {"velocity", 600}};
  const auto f = read_with_schema(j, lv, nullptr);
  const std::vector<double> t = f->node_times(lv);
  EXPECT_EQ(t[lv.node_sets.at("apex_endo")[0]], 0.0);
  EXPECT_EQ(t[lv.node_sets.at("apex_epi")[0]], 0.001);  // a source keeps its time
  // Anisotropic with a frame: the default velocities; a fibre frame along z (the long
  // axis) makes the front reach the far epicardium later than the isotropic fibre speed.
  AnalyticFrame frame;
  frame.fibre = Vec3::UnitZ();
  frame.sheet = Vec3::UnitX();
  const json k = {{"kind", "eikonal"}, {"sources", {{{"surface", "endo"}, {"time", 0.0}}}}};
  const auto g = read_with_schema(k, lv, &frame);
  const json iso = {{"kind", "eikonal"}, {"sources", {{{"surface", "endo"}}}}, {"velocity", kDefaultVelocityFibre}};
  const auto h = read_with_schema(iso, lv, nullptr);
  const int epi = lv.node_sets.at("apex_epi")[0];  // wall crossed along z: fibre speed
  EXPECT_NEAR(g->node_times(lv)[epi], h->node_times(lv)[epi], 1e-12);
  const std::vector<double> ga = g->node_times(lv), ha = h->node_times(lv);
  double later = 0;
  for (std::size_t i = 0; i < ga.size(); ++i) later = std::max(later, ga[i] - ha[i]);
  EXPECT_GT(later, 1e-3);  // across the fibres at the equator: 300 and 170 mm/s
  const json obj = {{"kind", "eikonal"},
                    {"sources", {{{"surface", "epi"}}}},
                    {"velocity", {{"fibre", 500}, {"sheet", 500}, {"normal", 500}}}};
  EXPECT_EQ(read_with_schema(obj, lv, nullptr)->kind(), ActivationField::Kind::per_vertex);
}

TEST(ActivationSpec, BadKeysAreNamed) {
  const TetMesh lv = make_lv_mesh(LvMeshParams{});
  const auto err = [&](const json& j, const FrameField* frames = nullptr) {
    return input_error([&] { read_with_schema(j, lv, frames); });
  };
  std::string msg = err({{"kind", "eikonal"}, {"sources", {{{"surface", "edno"}}}}});
  EXPECT_NE(msg.find("/activation/sources/0/surface: got \"edno\", expected a named surface of the mesh "
                     "(base, endo, epi); did you mean \"endo\"?"),
            std::string::npos)
      << msg;
  msg = err({{"kind", "eikonal"}, {"sources", {{{"surface", "endo"}}}}, {"velocity", -3}});
  EXPECT_NE(msg.find("/activation/velocity: got -3, expected a number > 0"), std::string::npos) << msg;
  msg = err({{"kind", "eikonal"}, {"sources", {{{"surface", "endo"}}}}, {"velocity", {{"fibre", 0}}}});
  EXPECT_NE(msg.find("/activation/velocity/fibre: got 0, expected a number > 0"), std::string::npos) << msg;
  msg = err({{"kind", "eikonal"}, {"sources", {{{"surface", "endo"}}}}, {"velocity", {{"fiber", 600}}}});
  EXPECT_NE(msg.find("unknown key 'fiber' in /activation/velocity; did you mean 'fibre'?"), std::string::npos) << msg;
  msg = err({{"kind", "eikonal"}, {"sources", {{{"surface", "endo"}}}}});
  EXPECT_NE(msg.find("/activation/velocity: got nothing (key missing), expected one number (isotropic): different "
                     "fibre, sheet and normal velocities need a fibre frame"),
            std::string::npos)
      << msg;
  msg = err({{"kind", "eikonal"}, {"sources", json::array()}});
  EXPECT_NE(msg.find("/activation/sources: got [], expected at least one source"), std::string::npos) << msg;
  msg = err({{"kind", "eikonal"}, {"sources", {{{"surface", "endo"}, {"point", {0, 0, 0}}}}}, {"velocity", 1}});
  EXPECT_NE(msg.find("/activation/sources/0/point: got [0,0,0], expected exactly one of 'surface'"), std::string::npos)
      << msg;
  msg = err({{"kind", "eikonal"}, {"sources", {{{"point", {0, 0, -20000}}}}}, {"velocity", 1}});
  EXPECT_NE(msg.find("/activation/sources/0/point: got [0,0,-20000], expected a point near the mesh"),
            std::string::npos)
      << msg;
  msg = err({{"kind", "eikonal"}, {"sources", {{{"surface", "endo"}, {"time", -1}}}}, {"velocity", 1}});
  EXPECT_NE(msg.find("/activation/sources/0/time: got -1, expected a number >= 0"), std::string::npos) << msg;
  msg = err({{"kind", "uniform"}, {"time", 1}, {"sources", 3}});
  EXPECT_NE(msg.find("unknown key 'sources' in /activation"), std::string::npos) << msg;
  msg = err({{"kind", "eikonall"}});
  EXPECT_NE(msg.find("/activation/kind: got \"eikonall\", expected one of \"uniform\", \"eikonal\", \"file\" (how "
                     "activation times are given: one time, an eikonal front, or a file); did you mean \"eikonal\"?"),
            std::string::npos)
      << msg;
  msg = err({{"kind", "file"}, {"file", "/nonexistent/act.csv"}, {"format", "csv"}});
  EXPECT_NE(msg.find("cannot open activation file '/nonexistent/act.csv'"), std::string::npos) << msg;
}

}  // namespace
}  // namespace fe2
