#pragma once
// The macro terms of a scene (MacroTerm.h), each built only when the scene asks for it:
//   PointStressTerm      the point models' response (Eq. 10): always
//   InertiaTerm          consistent mass under Newmark-β: time.scheme = newmark
//   FollowerPressureTerm pressure on deformed surfaces: /pressure
//   IncompressibilityTerm mixed u–p: formulation.kind = mixed
#include "coordinator/MacroPoints.h"
#include "coordinator/MacroTerm.h"

#include <memory>

namespace fe2 {

/// DOFs 3a + i of the given nodes (node-major).
std::vector<int> displacement_dofs(const std::vector<int>& nodes);

/// A point's answer, in the global frame.
struct PointResponse {
  Mat9 A = Mat9::Zero();      ///< 𝔸_hom
  Vec9 P_tilde = Vec9::Zero();///< P̃ (Eq. 9), drives Newton
  Vec9 P_bar = Vec9::Zero();  ///< P̄, the true stress (convergence)
  double active_tension = 0.0;///< T_a of the point's cells (output)
};

/// f_int = Σ_k |ē_k| B̄_kᵀ P̄_k, K = Σ_k |ē_k| B̄_kᵀ 𝔸_k B̄_k over the owned elements;
/// `responses[s]` answers the s-th owned point (ascending point ids).
class PointStressTerm final : public MacroTerm {
 public:
  PointStressTerm(const TetMesh& mesh, const MacroPoints& points, std::vector<int> owned_elements,
                  const std::vector<PointResponse>& responses);
  std::string name() const override { return "point stress"; }
  void declare(MacroSystem& system) override;
  void assemble(const MacroState& state, MacroAssembly& out) override;

 private:
  const TetMesh& mesh_;
  const MacroPoints& points_;
  std::vector<int> owned_;
  const std::vector<PointResponse>& responses_;
  std::vector<int> block_;
  std::vector<std::vector<int>> dofs_;
};

/// Newmark inertia: f_int += M ṻ, K += M/(βΔt²), M the consistent mass ρ∫N_a N_b (a rule
/// of degree 2·order, exact on affine elements).
class InertiaTerm final : public MacroTerm {
 public:
  InertiaTerm(const TetMesh& mesh, std::vector<int> owned_elements, double density);
  std::string name() const override { return "inertia"; }
  void declare(MacroSystem& system) override;
  void assemble(const MacroState& state, MacroAssembly& out) override;
  /// The element's scalar mass matrix (n x n, ρ∫N_a N_b).
  const Eigen::MatrixXd& element_mass(int k) const { return mass_[k]; }

 private:
  const TetMesh& mesh_;
  std::vector<int> owned_;
  std::vector<Eigen::MatrixXd> mass_;
  std::vector<int> block_;
  std::vector<std::vector<int>> dofs_;
};

/// Follower pressure t = −p n on the deformed surface (p > 0 pushes against the outward
/// normal of the solid, i.e. into it): f_ext,a = −p ∫ N_a (∂x/∂ξ₁ × ∂x/∂ξ₂) dξ over
/// linear or 6-node triangles, with its (unsymmetric) consistent tangent.
class FollowerPressureTerm final : public MacroTerm {
 public:
  /// Triangles k with k % parts == part of every /pressure load (dealt out in turn).
  FollowerPressureTerm(const RunSpec& spec, int part, int parts);
  std::string name() const override { return "follower pressure"; }
  void declare(MacroSystem& system) override;
  void assemble(const MacroState& state, MacroAssembly& out) override;

 private:
  const RunSpec& spec_;
  struct Face {
    std::vector<int> nodes;
    int load;
  };
  std::vector<Face> faces_;
  std::vector<int> block_;
  std::vector<std::vector<int>> dofs_;
};

/// Mixed u–p (a P1 pressure p on the vertices, positive in compression; enriched: plus a
/// constant per element, P2/(P1+P0), so ∫_e (J̄ − 1) = 0 on every element), for any point
/// model: the point's P̄ and 𝔸 enter unchanged and this term adds, from
///   Π(ū, p) = ∫ W − ∫ p (J̄ − 1) − ∫ p²/(2κ)      (κ = ∞: Lagrange multiplier)
/// at the same quadrature points:
///   R_u += −∫ p cof F̄ : δF̄          K_uu += −∫ p δF̄ : ∂cof F̄/∂F̄ : ΔF̄
///   R_p  = −∫ q (J̄ − 1) − (1/κ) M p  K_up = K_puᵀ = −∫ (cof F̄ : δF̄) q     K_pp = −M/κ
/// with ∂(cof F̄)_iJ/∂F̄_kL = (cof_iJ cof_kL − cof_iL cof_kJ)/J̄ and M the P1 mass matrix.
/// Equal-order P1/P1 adds the pressure-projection stabilization (Dohrmann & Bochev
/// 2004): −(1/μ_s) ∫ (p − Π₀p)(q − Π₀q), Π₀ the element mean, to R_p and K_pp.
class IncompressibilityTerm final : public MacroTerm {
 public:
  IncompressibilityTerm(const TetMesh& mesh, const MacroPoints& points, std::vector<int> owned_elements,
                        const FormulationSpec& formulation);
  std::string name() const override { return "incompressibility"; }
  void declare(MacroSystem& system) override;
  void assemble(const MacroState& state, MacroAssembly& out) override;
  /// ∫ N_p over the owned elements, per pressure unknown (the scale of R_p: volumes).
  const Eigen::VectorXd& pressure_volumes() const { return volumes_; }

 private:
  const TetMesh& mesh_;
  const MacroPoints& points_;
  std::vector<int> owned_;
  FormulationSpec formulation_;
  const MacroSystem* system_ = nullptr;
  std::vector<int> block_;
  std::vector<std::vector<int>> dofs_;     ///< ū DOFs then the 4 vertex pressures (+ its constant)
  std::vector<int> num_pressure_;          ///< pressure unknowns per element: 4, or 5 (P1+P0)
  std::vector<Eigen::MatrixXd> pressure_matrix_;  ///< −M/κ − S/μ_s per element
  Eigen::VectorXd volumes_;
};

}  // namespace fe2
