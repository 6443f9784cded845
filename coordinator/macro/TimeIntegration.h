#pragma once
// Time integration per field (FieldDecl::time). From the committed x_n, v_n, a_n and the
// trial x of the step, each field's rates follow from its scheme:
//   Newmark-β       a = (x − x_n − Δt v_n)/(βΔt²) − (1/(2β) − 1) a_n,
//                   v = v_n + Δt((1 − γ) a_n + γ a)                 (second order in time)
//   backward Euler  v = (x − x_n)/Δt, a = 0                          (first order)
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

  RateCoefficients coefficients(const Field& field, double dt) const;
  /// v, a of `field`'s block from the trial x and the committed state.
  void rates(const Field& field, double dt, const Eigen::VectorXd& x, const Eigen::VectorXd& x_n,
             const Eigen::VectorXd& v_n, const Eigen::VectorXd& a_n, Eigen::VectorXd& v,
             Eigen::VectorXd& a) const;

 private:
  double beta_, gamma_;
};

}  // namespace fe2
