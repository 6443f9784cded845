#pragma once
// When the macro factor is refreshed (`newton.macro_solver`; MacroSolver.h). No MPI here:
// RunSpec holds it.

namespace fe2 {

struct MacroSolverOptions {
  enum class Refresh { every_iteration, adaptive };
  /// How far GMRES with a kept factor solves: to gmres_rtol always (constant), or to the
  /// Eisenstat–Walker forcing term η_k (inexact Newton; gmres_rtol its floor).
  enum class Forcing { constant, eisenstat_walker };
  /// The fill-reducing ordering of S̄'s factor: METIS's nested dissection (fe2heart's, passed
  /// to MUMPS as the user's order) or MUMPS's own automatic choice among those its build has
  /// (Debian's MUMPS: PORD, AMD, AMF, QAMD; no METIS or SCOTCH).
  enum class Ordering { metis, mumps };
  Refresh refresh = Refresh::every_iteration;
  Forcing forcing = Forcing::constant;
  double gmres_rtol = 1e-12;      ///< ‖b − S̄x‖ / ‖b‖ to reach with a kept factor
  int max_gmres_iterations = 10;  ///< more in one solve: refactor for the next
  Ordering ordering = Ordering::metis;
};

}  // namespace fe2
