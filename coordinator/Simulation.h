#pragma once
// The macro problem and its Newton driver (paper Fig. 5), in the order the algorithm
// reads: for each step, for each Newton iteration —
//   (a) Z̄_k = B̄_k ū at every point, rotated into the unit frame (Z̄_μ = R Z̄)
//   (b–e) the points answer (𝔸_hom, P̃, P̄)           [PointEvaluator]
//   (g) S̄ = Σ |ē_k| B̄ᵀ 𝔸_hom B̄ (+ inertia, follower pressure), ḡ = f_ext − Σ |ē_k| B̄ᵀ P̃
//   (i) converged when the macro residual (with P̄) and every unit's ‖r‖ are small
//   (h) solve S̄ Δū = ḡ (MUMPS), (j) ū += Δū
// A step that fails (divergence, NaN, inverted element, iteration cap) is rolled back
// and cut in half, up to newton.max_cutbacks times; then the run stops, saying where
// and why.
#include "coordinator/MacroSystem.h"
#include "coordinator/MumpsSolver.h"
#include "coordinator/PointEvaluator.h"
#include "coordinator/RunSpec.h"
#include "coordinator/Trace.h"
#include "coordinator/tet_kinematics.h"
#include "proto/Transport.h"

#include <functional>
#include <string>
#include <vector>

namespace fe2 {

struct StepRecord {
  int step = 0;
  double time = 0.0;
  int iterations = 0;                 ///< Newton iterations of the accepted (sub)steps
  int cutbacks = 0;
  std::vector<double> residuals;      ///< macro ‖R_free‖ / F_ref per iteration (last substep)
  std::vector<double> micro_residuals;///< max_k ‖r_k‖ / r_ref,k per iteration (last substep)
  int gmres_iterations = 0;
  int refreshes = 0;
  double wall_seconds = 0.0;
  double micro_cpu_seconds = 0.0;
};

struct RunResult {
  bool converged = false;
  int steps = 0;                      ///< steps completed
  int newton_iterations = 0;
  std::vector<StepRecord> history;
  std::string error;                  ///< why the run stopped early, if it did
};

class Simulation {
 public:
  /// One process owning every element. `points` is lent.
  Simulation(const RunSpec& spec, PointEvaluator& points);
  /// A coordinator of a farm owning `owned_tets` (ascending); `coordinators` is lent.
  /// @note Collective on the coordinator group (the MUMPS communicator).
  Simulation(const RunSpec& spec, PointEvaluator& points, const proto::Group& coordinators,
             std::vector<int> owned_tets);

  /// Called after every accepted step (for output); may be empty.
  using StepHook = std::function<void(const StepRecord&)>;
  /// Called after every Newton iteration with its phase times (traces); may be empty.
  using IterationHook = std::function<void(const IterationTiming&)>;
  /// @note Collective.
  RunResult run(const StepHook& on_step = {}, const IterationHook& on_iteration = {});

  const RunSpec& spec() const { return spec_; }
  const Eigen::VectorXd& displacement() const { return u_; }
  const std::vector<TetPoint>& points() const { return pts_; }
  /// Per point, the last P̄ in the global frame, gathered on coordinator 0.
  /// @note Collective.
  std::vector<Vec9> gather_point_stress() const;
  const Mat3& frame(int e) const { return Q_[e]; }
  /// Deformed position of a reference point inside the mesh.
  Vec3 deformed_position(const Vec3& X) const;

  /// One Newton solve from the committed state to time t_new; true if converged.
  bool newton(int step, double t_new, double dt, StepRecord& rec);

 private:
  void compute_jobs(int step, int iteration, double t_new, double dt, bool apply_update);
  /// Throws the same NumericalError on every coordinator if any of them failed
  /// (`why` non-empty on the ones that did). @note Collective.
  void agree_on_failure(const std::string& why) const;
  void commit(double t_new);
  void rollback();

  const RunSpec& spec_;
  PointEvaluator& evaluator_;
  proto::Group self_;                  ///< MPI_COMM_SELF for the one-process form
  const proto::Group& group_;
  std::vector<int> owned_;             ///< this coordinator's tets (= units)
  MacroSystem system_;
  MumpsSolver mumps_;
  std::vector<TetPoint> pts_;
  std::vector<Mat3> Q_;
  std::vector<Mat9> R_;
  // Macro state: current and committed (u, v, a node-major 3a+i).
  Eigen::VectorXd u_, v_, a_, u_n_, v_n_, a_n_;
  std::vector<Vec9> Zbar_n_;           ///< committed Z̄ per point (for Ż̄ when quasi-static)
  std::vector<Vec9> P_bar_;
  double t_n_ = 0.0;
  std::vector<proto::JobInput> jobs_;
  std::vector<proto::JobOutput> results_;
  std::vector<double> values_;         ///< S̄ triplet values
  IterationHook on_iteration_;
};

}  // namespace fe2
