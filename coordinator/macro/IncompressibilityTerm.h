#pragma once
// Mixed u–p (formulation.kind = mixed): a P1 pressure p on the vertices, positive in
// compression; enriched: plus a constant per element, P2/(P1+P0), so ∫_e (J̄ − 1) = 0 on
// every element. For any point model: the point's P̄ and 𝔸 enter unchanged and this term
// adds, from
//   Π(ū, p) = ∫ W − ∫ p (J̄ − 1) − ∫ p²/(2κ)      (κ = ∞: Lagrange multiplier)
// at the same quadrature points:
//   R_u += −∫ p cof F̄ : δF̄          K_uu += −∫ p δF̄ : ∂cof F̄/∂F̄ : ΔF̄
//   R_p  = −∫ q (J̄ − 1) − (1/κ) M p  K_up = K_puᵀ = −∫ (cof F̄ : δF̄) q     K_pp = −M/κ
// with ∂(cof F̄)_iJ/∂F̄_kL = (cof_iJ cof_kL − cof_iL cof_kJ)/J̄ and M the P1 mass matrix.
// Equal-order P1/P1 adds the pressure-projection stabilization (Dohrmann & Bochev
// 2004): −(1/μ_s) ∫ (p − Π₀p)(q − Π₀q), Π₀ the element mean, to R_p and K_pp.
// R_p has the units of a volume; its scale is ∫N_p (add_residual_scale).
#include "coordinator/MacroPoints.h"
#include "coordinator/RunSpec.h"
#include "coordinator/macro/MacroTerm.h"

namespace fe2 {

class IncompressibilityTerm final : public MacroTerm {
 public:
  IncompressibilityTerm(const TetMesh& mesh, const MacroPoints& points, std::vector<int> owned_elements,
                        const FormulationSpec& formulation);
  std::string name() const override { return "incompressibility"; }
  void declare(MacroSystem& system) override;
  void assemble(const MacroState& state, MacroAssembly& out) override;
  /// The pressure field's scale: ∫ N_p over the owned elements, per pressure unknown.
  void add_residual_scale(const Field& field, Eigen::VectorXd& scale) const override;

 private:
  const TetMesh& mesh_;
  const MacroPoints& points_;
  std::vector<int> owned_;
  FormulationSpec formulation_;
  const Field* p_ = nullptr;
  std::vector<int> local_;
  std::vector<std::vector<int>> dofs_;     ///< ū DOFs then the 4 vertex pressures (+ its constant)
  std::vector<int> num_pressure_;          ///< pressure unknowns per element: 4, or 5 (P1+P0)
  std::vector<Eigen::MatrixXd> pressure_matrix_;  ///< −M/κ − S/μ_s per element
  Eigen::VectorXd volumes_;                ///< ∫ N_p per pressure unknown
};

}  // namespace fe2
