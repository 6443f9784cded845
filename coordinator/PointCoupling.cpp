#include "coordinator/PointCoupling.h"

#include "common/error.h"
#include "coordinator/agree_on_failure.h"
#include "coordinator/macro/gather.h"

#include <cmath>

namespace fe2 {

namespace {

/// Per point model: whether its units refresh collectively (unit.solver.refresh).
std::vector<bool> collective_models(const RunSpec& spec) {
  std::vector<bool> c;
  for (const auto& m : spec.models)
    c.push_back(m.kind == PointModelSpec::Kind::fe2 && m.plan &&
                m.plan->options.refresh == MicroSolverOptions::Refresh::collective);
  return c;
}

}  // namespace

PointCoupling::PointCoupling(const RunSpec& spec, PointEvaluator& evaluator, const proto::Group& group,
                             const std::vector<int>& owned_elements, const Field& u)
    : evaluator_(evaluator),
      group_(group),
      points_(spec.mesh, spec.formulation.quadrature_degree, spec.wall_elements()),
      owned_points_(points_.points_of(owned_elements)),
      collective_(spec.model_of_points(), collective_models(spec)) {
  FE2_CHECK(points_.points_per_element() == spec.points_per_element,
            "{} points per element, the spec counted {}", points_.points_per_element(),
            spec.points_per_element);
  // The material frame at every point (a rule-based field solves its Laplace problems here).
  const auto field = spec.frame.built ? spec.frame.built : make_frame_field(spec.frame.field, spec.mesh);
  const int np = points_.size();
  Q_.resize(np);
  R_.resize(np);
  activation_time_.assign(np, 0.0);
  for (int k = 0; k < np; ++k) {
    const Vec4& l = points_[k].bary;
    const Bary bary{l[0], l[1], l[2], l[3]};
    Q_[k] = field->at(points_[k].element, bary, points_[k].X);
    R_[k] = frame_rotation(Q_[k]);
    if (spec.activation) activation_time_[k] = spec.activation->at(points_[k].element, bary);
  }
  for (int k : owned_points_) point_dofs_.push_back(u.node_dofs(spec.mesh.element_nodes(points_[k].element)));
  responses_.resize(owned_points_.size());
  Zbar_.assign(owned_points_.size(), Vec9::Zero());
  Zbar_n_ = Zbar_;
  jobs_.resize(owned_points_.size());
}

void PointCoupling::evaluate(int step, int iteration, double t_new, double dt, const Eigen::VectorXd& x,
                             const Eigen::VectorXd& v, bool field_rate, double Zdot_coefficient) {
  std::string why;
  try {
    for (size_t s = 0; s < owned_points_.size(); ++s) {
      const int k = owned_points_[s];
      const MacroPoint& p = points_[k];
      const Vec9 Zbar = p.B * gather(x, point_dofs_[s]);
      const Vec9 Zdot = field_rate ? Vec9(p.B * gather(v, point_dofs_[s])) : Vec9((Zbar - Zbar_n_[s]) / dt);
      // Non-finite first: NaN compares false, so it would pass as "inverted" below.
      if (!Zbar.allFinite() || !Zdot.allFinite())
        throw NumericalError(fmt::format("non-finite macro displacement gradient Z̄ or rate Ż̄ at "
                                         "point {} (element {}), t = {:.6g}, dt = {:.3g}",
                                         k, p.element, t_new, dt));
      const double J = (Mat3::Identity() + as_mat3(Zbar)).determinant();
      if (!std::isfinite(J))
        throw NumericalError(fmt::format("non-finite det F̄ at point {} (element {}), t = {:.6g}", k,
                                         p.element, t_new));
      if (!(J > 0.0))
        throw NumericalError(fmt::format("macro element {} inverted at point {}, t = {:.6g} (det F̄ = {:.3e})",
                                         p.element, k, t_new, J));
      Zbar_[s] = Zbar;
      proto::JobInput& job = jobs_[s];
      job.unit = k;
      job.step = step;
      job.iteration = iteration;
      job.time = t_new;
      job.dt = dt;
      job.apply_update = iteration > 1;
      job.force_refresh = force_refresh_ || collective_.due(k) ? 1 : 0;
      job.Zbar = R_[k] * Zbar;  // Z̄_μ = QᵀZ̄Q
      job.Zbar_dot = R_[k] * Zdot;
      job.Zbar_dot_coefficient = Zdot_coefficient;
      job.activation_time = activation_time_[k];
      job.settle = settle_ ? 1 : 0;
    }
  } catch (const NumericalError& e) {
    why = e.what();
  }
  agree_on_failure(group_, why);
  evaluator_.evaluate(jobs_, results_);
  for (const auto& r : results_) {
    if (!why.empty()) break;
    if (r.failed) {
      // The unit's own message says what failed; where it sits is the coordinator's to say.
      const MacroPoint& p = points_[r.unit];
      why = fmt::format("{} (the FE² unit of point {}: macro element {}, at ({:.3g}, {:.3g}, {:.3g}))", r.message,
                        r.unit, p.element, p.X[0], p.X[1], p.X[2]);
    }
    else if (!r.A_hom.allFinite() || !r.P_tilde.allFinite() || !r.P_bar.allFinite() ||
             !std::isfinite(r.r_norm) || !std::isfinite(r.r_ref))
      why = fmt::format("point {}: non-finite stress, tangent or residual at t = {:.6g}", r.unit, t_new);
  }
  agree_on_failure(group_, why);
  settle_ = false;  // every point is settled now (a failure above threw)
  for (size_t s = 0; s < owned_points_.size(); ++s) {
    const Mat9& R = R_[owned_points_[s]];
    responses_[s].A = R.transpose() * results_[s].A_hom * R;  // back to the global frame
    responses_[s].P_tilde = R.transpose() * results_[s].P_tilde;
    responses_[s].P_bar = R.transpose() * results_[s].P_bar;
    responses_[s].active_tension = results_[s].active_tension;
  }
}

void PointCoupling::commit() {
  evaluator_.commit_step();
  collective_.commit();
  Zbar_n_ = Zbar_;
}

void PointCoupling::rollback() {
  evaluator_.rollback_step();
  collective_.rollback();
  Zbar_ = Zbar_n_;
}

void PointCoupling::restore(const Eigen::VectorXd& x_n) {
  // Z̄_n as the last converged iteration computed it: B̄ ū_n.
  for (size_t s = 0; s < owned_points_.size(); ++s)
    Zbar_n_[s] = points_[owned_points_[s]].B * gather(x_n, point_dofs_[s]);
  Zbar_ = Zbar_n_;
}

PointFields PointCoupling::gather_fields() const {
  // P̄ (9) and T_a (1) per point, summed onto the first coordinator.
  constexpr size_t kPer = 10;
  std::vector<double> flat(kPer * static_cast<size_t>(points_.size()), 0.0);
  for (size_t s = 0; s < owned_points_.size(); ++s) {
    double* at = &flat[kPer * static_cast<size_t>(owned_points_[s])];
    std::copy(responses_[s].P_bar.data(), responses_[s].P_bar.data() + 9, at);
    at[9] = responses_[s].active_tension;
  }
  group_.reduce_sum(flat.data(), static_cast<int>(flat.size()), 0);
  PointFields f;
  f.P.resize(points_.size());
  f.active_tension.resize(points_.size());
  for (int k = 0; k < points_.size(); ++k) {
    f.P[k] = Eigen::Map<const Vec9>(&flat[kPer * static_cast<size_t>(k)]);
    f.active_tension[k] = flat[kPer * static_cast<size_t>(k) + 9];
  }
  return f;
}

}  // namespace fe2
