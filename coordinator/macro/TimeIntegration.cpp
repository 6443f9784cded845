#include "coordinator/macro/TimeIntegration.h"

namespace fe2 {

RateCoefficients TimeIntegration::coefficients(const Field& field, double dt) const {
  switch (field.decl().time) {
    case TimeScheme::newmark: return {gamma_ / (beta_ * dt), 1.0 / (beta_ * dt * dt)};
    case TimeScheme::backward_euler: return {1.0 / dt, 0.0};
    case TimeScheme::none: break;
  }
  return {};
}

void TimeIntegration::rates(const Field& field, double dt, const Eigen::VectorXd& x, const Eigen::VectorXd& x_n,
                            const Eigen::VectorXd& v_n, const Eigen::VectorXd& a_n, Eigen::VectorXd& v,
                            Eigen::VectorXd& a) const {
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
    case TimeScheme::none: return;
  }
}

}  // namespace fe2
