#pragma once
// Inertia of the wall under Newmark-β (time.scheme = newmark): f_int += M ṻ,
// K += M ∂ṻ/∂ū = M/(βΔt²), with M the consistent mass ρ∫N_a N_b (a rule of degree
// 2·order, exact on affine elements), on the displacement field.
#include "coordinator/macro/MacroTerm.h"

namespace fe2 {

class InertiaTerm final : public MacroTerm {
 public:
  InertiaTerm(const TetMesh& mesh, std::vector<int> owned_elements, double density);
  std::string name() const override { return "inertia"; }
  void declare(MacroSystem& system) override;
  void assemble(const MacroState& state, MacroAssembly& out) override;
  /// wall_kinetic_energy: ½ u̇ᵀ M u̇ (the wall's share of a coupled energy balance).
  void observe(const MacroState& state, std::vector<Observable>& out) const override;
  /// The element's scalar mass matrix (n x n, ρ∫N_a N_b).
  const Eigen::MatrixXd& element_mass(int k) const { return mass_[k]; }

 private:
  const TetMesh& mesh_;
  std::vector<int> owned_;
  std::vector<Eigen::MatrixXd> mass_;
  const Field* u_ = nullptr;
  std::vector<int> local_;
  std::vector<std::vector<int>> dofs_;
};

}  // namespace fe2
