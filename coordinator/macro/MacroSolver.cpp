#include "coordinator/macro/MacroSolver.h"

#include "common/linalg/gmres.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>

namespace fe2 {

MacroSolver::MacroSolver(const proto::Group& group, int n, MacroSolverOptions options)
    : group_(group), mumps_(group.raw(), n, options.ordering), options_(options) {}

void MacroSolver::set_pattern(std::vector<int> rows, std::vector<int> cols) {
  rows_ = rows;
  cols_ = cols;
  mumps_.set_pattern(std::move(rows), std::move(cols));
  have_factor_ = false;
}

namespace {
// Eisenstat & Walker (1996), choice 2, and the cap on η. The safeguard applies only while
// its floor γ η_{k−1}^α is above their threshold 0.1 (the same number as the cap here, by
// choice of the cap, not of the method).
constexpr double ew_gamma = 0.9, ew_alpha = 2.0, ew_eta_max = 0.1, ew_safeguard_threshold = 0.1;
}  // namespace

double MacroSolver::relative_tolerance(double b_norm) {
  if (options_.forcing == MacroSolverOptions::Forcing::constant) return options_.gmres_rtol;
  double eta = ew_eta_max;  // the first solve, or a residual that grew (a new step)
  if (last_b_norm_ > 0.0 && b_norm < last_b_norm_) {
    eta = ew_gamma * std::pow(b_norm / last_b_norm_, ew_alpha);
    // Safeguard: η may not drop faster than the residual has been converging.
    if (const double floor = ew_gamma * std::pow(last_eta_, ew_alpha); floor > ew_safeguard_threshold)
      eta = std::max(eta, floor);
  }
  eta = std::clamp(eta, options_.gmres_rtol, ew_eta_max);
  last_b_norm_ = b_norm;
  last_eta_ = eta;
  return eta;
}

void MacroSolver::solve(const std::vector<double>& values, std::vector<double>& rhs) {
  if (options_.refresh == MacroSolverOptions::Refresh::adaptive && have_factor_ &&
      solve_with_kept_factor(values, rhs))
    return;
  if (options_.forcing == MacroSolverOptions::Forcing::eisenstat_walker && !have_factor_) {
    // A direct solve: record ‖b‖ (rank 0's, sent to all) for the next η.
    double b_norm = group_.rank() == 0 ? Eigen::Map<const Vec>(rhs.data(), mumps_.size()).norm() : 0.0;
    group_.bcast(&b_norm, 1, 0);
    relative_tolerance(b_norm);
  }
  have_factor_ = false;  // a failed factorization leaves none to keep
  mumps_.factorize(values);
  have_factor_ = true;
  ++stats_.factorizations;
  stats_.factor_entries = mumps_.factor_entries();
  stats_.factor_flops = mumps_.factor_flops();
  mumps_.solve(rhs);
}

bool MacroSolver::solve_with_kept_factor(const std::vector<double>& values, std::vector<double>& rhs) {
  const int n = mumps_.size();
  Vec b = Eigen::Map<const Vec>(rhs.data(), n);
  group_.bcast(b.data(), n, 0);
  // y = S̄ x: each rank's triplets, summed over the group.
  const LinearOp A = [&](const Vec& x, Vec& y) {
    y.setZero(n);
    for (size_t k = 0; k < values.size(); ++k) y[rows_[k]] += values[k] * x[cols_[k]];
    group_.allreduce_sum(y.data(), n);
  };
  // z = M⁻¹ r with the kept factor (MUMPS solves on the host; every rank gets z).
  std::vector<double> buffer(n);
  const LinearOp Minv = [&](const Vec& r, Vec& z) {
    Eigen::Map<Vec>(buffer.data(), n) = r;
    mumps_.solve(buffer);
    group_.bcast(buffer.data(), n, 0);
    z = Eigen::Map<const Vec>(buffer.data(), n);
  };
  Vec x = Vec::Zero(n);
  const double tol = relative_tolerance(b.norm()) * b.norm();
  // Twice the refactor threshold before giving up on the kept factor this time.
  const GmresResult g = gmres(A, Minv, b, x, tol, 2 * options_.max_gmres_iterations,
                              2 * options_.max_gmres_iterations);
  stats_.gmres_iterations += g.iterations;
  if (!g.converged || !x.allFinite()) {
    spdlog::debug("macro GMRES with the kept factor: {} iterations, |r|/|b| = {:.2e}; refactoring",
                  g.iterations, g.residual / b.norm());
    return false;
  }
  ++stats_.reused;
  if (g.iterations > options_.max_gmres_iterations) have_factor_ = false;  // refactor next time
  Eigen::Map<Vec>(rhs.data(), n) = x;
  return true;
}

}  // namespace fe2
