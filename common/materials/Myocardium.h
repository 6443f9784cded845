#pragma once
// Myocardium as the heart needs it at a material point: a passive law, plus the active
// stress of contracting cells (a cell model, active_stress.h) and Kelvin–Voigt viscosity
// (kelvin_voigt.h), each only where the spec asks:
//
//   Π(Z, Ż) = Π_passive(Z) + F S_a(T_a(λ, λ̇; cell state)) + F η Ė(Z, Ż)
//
// The point's history is [passive law's history | cell state | T_a], the last only so
// that output and tests can read the tension a point produced. The cell state advances
// over the step from its committed value at every evaluation (MaterialPointContext.h),
// so Newton iterations and cut-backs repeat exactly.
#include "common/cellmodels/CellModel.h"
#include "common/materials/Material.h"

namespace fe2 {

struct MyocardiumOptions {
  CellModelPtr cell;               ///< null: passive (no active stress)
  double transverse_fraction = 0;  ///< n_t ∈ [0, 1)
  double viscosity = 0;            ///< η (Pa·s), 0: none
};

class Myocardium final : public Material {
 public:
  Myocardium(MaterialPtr passive, MyocardiumOptions options);

  std::string name() const override { return passive_->name(); }
  std::string description() const override;
  /// The passive energy (active and viscous stresses have no potential).
  double energy(const Vec9& Z) const override { return passive_->energy(Z); }
  /// Without a context: the resting, still material (the passive law alone).
  void stress_and_tangent(const Vec9& Z, Vec9& Pi, Mat9& A) const override {
    passive_->stress_and_tangent(Z, Pi, A);
  }
  double stiffness_scale() const override { return passive_->stiffness_scale(); }
  bool major_symmetric() const override;
  int history_size() const override { return passive_history_ + cell_history_ + (options_.cell ? 1 : 0); }
  bool uses_context() const override { return true; }
  bool rate_dependent() const override;
  void initial_history(std::span<double> history) const override;
  void stress_and_tangent_at(const Vec9& Z, const MaterialPointContext& context, PointHistory history,
                             Vec9& Pi, Mat9& A, Mat9& A_rate) const override;

  const Material& passive() const { return *passive_; }
  const MyocardiumOptions& options() const { return options_; }
  /// Where T_a sits in the history (−1 without a cell model).
  int tension_slot() const { return options_.cell ? passive_history_ + cell_history_ : -1; }
  int active_tension_slot() const override { return tension_slot(); }

 private:
  MaterialPtr passive_;
  MyocardiumOptions options_;
  int passive_history_ = 0, cell_history_ = 0;
};

}  // namespace fe2
