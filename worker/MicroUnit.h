#pragma once
// One FE² micro unit: the periodic fluctuation w of a cell under the macro gradient
// Z̄, with its cached factor of K and characteristic modes χ. Each call to iterate()
// is one Newton iteration of the coupled problem as the paper's Fig. 5 (b)–(e) and
// Fig. 6 do it:
//
//   (update)  w += δw₁ − χ ΔZ̄                         Eq. (11), Step 4 (a flag)
//   (b)       assemble r, K, G, H, Ā, P̄ at (w, Z̄)     DESIGN §1
//   (c1,c3)   on refresh: factor K, χ = K⁻¹ G           Eq. (6)
//   (c2)      K δw₁ = −r by GMRES, factor as preconditioner   Eq. (8), Step 1
//   (d)       𝔸_hom = Ā − H χ                           Eq. (7)
//   (e)       P̃ = P̄ + H δw₁                             Eq. (9)
//
// The pending δw₁ is applied at the start of the next job when that job says so
// (the coordinator accepted the iteration), with −χ(Z̄_new − Z̄_old) when Step 4 is on.
//
// Laws with a point context (Material::uses_context) get t, Δt of the job and
// Ż = Ż̄ + B̃ẇ at each Gauss point; laws with history get their slice of the unit's
// history arrays (MicroModel::history_offset), committed and rolled back with w.
#include "worker/MicroModel.h"
#include "worker/PointModel.h"
#include "worker/RefreshPolicy.h"
#include "common/linalg/gmres.h"

namespace fe2 {

class MicroUnit final : public PointModel {
 public:
  /// The averaged quantities at one state (DESIGN §1), G n×9, H 9×n.
  struct System {
    Vec r;
    SparseMatrix K;
    Eigen::MatrixXd G;
    Eigen::MatrixXd H;
    Mat9 Abar = Mat9::Zero();
    Vec9 Pbar = Vec9::Zero();
  };

  explicit MicroUnit(MicroModelPtr model);

  proto::JobOutput iterate(const proto::JobInput& in) override;
  void commit_step() override;
  void rollback_step() override;
  void serialize(Bytes& out) const override { serialize_for_checkpoint(out, false); }
  void deserialize(const Bytes& in) override;
  /// With `with_factor`, a CHOLMOD factor is stored (SparseFactor::save); UMFPACK, MUMPS
  /// or a dropped factor store the rebuild flag, as without it.
  void serialize_for_checkpoint(Bytes& out, bool with_factor) const override;
  std::string kind() const override { return "micro_unit"; }
  bool next_refresh(int step, int iteration) const override;
  size_t state_bytes() const override;
  /// SparseFactor::factor_bytes: CHOLMOD's numeric factor (L->xsize doubles) or
  /// UMFPACK's Numeric object, as the libraries count them; the symbolic analysis and
  /// solve workspace (a few per cent) are not counted.
  double factor_bytes() const override { return factor_ ? factor_->factor_bytes() : 0.0; }
  /// Frees the factor; the next job that reuses it rebuilds it from the matrix it was
  /// made of (K at the last refresh), bit for bit, as after a migration.
  void drop_factor() override { factor_.reset(); }

  /// Assembles r, K, G, H, Ā, P̄ at (w, Z̄) into `sys` (its K must hold the pattern),
  /// with the point context of the last job. Laws with history write their current
  /// values into `history` (MicroModel::history_size() doubles), or into a scratch
  /// array when it is null. `element_P`, if given, receives each element's share of P̄
  /// (⟨Π⟩ over that element, so the shares sum to P̄): the micro stress field for output.
  void assemble_at(const Vec& w, const Vec9& Zbar, System& sys,
                   std::vector<double>* history = nullptr,
                   std::vector<Vec9>* element_P = nullptr) const;

  const MicroModel& model() const { return *model_; }
  const Vec& w() const { return w_; }
  /// Z̄ at the last assembled state.
  const Vec9& Zbar() const { return Zbar_; }
  /// Brings the unit from its committed state to equilibrium at `job`'s Z̄ and commits
  /// there (proto::JobInput::settle): see MicroUnit.cpp. Throws NumericalError if it
  /// cannot.
  void settle(const proto::JobInput& job);
  void set_w(const Vec& w) { w_ = w; }
  const Vec& pending_dw1() const { return dw1_; }
  const Eigen::MatrixXd& chi() const { return chi_; }
  const System& system() const { return sys_; }
  int refresh_count() const { return refresh_count_; }
  /// How the last refresh reached χ: rounds of block refinement (0 when the factor's
  /// solve already meets the tolerance or the round-off floor, as an exact factor's does)
  /// and GMRES iterations spent on columns refinement left open.
  struct ChiSolve {
    int refinement_rounds = 0;
    int gmres_iterations = 0;
  };
  const ChiSolve& last_chi_solve() const { return last_chi_solve_; }
  const RefreshPolicy& policy() const { return policy_; }
  FactorKind factor_kind() const { return factor_kind_; }
  const SparseFactor* factor() const { return factor_.get(); }
  /// y = K̃⁻¹ x with the cached factor: one GMRES preconditioner application.
  LinearOp preconditioner() const;
  /// Point history of every Gauss point at the last assembled state, and at the last commit.
  const std::vector<double>& history() const { return history_; }
  /// T_a averaged over the Gauss points of the contracting cells (0 without any).
  double mean_active_tension() const;
  const std::vector<double>& history_committed() const { return history_committed_; }

 private:
  bool refresh_due(const proto::JobInput& in) const;
  void refresh();
  void rebuild_factor();
  /// Step 1 (Fig. 6 c2): K δw₁ = −r to ‖K δw₁ + r‖ ≤ rtol ‖r‖.
  /// Step 1 (Fig. 6 (c2)): K δw₁ = −r by GMRES on the kept factor, at most `max_iterations`
  /// (< 0: the model's gmres_max_iterations).
  GmresResult step1(double rtol, int max_iterations = -1);
  /// ‖r‖ below which the residual is round-off of the assembly (JobOutput::r_floor).
  double residual_floor();
  /// y = K x for GMRES (its first product also keeps |K|𝟙 for residual_floor()).
  LinearOp K_operator();
  /// The residual a solve with K can reach at x, for GMRES's stopping test.
  ResidualFloor solve_floor() const;

  MicroModelPtr model_;
  // --- state (serialized) ---
  Vec w_;                       ///< periodic fluctuation at the last assembled state
  Vec dw1_;                     ///< pending Step 1 increment δw₁
  Vec9 Zbar_ = Vec9::Zero();    ///< Z̄ at the last assembled state
  bool has_pending_ = false;
  Eigen::MatrixXd chi_;         ///< characteristic modes χ (n×9), Eq. (6)
  std::vector<double> K_factored_;  ///< values of K at the last refresh (rebuilds the factor bit for bit)
  FactorKind factor_kind_;
  Vec w_committed_;
  Vec9 Zbar_committed_ = Vec9::Zero();
  RefreshPolicy policy_;            ///< when to refactor (its counters are state)
  int refresh_count_ = 0;
  ChiSolve last_chi_solve_;         ///< diagnostics of the last refresh (not state)
  /// The factor state at the last commit, kept only once a refresh inside the current
  /// step has replaced it: a rolled-back step's retry then starts from exactly the
  /// committed unit (not from a factor and χ of a failed, perhaps inverted, iterate).
  struct FactorState {
    std::vector<double> K_factored;
    Eigen::MatrixXd chi;
    FactorKind kind = FactorKind::cholesky;
  };
  bool refreshed_since_commit_ = false;
  FactorState committed_factor_;    ///< valid while refreshed_since_commit_
  RefreshPolicy policy_committed_;
  int refresh_count_committed_ = 0;
  std::vector<double> history_;            ///< point history at the last assembly
  std::vector<double> history_committed_;  ///< point history at the last commit
  // --- the last job's context (set by every job, so not state) ---
  double time_ = 0.0, dt_ = 0.0;
  Vec9 Zbar_dot_ = Vec9::Zero();
  double Zbar_dot_coefficient_ = 0.0;
  double activation_time_ = 0.0;
  // --- workspace ---
  System sys_;
  Vec abs_row_sums_;              ///< |K|𝟙 of sys_.K, valid while abs_row_sums_current_
  bool abs_row_sums_current_ = false;
  std::unique_ptr<SparseFactor> factor_;
};

}  // namespace fe2
