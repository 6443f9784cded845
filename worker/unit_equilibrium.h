#pragma once
// Equilibrating one micro unit under a prescribed macro gradient Z̄ (the unit alone,
// as `fe2heart unit` and the homogenization tests use it): Newton iterations of the
// unit (Step 1 updates) until ‖r‖ <= rtol·r_ref, then one more assembly at the
// equilibrium with a fresh factor, so 𝔸_hom = Ā − Hχ uses exact modes.
#include "worker/MicroUnit.h"

#include <vector>

namespace fe2 {

struct UnitEquilibrium {
  Vec9 P_bar = Vec9::Zero();
  Mat9 A_hom = Mat9::Zero();
  int newton_iterations = 0;
  int gmres_iterations = 0;
  std::vector<double> residuals;  ///< ‖r‖ / r_ref per iteration
};

/// `step` labels the jobs (the refresh policy sees it). Throws NumericalError if the
/// unit does not reach rtol within max_iterations.
UnitEquilibrium equilibrate(MicroUnit& unit, const Vec9& Zbar, double rtol, int max_iterations,
                            int step = 0);

/// The same over a step of a scene: `job` gives Z̄, Ż̄, ∂Ż̄/∂Z̄, t, Δt, the step and the
/// activation time (its unit, iteration and update flags are set here). The unit's
/// history advances from its committed state and is committed at the equilibrium.
UnitEquilibrium equilibrate(MicroUnit& unit, const proto::JobInput& job, double rtol,
                            int max_iterations);

}  // namespace fe2
