#pragma once
// Backtracking line search for the macro Newton (newton.line_search "backtracking").
//
// Armijo backtracking on a residual merit (Dennis & Schnabel 1983, Alg. A6.3.1; Nocedal
// & Wright 2006, Alg. 3.1 with the interpolation of §3.5): the correction Δx of a Newton
// iteration is taken as x_k + α Δx with the first α = 1 accepted when
//
//   φ(x_k + α Δx) ≤ (1 − c α) φ(x_k),   c = 1e-4,
//
// else α shrinks by the minimiser of the quadratic through m(0) = φ₀², m'(0) = −2φ₀² (the
// Newton direction's slope of ½‖R‖², exact for the Euclidean norm) and m(α) = φ(α)²,
// safeguarded to [α/10, α/2]; a trial that fails outright (an inverted element, a
// non-finite value) halves α. Below newton.line_search_min_step a finite trial is taken
// anyway (Newton may still recover; the iteration cap decides), a failed one ends the
// step (a cut-back).
//
// Why the residual and not the energy: the mixed formulation is a saddle point (the
// Lagrange-multiplier pressure maximises), the follower pressure is not conservative and
// FE² units have no energy at the macro scale, so an energy merit is not available in
// general; the residual is. φ is the driver's convergence measure (each field's residual
// norm over its tolerance, the largest), computed from globally reduced norms: every
// coordinator takes the same α. The trial at α = 1 is the next Newton iteration's own
// evaluation, so a line search that never backtracks costs nothing and changes nothing.
namespace fe2 {

struct LineSearchOptions {
  bool backtracking = false;   ///< newton.line_search
  double min_step = 1.0 / 64;  ///< newton.line_search_min_step
};

class LineSearch {
 public:
  explicit LineSearch(const LineSearchOptions& o) : o_(o) {}
  bool active() const { return o_.backtracking; }

  /// A correction from a point of merit φ₀ is about to be taken: its first trial is α = 1.
  void start(double merit0);
  enum class Verdict {
    take,     ///< the trial stands
    retry,    ///< try x_k + alpha() Δx instead
    give_up,  ///< a failed trial at the shortest step: the iteration fails
  };
  /// The merit at the trial x_k + alpha() Δx, or +∞ if evaluating it failed.
  Verdict judge(double merit);
  double alpha() const { return alpha_; }
  /// Trials rejected since the start of the Newton solve (summary, logs).
  int backtracks() const { return backtracks_; }

 private:
  LineSearchOptions o_;
  double merit0_ = 0.0;
  double alpha_ = 1.0;
  bool started_ = false;
  int backtracks_ = 0;
};

}  // namespace fe2
