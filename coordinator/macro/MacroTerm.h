#pragma once
// A macro term: one piece of physics of the macro problem over the block system
// (MFEM's integrators on a BlockOperator): the points' stress, inertia, follower
// pressure, incompressibility, cavity pressures. Each looks up the fields it needs by
// name and declares its local matrices once, then adds its residual and tangent every
// Newton iteration, and keeps whatever history it has through commit/rollback. A term
// that is off is not built: it allocates and assembles nothing.
//
// Sign convention: the residual is R = f_int − f_ext (zero at equilibrium) and the
// tangent is K = ∂R/∂x, so Newton solves K Δx = −R. A point model's R̃ (with P̃, Eq. 9)
// drives Newton; the true R (with P̄) decides convergence.
#include "common/bytes.h"
#include "coordinator/macro/MacroSystem.h"
#include "coordinator/macro/TimeIntegration.h"

#include <Eigen/Dense>
#include <string>
#include <vector>

namespace fe2 {

/// The state the terms read: the current iterate and its rates, at the new time.
struct MacroState {
  const Eigen::VectorXd& x;   ///< every DOF, field by field (FieldTable offsets)
  const Eigen::VectorXd& v;   ///< ẋ of the fields that have a rate (zero elsewhere)
  const Eigen::VectorXd& a;   ///< ẍ of second-order fields
  double time = 0.0;
  double dt = 0.0;
  std::vector<RateCoefficients> rates;  ///< per field id: ∂v/∂x, ∂a/∂x (empty: none)
  /// ∂v/∂x and ∂a/∂x of `field`'s scheme (zero if it has no rate).
  RateCoefficients rate(const Field& field) const {
    return field.id() < static_cast<int>(rates.size()) ? rates[field.id()] : RateCoefficients{};
  }
};

/// Where the terms add: tangent values in the pattern, and residual parts over every DOF.
class MacroAssembly {
 public:
  MacroAssembly(const MacroSystem& system, std::vector<double>& values);
  void clear();

  /// K over the local matrix's DOFs (MacroSystem::declare_local) into the matrix.
  void add_tangent(int local, const Eigen::MatrixXd& K);
  /// Internal force over `dofs`: the true one (convergence) and the one Newton uses.
  void add_internal(const std::vector<int>& dofs, const Eigen::VectorXd& f_true,
                    const Eigen::VectorXd& f_newton);
  void add_internal(const std::vector<int>& dofs, const Eigen::VectorXd& f) { add_internal(dofs, f, f); }
  /// External force over `dofs` (loads): R = f_int − f_ext.
  void add_external(const std::vector<int>& dofs, const Eigen::VectorXd& f);

  /// The prescribed increment Δx_D of the first iteration, or null: every local
  /// matrix added while it is set also moves K_fD Δx_D to the right-hand side.
  void set_lift(const Eigen::VectorXd* du_D) { lift_ = du_D; }

  const Eigen::VectorXd& internal() const { return internal_; }
  const Eigen::VectorXd& external() const { return external_; }
  Eigen::VectorXd& internal() { return internal_; }
  Eigen::VectorXd& external() { return external_; }
  /// −R̃ − K_fD Δx_D on the free equations: the Newton right-hand side (this process's part).
  std::vector<double>& rhs() { return rhs_; }

 private:
  const MacroSystem& system_;
  std::vector<double>& values_;
  Eigen::VectorXd internal_, external_;
  std::vector<double> rhs_;
  const Eigen::VectorXd* lift_ = nullptr;
};

/// A scalar a term reports at the end of every step (summary.json
/// history[].observables): its value on this coordinator's part, summed over the
/// coordinators (integrals, fluxes), or their minimum (a worst quality).
struct Observable {
  std::string name;
  double value = 0.0;
  bool minimum = false;
};

class MacroTerm {
 public:
  virtual ~MacroTerm() = default;
  virtual std::string name() const = 0;
  /// The physics it belongs to: the traces give each one's share of the macro's
  /// assembly (IterationTiming::assemble_fluid).
  enum class Physics { wall, fluid, circulation };
  virtual Physics physics() const { return Physics::wall; }
  /// Looks up its fields and declares its local matrices in the pattern (once, before
  /// the first assembly).
  virtual void declare(MacroSystem& system) = 0;
  /// Adds this process's part of the residual scale s of `field` (its size), for the
  /// fields measured by ResidualNorm::scaled_l2 or scaled_max (and a floor of the load
  /// for relative_to_load); summed over coordinators.
  virtual void add_residual_scale(const Field& /*field*/, Eigen::VectorXd& /*scale*/) const {}
  /// Adds residual and tangent at `state`.
  virtual void assemble(const MacroState& state, MacroAssembly& out) = 0;
  /// Appends its observables at the committed state; the same names, in the same order,
  /// on every coordinator.
  virtual void observe(const MacroState& /*state*/, std::vector<Observable>& /*out*/) const {}
  /// The step converged at `state`: false if that contradicts a discrete choice the term
  /// held for the step (a valve ring's state). The term has then made the other choice,
  /// and the step is solved again from its start (Simulation::advance; a few times at most).
  virtual bool accept(const MacroState& /*state*/) { return true; }
  /// The step converged / is being cut back (terms with their own history).
  virtual void commit(const MacroState&) {}
  virtual void rollback() {}
  /// The committed history, for checkpoints (terms without one write nothing).
  virtual void save(ByteWriter&) const {}
  virtual void restore(ByteReader&) {}
};

}  // namespace fe2
