#pragma once
// The macro Newton system S̄ Δx = −R̃ (Eq. 10) on the coordinator group, with the
// MUMPS factor kept across Newton iterations and steps as the paper keeps a unit's
// (Fig. 6): policy `every_iteration` factors every call (a direct solve); `adaptive`
// factors only when there is no factor yet, when the last solve needed more than
// `max_gmres_iterations` GMRES iterations, or when GMRES on the current S̄,
// right-preconditioned by the kept factor, fails to reach ‖b − S̄x‖ ≤ gmres_rtol ‖b‖.
// At the macro sizes of a heart the factorization is most of the macro time (a 5k-unknown
// quadratic LV: 81 %), a solve with the kept factor a few percent of it.
//
// With `gmres_forcing` eisenstat_walker the kept-factor GMRES stops at ‖b − S̄x‖ ≤ η_k ‖b‖, the
// forcing term of Eisenstat & Walker (1996, choice 2) from the Newton residuals' ratio
// (‖b‖ is ‖R̃‖ of the iteration): η_k = γ(‖b_k‖/‖b_{k−1}‖)^α, γ = 0.9, α = 2, kept from
// falling faster than γη_{k−1}^α while that exceeds 0.1, within [gmres_rtol, η_max = 0.1].
// Loose while Newton is far from the solution, tight as it converges: Newton keeps its
// superlinear rate and early iterations cost a few preconditioned products, not a
// solve to round-off. A direct (factorizing) solve is exact whatever η.
//
// Every coordinator runs the same GMRES on the same numbers (the matrix-vector product
// is summed over the group, the preconditioner is MUMPS's collective solve, its result
// broadcast), so all take the same decisions without further messages, and the policy
// depends only on iteration counts: deterministic.
#include "coordinator/macro/MacroSolverOptions.h"
#include "coordinator/macro/MumpsSolver.h"
#include "proto/Transport.h"

#include <string>
#include <vector>

namespace fe2 {

class MacroSolver {
 public:
  struct Stats {
    int factorizations = 0;
    int gmres_iterations = 0;  ///< over the solves with a kept factor
    int reused = 0;            ///< solves that used a kept factor
    double factor_entries = 0; ///< of the last factor (MUMPS INFOG(29))
    double factor_flops = 0;   ///< of the last factorization (RINFOG(3))
  };

  /// @note Collective on `group` (lent; must outlive this object).
  MacroSolver(const proto::Group& group, int n, MacroSolverOptions options);

  /// This rank's triplets (0-based); runs the analysis. @note Collective.
  void set_pattern(std::vector<int> rows, std::vector<int> cols);
  /// Solves with this rank's triplet `values` (summed over the group): `rhs` (length n,
  /// significant on rank 0) is overwritten with the solution on rank 0. Throws
  /// SingularMatrixError / NumericalError as MumpsSolver does. @note Collective.
  void solve(const std::vector<double>& values, std::vector<double>& rhs);
  /// The next solve factors and the forcing starts afresh (after a rollback, at a
  /// checkpoint: a restart then takes the same path as the run that went on).
  void drop_factor() {
    have_factor_ = false;
    last_b_norm_ = last_eta_ = 0.0;
  }

  const Stats& stats() const { return stats_; }
  const std::string& ordering() const { return mumps_.ordering(); }

 private:
  bool solve_with_kept_factor(const std::vector<double>& values, std::vector<double>& rhs);
  /// The relative tolerance of this solve's GMRES; `b_norm` is ‖b‖, the same on every rank.
  double relative_tolerance(double b_norm);

  const proto::Group& group_;
  MumpsSolver mumps_;
  MacroSolverOptions options_;
  std::vector<int> rows_, cols_;
  bool have_factor_ = false;
  double last_b_norm_ = 0.0;  ///< ‖b‖ of the previous solve (0: none yet)
  double last_eta_ = 0.0;     ///< η of the previous solve
  Stats stats_;
};

}  // namespace fe2
