#pragma once
// When the macro factor is refreshed (`newton.macro_solver`; MacroSolver.h). No MPI here:
// RunSpec holds it.

namespace fe2 {

struct MacroSolverOptions {
  enum class Refresh { every_iteration, adaptive };
  /// How far GMRES with a kept factor solves: to gmres_rtol always (constant), or to the
  /// Eisenstat–Walker forcing term η_k (inexact Newton; gmres_rtol its floor).
  enum class Forcing { constant, eisenstat_walker };
  Refresh refresh = Refresh::every_iteration;
  Forcing forcing = Forcing::constant;
  double gmres_rtol = 1e-12;      ///< ‖b − S̄x‖ / ‖b‖ to reach with a kept factor
  int max_gmres_iterations = 10;  ///< more in one solve: refactor for the next
};

}  // namespace fe2
