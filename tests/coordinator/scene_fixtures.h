#pragma once
// Small scenes for coordinator tests, written as JSON specs exactly as users write them.
#include "coordinator/RunSpec.h"
#include "coordinator/Simulation.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <string>
#include <vector>

namespace fe2::test {

inline json nh(double E, double nu) { return {{"model", "neo_hookean"}, {"E", E}, {"nu", nu}}; }

/// A heterogeneous two-cell unit (paper Fig. 4) at a small resolution.
inline json two_cell_unit(const std::string& refresh = "every_iteration", bool step4 = true,
                          int N_t = 10) {
  return {{"cell", "two_cells"},
          {"size", {1.0, 0.4, 0.4}},
          {"resolution", {4, 4, 4}},
          {"gap", 0.125},
          {"cross_section", 0.5},
          {"materials", {{"cell", nh(2.0e4, 0.4)}, {"ecm", nh(2.0e3, 0.3)}}},
          {"solver", {{"refresh", refresh}, {"step4", step4}, {"N_t", N_t}}}};
}

inline json homogeneous_unit(const json& material) {
  return {{"cell", "homogeneous"},
          {"resolution", {2, 2, 2}},
          {"materials", {{"matrix", material}}},
          {"solver", {{"refresh", "every_iteration"}}}};
}

/// The model of `material` with a volumetric penalty (so a unit has one): the macro law
/// itself, or FE² units that are homogeneous in it (whose homogenized law is the law).
inline json macro_law_or_its_units(json material, bool fe2) {
  material["volumetric"] = "penalty";
  material["kappa"] = 1e6;
  return fe2 ? json{{"kind", "fe2"}, {"unit", homogeneous_unit(material)}}
             : json{{"kind", "macro_law"}, {"material", material}};
}

/// A cantilever [0,2]x[0,1]x[0,1], clamped at x = 0, under a follower pressure on top.
inline json beam(const json& model, int steps = 3, double pressure = 60.0) {
  return {{"mesh", {{"kind", "box"}, {"hi", {2, 1, 1}}, {"divisions", {2, 1, 1}}}},
          {"frame", {{"fibre", {1, 0.2, 0}}, {"sheet", {0, 1, 0.3}}}},
          {"models", {{"m", model}}},
          {"dirichlet", {{{"set", "xmin"}}}},
          {"pressure", {{{"surface", "zmax"}, {"value", pressure}}}},
          {"time", {{"t_end", 1.0}, {"steps", steps}}},
          {"newton", {{"rtol", 1e-11}, {"micro_rtol", 1e-11}, {"max_iterations", 40}}},
          {"probes", {{"tip", {2, 0.5, 0.5}}, {"mid", {1, 0.2, 0.7}}}},
          {"output", {{"vtu", false}}}};
}

/// Newton iterations of one step in the asymptotic range (below 1e-2, and the next above
/// the round-off floor) must at least nearly square the residual: log r_{k+1}/log r_k > 1.8.
/// Returns how many were checked (gtest expectations inside).
inline int expect_quadratic_iterations(const std::vector<double>& res, const std::string& where) {
  int checked = 0;
  for (size_t k = 1; k + 1 < res.size(); ++k) {
    if (res[k] > 1e-2 || res[k + 1] < 1e-13) continue;
    EXPECT_GT(std::log(res[k + 1]) / std::log(res[k]), 1.8) << where << ": " << res[k] << " -> " << res[k + 1];
    ++checked;
  }
  return checked;
}

struct SceneRun {
  RunResult result;
  Eigen::VectorXd u;  ///< every macro DOF: ū, then p (mixed)
  std::vector<Vec3> probes;
};

inline SceneRun run_scene(const json& j) {
  const RunSpec spec = read_run_spec(j, "");
  LocalEvaluator points(spec.models, spec.model_of_points());
  Simulation sim(spec, points);
  SceneRun r;
  r.result = sim.run();
  r.u = sim.state();
  for (const auto& [name, X] : spec.probes) r.probes.push_back(sim.deformed_position(X));
  return r;
}

}  // namespace fe2::test
