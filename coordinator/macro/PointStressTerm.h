#pragma once
// The point models' response (Eq. 10), always part of the scene:
//   f_int = Σ_k |ē_k| B̄_kᵀ P̄_k (the true force: convergence), f̃ = Σ_k |ē_k| B̄_kᵀ P̃_k
//   (with P̃ of Eq. 9: drives Newton), K = Σ_k |ē_k| B̄_kᵀ 𝔸_hom,k B̄_k
// over the owned elements, on the displacement field.
#include "coordinator/MacroPoints.h"
#include "coordinator/macro/MacroTerm.h"

namespace fe2 {

/// A point's answer, in the global frame.
struct PointResponse {
  Mat9 A = Mat9::Zero();      ///< 𝔸_hom
  Vec9 P_tilde = Vec9::Zero();///< P̃ (Eq. 9), drives Newton
  Vec9 P_bar = Vec9::Zero();  ///< P̄, the true stress (convergence)
  double active_tension = 0.0;///< T_a of the point's cells (output)
};

/// `responses[s]` answers the s-th owned point (ascending point ids); lent.
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
  std::vector<int> local_;
  std::vector<std::vector<int>> dofs_;
};

}  // namespace fe2
