#pragma once
// Time integration per field (FieldDecl::time). From the committed x_n, v_n, a_n and the
// trial x of the step, each field's rates follow from its scheme:
//   Newmark-β       a = (x − x_n − Δt v_n)/(βΔt²) − (1/(2β) − 1) a_n,
//                   v = v_n + Δt((1 − γ) a_n + γ a)                 (second order in time)
//   backward Euler  v = (x − x_n)/Δt, a = 0                          (first order)
//   BDF2            v = [(1+2ω)/(1+ω) x − (1+ω) x_n + ω²/(1+ω) x_{n−1}]/Δt, a = 0,
//                   ω = Δt/Δt_{n−1}: the variable-step form (second order across cut-backs);
//                   the first step (no Δt_{n−1}) is backward Euler
//   none            v = a = 0
// and a term linearizes its rates with ∂v/∂x, ∂a/∂x (RateCoefficients).
#include "coordinator/macro/FieldTable.h"

#include <Eigen/Dense>

namespace fe2 {

/// ∂v/∂x and ∂a/∂x of a field's scheme at step Δt (0 where the field has no such rate).
struct RateCoefficients {
  double dv_dx = 0.0;
  double da_dx = 0.0;
};

class TimeIntegration {
 public:
  TimeIntegration(double beta, double gamma) : beta_(beta), gamma_(gamma) {}

  /// `dt_prev`: the committed step before this one (0: none yet).
  RateCoefficients coefficients(const Field& field, double dt, double dt_prev) const;
  /// v, a of `field`'s block from the trial x and the committed state (x_{n−1} and
  /// Δt_{n−1}: the step before it, for BDF2).
  void rates(const Field& field, double dt, const Eigen::VectorXd& x, const Eigen::VectorXd& x_n,
             const Eigen::VectorXd& v_n, const Eigen::VectorXd& a_n, const Eigen::VectorXd& x_nm1, double dt_prev,
             Eigen::VectorXd& v, Eigen::VectorXd& a) const;

 private:
  double beta_, gamma_;
};

}  // namespace fe2
