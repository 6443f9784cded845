#pragma once
// Small micro units for the tests, built in code.
#include "common/materials/NeoHookean.h"
#include "common/materials/StVenantKirchhoff.h"
#include "worker/MicroUnit.h"
#include "worker/micro_cell.h"

#include <memory>

namespace fe2::test {

inline MicroModelPtr make_unit_model(CellLayout layout, std::vector<MaterialPtr> materials,
                                     MicroSolverOptions options = {}) {
  return std::make_shared<const MicroModel>(make_cell_mesh(layout), std::move(materials), options,
                                            "test unit");
}

/// Two cells (stiff) in matrix (soft), as paper Fig. 4, at a small resolution.
inline MicroModelPtr two_cell_model(MicroSolverOptions options = {},
                                    std::array<int, 3> resolution = {6, 4, 4}) {
  CellLayout c;
  c.kind = "two_cells";
  c.size = Vec3(1.0, 0.4, 0.4);
  c.resolution = resolution;
  c.gap = 0.1;
  c.cross_section = 0.5;
  return make_unit_model(c,
                         {std::make_shared<NeoHookean>(1.0e3, 0.3),     // ecm
                          std::make_shared<NeoHookean>(2.0e4, 0.4)},    // cell
                         options);
}

inline Vec9 gradient(std::initializer_list<double> v) {
  Vec9 z;
  int i = 0;
  for (double x : v) z[i++] = x;
  return z;
}

/// A unit's first job, step 0 iteration 1 at a moderate Z̄: a refresh (K and χ there, w = 0)
/// that later jobs at other Z̄ find as their stale factor. Returns that job's input.
inline proto::JobInput factor_at_step_zero(MicroUnit& unit) {
  proto::JobInput in;
  in.step = 0;
  in.iteration = 1;
  in.Zbar = gradient({0.04, 0.01, 0.0, 0.0, -0.015, 0.0, 0.01, 0.0, 0.005});
  unit.iterate(in);
  return in;
}

/// Relative Frobenius difference.
template <class A, class B>
double rel_diff(const A& a, const B& b) {
  return (a - b).norm() / std::max(b.norm(), 1e-300);
}

}  // namespace fe2::test
