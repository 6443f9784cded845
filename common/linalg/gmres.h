#pragma once
// Restarted GMRES(m) with right preconditioning, keeping the preconditioned basis
// (Saad, Iterative Methods, Alg. 9.6, FGMRES) so the update costs no extra solve:
// solves A x = b with x = M⁻¹ y, so the residual it minimises is the true residual
// b − A x, and the stopping test ‖b − A x‖ ≤ tol is checked on the true residual at
// every restart (after a one-iteration cycle from x = 0 as y₀·(A z₀), the product the
// iteration already made, so a well-preconditioned solve applies A once). Used for Step 1 (Eq. 8) and stale characteristic modes (Eq. 6) with
// the unit's cached factor as M⁻¹ (paper Fig. 6, c2 and c3), and for the macro system
// with a kept MUMPS factor (MacroSolver).
#include <Eigen/Dense>

#include <functional>

namespace fe2 {

using Vec = Eigen::VectorXd;
/// y = Op(x); y is sized by the caller.
using LinearOp = std::function<void(const Vec& x, Vec& y)>;

struct GmresResult {
  int iterations = 0;      ///< Krylov iterations (preconditioner applications)
  double residual = 0.0;   ///< final true residual norm ‖b − Ax‖
  bool converged = false;
};

/// The residual norm round-off allows at x (e.g. eps·‖|A||x|‖): no Krylov method gets
/// the true residual below it, so it is met when ‖b − Ax‖ is under it too.
using ResidualFloor = std::function<double(const Vec& x)>;

/// `x` is the initial guess on entry and the solution on exit. Converged when the true
/// residual is ≤ tol, or ≤ floor(x) if a floor is given (checked at every restart).
GmresResult gmres(const LinearOp& A, const LinearOp& Minv, const Vec& b, Vec& x, double tol,
                  int restart, int max_iterations, const ResidualFloor& floor = {});

}  // namespace fe2
