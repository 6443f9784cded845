#pragma once
// The micro-unit element kernel: one hexahedron's contribution to the averaged
// quantities of DESIGN §1, at the unit's current state (w, Z̄):
//
//   Z = Z̄ + B̃ w                    (displacement gradient at a Gauss point)
//   r = ⟨B̃ᵀ Π⟩      K = ⟨B̃ᵀ 𝔸 B̃⟩    G = ⟨B̃ᵀ 𝔸⟩    H = ⟨𝔸 B̃⟩    Ā = ⟨𝔸⟩    P̄ = ⟨Π⟩
//
// with ⟨·⟩ = |Y|⁻¹ ∫_Y · dX. Paper: r_wk = −|ē_k| r (Eq. 5), A_wk = |ē_k| K, G_k, Ā_k.
// Element unknowns are ordered component-major, local index 8i + a (component i of
// node a), so each (i,k) block of K is a contiguous 8x8 product ∇Nᵀ D ∇N.
// The kernel works on fixed-size arrays only; scatter into the unit lives elsewhere.
#include "common/materials/Material.h"
#include "worker/hex8.h"

namespace fe2 {

struct HexContribution {
  Eigen::Matrix<double, 24, 24> K;  ///< ⟨B̃ᵀ𝔸B̃⟩ of this element
  Eigen::Matrix<double, 24, 1> r;   ///< ⟨B̃ᵀΠ⟩
  Eigen::Matrix<double, 9, 24> H;   ///< ⟨𝔸B̃⟩ (G = Hᵀ when 𝔸 has major symmetry)
  Eigen::Matrix<double, 24, 9> G;   ///< ⟨B̃ᵀ𝔸⟩, filled only when need_G
  Mat9 Abar;                        ///< ⟨𝔸⟩
  Vec9 Pbar;                        ///< ⟨Π⟩
};

/// What an element's Gauss points see besides Z, for a law that reads its context
/// (Material::uses_context): at Gauss point q,
///
///   Ż = Ż̄ + B̃ ẇ,    history = [q·h, (q+1)·h) of the element's arrays, h = history_size()
struct HexPointContext {
  double time = 0.0;
  double dt = 0.0;
  Vec9 Zbar_dot = Vec9::Zero();          ///< Ż̄
  double Zbar_dot_coefficient = 0.0;     ///< ∂Ż̄/∂Z̄ of the macro integrator
  double activation_time = 0.0;          ///< the unit's activation time (s)
  Eigen::Matrix<double, 3, 8> w_dot_e;   ///< ẇ of the element's nodes, as w_e
  const double* history_committed = nullptr;  ///< 8·h values (null when h = 0)
  double* history = nullptr;                  ///< 8·h values, written
};

/// Local element unknown index of component i at node a.
constexpr int hex_local(int i, int a) { return 8 * i + a; }

/// Computes one element's contribution. `w_e(i,a)` = w of node a, component i.
/// `inv_volume` = 1/|Y|. `point` is null for a law that reads no context (the
/// stateless path, unchanged). Throws NumericalError if a Gauss point is inverted.
void hex_contribution(const HexGeometry& geo, double inv_volume,
                      const Eigen::Matrix<double, 3, 8>& w_e, const Vec9& Zbar,
                      const Material& material, bool need_G, HexContribution& out,
                      const HexPointContext* point = nullptr);

}  // namespace fe2
