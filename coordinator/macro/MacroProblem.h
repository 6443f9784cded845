#pragma once
// The macro problem of a run: its system (fields, constraints, pattern), its terms, its
// state x with the rates of each field and the committed state of the last step, and
// the solve of S̄ Δx = −R̃ on the coordinators (MUMPS, or the kept factor). The Newton
// driver (Simulation) calls its phases in order:
//   predict  → assemble → residuals → solve → update     (each iteration)
//   commit | rollback                                     (each step)
//   save / restore                                        (checkpoints)
#include "coordinator/RunSpec.h"
#include "coordinator/macro/MacroSolver.h"
#include "coordinator/macro/MacroSystem.h"
#include "coordinator/macro/MacroTerm.h"
#include "proto/Transport.h"

#include <Eigen/Sparse>

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace fe2 {

class MacroProblem {
 public:
  /// `group` (the coordinators) is lent. @note Collective on `group` (MUMPS).
  MacroProblem(const RunSpec& spec, const proto::Group& group, MacroSystem system);

  /// Adds a term. Before the first assemble().
  void add_term(std::unique_ptr<MacroTerm> term);
  const std::vector<std::unique_ptr<MacroTerm>>& terms() const { return terms_; }
  /// Replaces the prescribed values: value(k, t) for the k-th prescribed DOF (tests:
  /// manufactured solutions). Before the first step.
  void set_prescribed_values(std::function<double(int k, double t)> value) { prescribed_value_ = std::move(value); }
  /// Sets the initial state (values and rates, at t_start) by `initial`. Before the first step.
  void set_initial(const std::function<void(const FieldTable&, Eigen::VectorXd& x, Eigen::VectorXd& v)>& initial);

  const MacroSystem& system() const { return system_; }
  const MacroSolver& solver() const { return solver_; }
  /// Every DOF, field by field; its rates (fields with a time scheme).
  const Eigen::VectorXd& x() const { return x_; }
  const Eigen::VectorXd& v() const { return v_; }
  /// The block of field `name`.
  Eigen::VectorXd field_values(const std::string& name) const;
  double committed_time() const { return t_n_; }

  /// Δx_D: the prescribed values at t_new less the committed ones.
  Eigen::VectorXd prescribed_increment(double t_new) const;
  /// Each field's rates of the trial x, by its scheme.
  void predict(double dt);
  /// What the terms see: x, its rates and each field's ∂v/∂x, ∂a/∂x.
  MacroState state(double t_new, double dt) const;
  /// Declares every term's local matrices and the pattern, once. @note Collective.
  void prepare();
  /// (g) every term into S̄ and the residual; `lift` the first iteration's Δx_D or null.
  /// @note Collective.
  void assemble(double t_new, double dt, const Eigen::VectorXd* lift);
  /// Wall seconds the last assemble() spent in the blood's terms (MacroTerm::Physics::fluid)
  /// on this coordinator.
  double fluid_assembly_seconds() const { return fluid_assembly_seconds_; }
  /// (i) each field's residual norm (table order), the same on every coordinator.
  /// @note Collective.
  std::vector<double> residual_norms(double t_new);
  /// (h) S̄ Δx = −R̃; `quasi_static_first`: the matrix is the committed state's, so a
  /// singular one cannot be helped by a cut-back. @note Collective.
  void solve(bool quasi_static_first);
  /// (j) x += Δx (and Δx_D after the first iteration).
  void update(bool first, const Eigen::VectorXd& du_D);
  /// A line search's shorter step: x = x_k + α Δx (and the whole Δx_D if `first`), from
  /// the x_k and Δx of the last update().
  void retract(double alpha, bool first, const Eigen::VectorXd& du_D);
  /// Each field's largest |α Δx| over its free DOFs (table order, the field's units), of
  /// the last solve's correction taken with length α: Newton's order is read in these
  /// (the residual norms are scaled, so their logs' ratio is not an order).
  std::vector<double> correction_norms(double alpha = 1.0) const;

  /// Whether every term accepts the converged step (MacroTerm::accept; each is asked).
  bool accept(double t_new, double dt);
  void commit(double t_new, double dt);
  /// Every term's observables at the committed state, reduced over the coordinators.
  /// @note Collective.
  std::vector<std::pair<std::string, double>> observe() const;
  void rollback();
  /// t, x and its rates, each term's history (the committed state).
  void save(ByteWriter& w) const;
  void restore(ByteReader& r);
  /// The last assembled S̄ over the free equations, as this coordinator holds it (the
  /// whole matrix on one coordinator): for diagnostics and tests (the partitioned
  /// schemes' iteration matrices are blocks of it).
  Eigen::SparseMatrix<double> tangent() const;
  /// Drops the kept macro factor (a restart and the run it continues start alike).
  void drop_factor() { solver_.drop_factor(); }

 private:

  const RunSpec& spec_;
  const proto::Group& group_;
  MacroSystem system_;
  std::vector<std::unique_ptr<MacroTerm>> terms_;
  TimeIntegration time_integration_;
  MacroSolver solver_;
  std::function<double(int, double)> prescribed_value_;
  bool pattern_set_ = false;
  std::vector<Eigen::VectorXd> residual_scales_;  ///< per field (MacroTerm::add_residual_scale), summed
  std::vector<double> values_;         ///< S̄ triplet values
  std::vector<double> du_;             ///< Newton correction on the free equations
  std::unique_ptr<MacroAssembly> assembly_;
  // Current and committed (every DOF; v, a of the fields with a rate).
  Eigen::VectorXd x_, v_, a_, x_n_, v_n_, a_n_;
  Eigen::VectorXd x_nm1_;              ///< committed x of the step before (BDF2)
  double dt_n_ = 0.0;                  ///< the last committed step (0: none yet)
  Eigen::VectorXd x_k_;                ///< x before the last update (retract)
  double t_n_ = 0.0;
  double fluid_assembly_seconds_ = 0.0;
};

}  // namespace fe2
