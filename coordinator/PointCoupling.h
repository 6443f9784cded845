#pragma once
// The coupling of the macro problem to its integration points (paper Fig. 5 (a)–(e)):
// each owned point's frame Q (R = kron(Qᵀ, Qᵀ)) and activation time; Z̄_k = B̄_k ū and its
// rate, checked and rotated into the point's frame as a job (Z̄_μ = R Z̄); the points'
// answers (𝔸_hom, P̃, P̄) rotated back (PointResponse, what PointStressTerm assembles);
// the committed Z̄ of the step; whether the next jobs refactor every unit (a stalled
// Newton, a collective refresh).
#include "coordinator/MacroPoints.h"
#include "coordinator/PointEvaluator.h"
#include "coordinator/RunSpec.h"
#include "coordinator/farm/CollectiveRefresh.h"
#include "coordinator/macro/FieldTable.h"
#include "coordinator/macro/PointStressTerm.h"
#include "proto/Transport.h"

#include <vector>

namespace fe2 {

/// What the points answered at the last evaluation, for output (on the first coordinator).
struct PointFields {
  std::vector<Vec9> P;                ///< P̄ per point (global frame)
  std::vector<double> active_tension; ///< T_a per point (0 where nothing contracts), Pa
};

class PointCoupling {
 public:
  /// `evaluator` and `group` are lent; `u` is the displacement field.
  PointCoupling(const RunSpec& spec, PointEvaluator& evaluator, const proto::Group& group,
                const std::vector<int>& owned_elements, const Field& u);

  const MacroPoints& points() const { return points_; }
  const Mat3& frame(int point) const { return Q_[point]; }
  /// The owned points' answers, in the global frame (lent to PointStressTerm).
  const std::vector<PointResponse>& responses() const { return responses_; }
  /// The owned points' raw answers of the last evaluation (norms, work, costs).
  const std::vector<proto::JobOutput>& results() const { return results_; }

  /// (a)–(e) at the trial state: `x`, `v` every DOF; `Zdot_coefficient` = ∂Ż̄/∂Z̄ and
  /// `field_rate` whether Ż̄ = B̄ v̄ (else the backward difference of Z̄ over dt).
  /// Throws the same NumericalError on every coordinator if any point failed.
  /// @note Collective.
  void evaluate(int step, int iteration, double t_new, double dt, const Eigen::VectorXd& x,
                const Eigen::VectorXd& v, bool field_rate, double Zdot_coefficient);
  /// The next iteration's jobs refactor every unit (a stalled Newton).
  void force_refresh(bool on) { force_refresh_ = on; }
  /// The points start afresh under the restored macro state (--fresh-units): the next
  /// evaluation asks each to settle at its Z̄ first (proto::JobInput::settle), and so
  /// does every evaluation until one succeeds.
  void settle_points() { settle_ = true; }
  bool refresh_forced() const { return force_refresh_; }
  CollectiveRefresh& collective() { return collective_; }

  /// output.units: the chosen units' micro fields (on the first coordinator). @note Collective.
  std::vector<proto::UnitFields> unit_fields(const std::vector<int>& units, int step) {
    return evaluator_.unit_fields(units, step);
  }

  void commit();
  void rollback();
  /// After a restart: Z̄_n of the restored ū_n.
  void restore(const Eigen::VectorXd& x_n);
  /// Per point, the last P̄ in the global frame and T_a, on coordinator 0. @note Collective.
  PointFields gather_fields() const;

 private:
  PointEvaluator& evaluator_;
  const proto::Group& group_;
  MacroPoints points_;
  std::vector<int> owned_points_;      ///< this coordinator's points (= units), ascending
  std::vector<Mat3> Q_;                ///< frame per point
  std::vector<Mat9> R_;
  std::vector<double> activation_time_;  ///< t_act per point (s)
  std::vector<std::vector<int>> point_dofs_;  ///< per owned point: its element's ū DOFs
  std::vector<Vec9> Zbar_, Zbar_n_;    ///< per owned point: current and committed Z̄
  std::vector<proto::JobInput> jobs_;
  std::vector<proto::JobOutput> results_;
  std::vector<PointResponse> responses_;
  /// Set when the coupled Newton stopped contracting with kept factors (stale χ, stale A_hom).
  bool force_refresh_ = false;
  bool settle_ = false;
  /// unit.solver.refresh "collective": when all units of a model refactor together.
  CollectiveRefresh collective_;
};

}  // namespace fe2
