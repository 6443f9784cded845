// Newmark-β inertia and fibre frames.
#include "tests/coordinator/scene_fixtures.h"

#include "coordinator/MacroPoints.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <Eigen/Geometry>

#include <cmath>
#include <filesystem>
#include <fstream>

namespace fe2 {
namespace {

json cantilever(const std::string& scheme, int steps, double t_end) {
  return {{"mesh", {{"kind", "box"}, {"hi", {4, 1, 1}}, {"divisions", {4, 1, 1}}}},
          {"models", {{"m", {{"kind", "macro_law"}, {"material", {{"model", "st_venant_kirchhoff"}, {"E", 1e4}, {"nu", 0.3}}}}}}},
          {"dirichlet", {{{"set", "xmin"}}}},
          {"pressure", {{{"surface", "zmax"}, {"value", 0.2}, {"ramp", "constant"}}}},
          {"time", {{"t_end", t_end}, {"steps", steps}, {"scheme", scheme}, {"density", 10.0}}},
          {"newton", {{"rtol", 1e-10}}},
          {"probes", {{"tip", {4, 0.5, 0.5}}}},
          {"output", {{"vtu", false}}}};
}

// A load applied suddenly to an undamped linear structure makes it oscillate about
// the static deflection with amplitude equal to it: the peak is twice the static
// deflection (dynamic amplification factor 2) and the time average is the static one.
// The load is small (tip deflection ~1 % of the length), so the response is linear to
// about 1 %; Newmark's average-acceleration rule (β = ¼, γ = ½) adds no damping.
TEST(Newmark, SuddenLoadPeaksAtTwiceStaticDeflection) {
  const auto stat = test::run_scene(cantilever("quasi_static", 1, 1.0));
  ASSERT_TRUE(stat.result.converged);
  const double w_static = stat.probes[0].z() - 0.5;
  ASSERT_LT(w_static, -1e-3);

  const RunSpec spec = read_run_spec(cantilever("newmark", 1200, 6.0), "");
  LocalEvaluator points(spec.models, spec.model_of_points());
  Simulation sim(spec, points);
  std::vector<double> w;
  const RunResult r = sim.run([&](const StepRecord&) {
    w.push_back(sim.deformed_position(spec.probes[0].second).z() - 0.5);
  });
  ASSERT_TRUE(r.converged) << r.error;
  const double peak = *std::min_element(w.begin(), w.end());
  // Several periods must be inside the run for the average to mean anything.
  int crossings = 0;
  for (size_t k = 1; k < w.size(); ++k)
    crossings += (w[k] - w_static) * (w[k - 1] - w_static) < 0;
  ASSERT_GE(crossings, 4) << "fewer than two periods simulated";
  EXPECT_NEAR(peak / w_static, 2.0, 0.05);
  double mean = 0.0;
  for (double x : w) mean += x / w.size();
  EXPECT_NEAR(mean / w_static, 1.0, 0.1);  // partial last period: loose on purpose
}

TEST(FibreFrame, RotatingRuleTurnsFibresAboutTheAxisAndStaysOrthonormal) {
  json j = cantilever("quasi_static", 1, 1.0);
  j["frame"] = {{"kind", "rotating"}, {"fibre", {1, 0, 0}}, {"sheet", {0, 1, 0}},
                {"axis", {0, 1, 0}}, {"coordinate", {0, 1, 0}}, {"from", {0.0, -60.0}},
                {"to", {1.0, 60.0}}};
  const RunSpec spec = read_run_spec(j, "");
  for (double y : {0.0, 0.25, 0.5, 1.0, 2.0}) {
    const Mat3 Q = spec.frame.at(Vec3(1.0, y, 0.3));
    EXPECT_LT((Q.transpose() * Q - Mat3::Identity()).norm(), 1e-14);
    EXPECT_NEAR(Q.determinant(), 1.0, 1e-14);
    const double expected = -60.0 + 120.0 * std::clamp(y, 0.0, 1.0);  // degrees, clamped
    const double angle = std::atan2(-Q(2, 0), Q(0, 0)) * 180.0 / M_PI;  // rotation about +y
    EXPECT_NEAR(angle, expected, 1e-10) << "y = " << y;
  }
}

// A fibre file per integration point: each macro point (numbered as MacroPoints numbers
// them, by formulation.quadrature_degree) gets exactly its line's frame, evaluated as
// PointCoupling evaluates it; read with another rule, the file is refused.
TEST(FibreFrame, PerPointFileGivesEachMacroPointItsFrame) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / fmt::format("fe2_per_point_frames_{}", getpid());
  fs::create_directories(dir);
  json j = cantilever("quasi_static", 1, 1.0);
  j["formulation"] = {{"quadrature_degree", 2}};
  j["frame"] = {{"kind", "file"}, {"file", "points.csv"}, {"format", "csv"}, {"per", "point"}};
  const int ne = 4 * 6, np = 4;  // 4x1x1 box cells of 6 tets, the 4-point rule
  const auto frame_of = [](int e, int k) {
    return Mat3(Eigen::AngleAxisd((7.0 * e + 40.0 * k) * M_PI / 180, Vec3(1, 2, 3).normalized()));
  };
  {
    std::ofstream out(dir / "points.csv");
    out << "tag,point,fx,fy,fz,sx,sy,sz\n";
    for (int e = 0; e < ne; ++e)
      for (int k = np - 1; k >= 0; --k) {
        const Mat3 Q = frame_of(e, k);
        out << fmt::format("{},{},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g}\n", e + 1, k, Q(0, 0), Q(1, 0),
                           Q(2, 0), Q(0, 1), Q(1, 1), Q(2, 1));
      }
  }
  const std::string spec_file = (dir / "spec.json").string();
  const RunSpec spec = read_run_spec(j, spec_file);
  ASSERT_EQ(spec.points_per_element, np);
  const MacroPoints points(spec.mesh, spec.formulation.quadrature_degree);
  const auto field = spec.frame.built ? spec.frame.built : make_frame_field(spec.frame.field, spec.mesh);
  double worst = 0;
  for (int p = 0; p < points.size(); ++p) {
    const Vec4& l = points[p].bary;
    const int e = points[p].element;
    const Mat3 Q = field->at(e, Bary{l[0], l[1], l[2], l[3]}, points[p].X);
    worst = std::max(worst, (Q - frame_of(e, p - points.first_point(e))).norm());
  }
  EXPECT_LT(worst, 1e-15);
  j["formulation"] = json::object();  // the default rule on linear tets: one point
  try {
    read_run_spec(j, spec_file);
    ADD_FAILURE() << "a 4-point file read with the 1-point rule";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("line 2: element 1 point 3: no such point: the quadrature "
                                         "rule of degree 0 has 1 points per element (0..0), got point 3"),
              std::string::npos)
        << e.what();
  }
  fs::remove_all(dir);
}

TEST(RunSpecErrors, UnknownSetAndModelAreNamedWithSuggestions) {
  json j = cantilever("quasi_static", 1, 1.0);
  j["dirichlet"][0]["set"] = "xmn";
  try {
    read_run_spec(j, "");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("did you mean \"xmin\""), std::string::npos) << e.what();
  }
  j = cantilever("quasi_static", 1, 1.0);
  j["assign"] = {{"default", "n"}};
  EXPECT_THROW(read_run_spec(j, ""), InputError);
  j = cantilever("quasi_static", 1, 1.0);
  j["probes"]["outside"] = {9, 9, 9};
  try {
    read_run_spec(j, "");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/probes/outside"), std::string::npos) << e.what();
  }
}

/// read_run_spec's InputError text for `j` ("" if it reads).
std::string run_spec_error(const json& j) {
  try {
    read_run_spec(j, "");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// Every refused name lists the known ones and suggests the nearest (known_names).
TEST(RunSpecErrors, RefusedNamesSuggestTheNearest) {
  json j = cantilever("quasi_static", 1, 1.0);
  j["pressure"][0]["surface"] = "zmx";
  EXPECT_EQ(run_spec_error(j),
            "/pressure/0/surface: got \"zmx\", expected a named surface of the mesh (xmax, xmin, ymax, "
            "ymin, zmax, zmin); did you mean \"zmax\"?");
  j = cantilever("quasi_static", 1, 1.0);
  j["assign"] = {{"default", "mm"}};
  EXPECT_EQ(run_spec_error(j),
            "/assign/default: got \"mm\", expected the name of a model in /models (m); did you mean \"m\"?");
  j = cantilever("quasi_static", 1, 1.0);
  j["cavities"] = {{"box", {{"surface", "xmaxx"}}}};
  EXPECT_NE(run_spec_error(j).find("/cavities/box/surface: got \"xmaxx\", expected a named surface of the mesh "
                                   "(xmax, xmin, ymax, ymin, zmax, zmin); did you mean \"xmax\"?"),
            std::string::npos)
      << run_spec_error(j);
  j = cantilever("quasi_static", 1, 1.0);
  j["time"]["scheme"] = "newmrk";
  EXPECT_NE(run_spec_error(j).find("/time/scheme: got \"newmrk\", expected one of \"quasi_static\", \"newmark\" "
                                   "(quasi-static load stepping or Newmark-β dynamics); did you mean \"newmark\"?"),
            std::string::npos)
      << run_spec_error(j);
}

}  // namespace
}  // namespace fe2
