#include "coordinator/macro/TimeIntegration.h"

namespace fe2 {

namespace {

/// BDF2's weights on x, x_n, x_{n−1} (times 1/Δt) at step ratio ω = Δt/Δt_{n−1}.
struct Bdf2Weights {
  double x, x_n, x_nm1;
};
Bdf2Weights bdf2_weights(double dt, double dt_prev) {
  if (dt_prev <= 0.0) return {1.0, -1.0, 0.0};  // the first step: backward Euler
  const double w = dt / dt_prev;
  return {(1.0 + 2.0 * w) / (1.0 + w), -(1.0 + w), w * w / (1.0 + w)};
}

}  // namespace

RateCoefficients TimeIntegration::coefficients(const Field& field, double dt, double dt_prev) const {
  switch (field.decl().time) {
    case TimeScheme::newmark: return {gamma_ / (beta_ * dt), 1.0 / (beta_ * dt * dt)};
    case TimeScheme::backward_euler: return {1.0 / dt, 0.0};
    case TimeScheme::bdf2: return {bdf2_weights(dt, dt_prev).x / dt, 0.0};
    case TimeScheme::none: break;
  }
  return {};
}

void TimeIntegration::rates(const Field& field, double dt, const Eigen::VectorXd& x, const Eigen::VectorXd& x_n,
                            const Eigen::VectorXd& v_n, const Eigen::VectorXd& a_n, const Eigen::VectorXd& x_nm1,
                            double dt_prev, Eigen::VectorXd& v, Eigen::VectorXd& a) const {
  const Eigen::Index o = field.offset(), n = field.size();
  switch (field.decl().time) {
    case TimeScheme::newmark: {
      const double c = 1.0 / (beta_ * dt * dt);
      a.segment(o, n) = c * (x.segment(o, n) - x_n.segment(o, n) - dt * v_n.segment(o, n)) -
                        (0.5 / beta_ - 1.0) * a_n.segment(o, n);
      v.segment(o, n) = v_n.segment(o, n) + dt * ((1.0 - gamma_) * a_n.segment(o, n) + gamma_ * a.segment(o, n));
      return;
    }
    case TimeScheme::backward_euler:
      v.segment(o, n) = (x.segment(o, n) - x_n.segment(o, n)) / dt;
      a.segment(o, n).setZero();
      return;
    case TimeScheme::bdf2: {
      const Bdf2Weights k = bdf2_weights(dt, dt_prev);
      v.segment(o, n) = (k.x * x.segment(o, n) + k.x_n * x_n.segment(o, n) + k.x_nm1 * x_nm1.segment(o, n)) / dt;
      a.segment(o, n).setZero();
      return;
    }
    case TimeScheme::none: return;
  }
}

}  // namespace fe2
