#pragma once
// Rule-based fibres (frame kind "rule"): the Laplace–Dirichlet rule-based method of
// Bayer, Blake, Plank, Trayanova, "A novel rule-based algorithm for assigning
// myocardial fiber orientation to computational heart models", Ann. Biomed. Eng. 40
// (2012) 2243–2254 (LDRB), on the tet vertices (P1):
//   ψ: ψ = 0 on `apex`, 1 on `base`                     (apico-basal; `apex` ""
//        means the node of `epi` farthest from the centroid of `base`, Bayer's apex)
//   LV:  φ = 0 on `endo`, 1 on `epi`                     (transmural)
//   BiV: φ_epi (1 on epi, 0 on both endo), φ_lv (1 on the LV endo, 0 on RV endo and
//        epi), φ_rv (1 on the RV endo, 0 on LV endo and epi)  (Bayer §2.2)
// At a point, from the interpolated values and the element's gradients:
//   axis: t = ∇φ/|∇φ| (transmural, out of the wall), l = ∇ψ made orthogonal to t
//         (apico-basal, towards the base), c = l × t (circumferential). Bayer keeps ∇ψ
//         and tilts t; here t is kept so that the sheet is exactly transmural.
//   orient: α(φ) = α_endo + (α_epi − α_endo) φ, β(φ) likewise;
//         f = cos α c + sin α l (the helix angle α is measured from c towards l in the
//         plane orthogonal to ∇φ); w = −sin α c + cos α l; s = cos β t + sin β w;
//         n = f × s. (Bayer's orient(Q, α, β) = Q·R_t(α)·R_f(β), columns f, ·, s.)
//   BiV: Bayer's two-cavity interpolation: Q_lv = orient(axis(∇ψ, −∇φ_lv), α_s, β_s),
//         Q_rv = orient(axis(∇ψ, ∇φ_rv), α_s, β_s), depth d = φ_rv/(φ_lv + φ_rv),
//         α_s = α_endo (1 − 2d) (septum: the RV side mirrors the LV helix),
//         Q_endo = bislerp(Q_lv, Q_rv, d); Q_epi = orient(axis(∇ψ, ∇φ_epi), α(φ_epi),
//         β(φ_epi)); Q = bislerp(Q_endo, Q_epi, φ_epi). bislerp: quaternion slerp from the
//         symmetry-equivalent of Q_a (±, or turned by π about one of its own axes, which
//         leaves the fibre, sheet and normal lines unchanged) closest to Q_b
//         (frame_interpolation.h, shared with the nodal fibre files).
// Evaluated inside elements only, so never at the apex point where ∇ψ is singular.
// Gradients are the element's (constant); where one vanishes (all four vertices on one
// surface), the recovered nodal gradients interpolated to the point. Where ∇ψ vanishes
// or is parallel to ∇φ, l falls back to the mesh's long axis (the
// centroid of `apex` to that of `base`) made orthogonal to t, and failing that to
// any direction orthogonal to t. A vanishing ∇φ is an InputError naming the element.
#include "common/fibres/FrameField.h"
#include "common/fibres/frame_interpolation.h"  // bislerp
#include "common/mesh/TetMesh.h"

#include <string>
#include <vector>

namespace fe2 {

struct RuleFrameOptions {
  double alpha_endo = 60, alpha_epi = -60, beta_endo = 0, beta_epi = 0;  ///< degrees
  std::string endo = "endo", epi = "epi", base = "base";  ///< named node sets / faces
  std::string apex;     ///< named node set; "": the `epi` node farthest from the base centroid
  std::string rv_endo;  ///< non-empty: biventricular, with `endo` the LV endocardium
};

class RuleFrame : public FrameField {
 public:
  /// Solves the Laplace problems on `mesh` (copies what it needs). Throws InputError if
  /// a named set is missing or empty, or a problem is ill-posed (see solve_laplace_p1).
  RuleFrame(const TetMesh& mesh, RuleFrameOptions opt);

  Mat3 at(int e, const Bary& lambda, const Vec3& X) const override;

  /// The rule's axes [c l t] (circumferential, apico-basal, transmural) at a point, from
  /// ∇ψ and ∇φ (BiV: ∇φ_epi); the helix angle is atan2(f·l, f·c).
  Mat3 axes(int e, const Bary& lambda) const;
  /// The transmural coordinate at a point: φ (LV) or φ_epi (BiV), in [0, 1].
  double transmural(int e, const Bary& lambda) const;
  bool biventricular() const { return !opt_.rv_endo.empty(); }

 private:
  /// A Laplace solution: nodal values and recovered nodal gradients (volume-weighted
  /// means of the element gradients around each vertex).
  struct Field {
    std::vector<double> u;
    std::vector<Vec3> g;
  };
  Field field(const TetMesh& mesh, std::vector<double> u) const;
  /// Bayer's axis(∇ψ, g) as [c l t], with t = g/|g| kept exactly.
  Mat3 axis(int e, const Bary& l, const Vec3& g) const;
  /// Bayer's orient(axis(∇ψ, g), α, β) as [f · s] (a proper rotation).
  Mat3 oriented(int e, const Bary& l, const Vec3& g, double alpha, double beta) const;
  double value(const Field& f, int e, const Bary& l) const;
  /// The element's gradient; where that vanishes (a tet whose vertices all lie on one
  /// Dirichlet surface, e.g. a sliver on a thin septum), the interpolated nodal one.
  Vec3 gradient(const Field& f, int e, const Bary& l) const;

  RuleFrameOptions opt_;
  std::vector<std::array<int, 4>> tets_;
  std::vector<std::array<Vec3, 4>> grads_;  ///< ∇λ_a per element
  Field psi_, phi_, phi_lv_, phi_rv_;  ///< phi_: φ (LV) or φ_epi (BiV)
  Vec3 long_axis_ = Vec3::UnitZ();
  double length_ = 1;  ///< the mesh's bounding-box diagonal (scale of gradients)
};

}  // namespace fe2
