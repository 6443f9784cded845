#pragma once
// St Venant–Kirchhoff law, linear elasticity in the Green–Lagrange strain:
//
//   W(E) = λ/2 (tr E)² + μ E:E,          E = ½(FᵀF − I)
//   S    = λ tr(E) I + 2μ E
//   ℂ    = λ I⊗I + 2μ 𝕀,                 𝕀_IJKL = ½(δ_IK δ_JL + δ_IL δ_JK)
//
// Π and 𝔸 by push_forward (hyperelastic_push.h). ℂ is constant and built once.
// The law is defined for det F <= 0 too, but such a point is still rejected with a
// NumericalError, as for every Material.
#include "common/materials/Material.h"
#include "common/materials/hyperelastic_push.h"
#include "common/materials/lame.h"

namespace fe2 {

class StVenantKirchhoff final : public Material {
 public:
  static constexpr const char* kName = "st_venant_kirchhoff";

  /// Young's modulus E (Pa) > 0 and Poisson's ratio −1 < ν < ½.
  StVenantKirchhoff(double E, double nu);

  std::string name() const override { return kName; }
  double energy(const Vec9& Z) const override;
  void stress_and_tangent(const Vec9& Z, Vec9& Pi, Mat9& A) const override;
  /// Π = F S alone, without building ℂ's push-forward.
  Vec9 stress(const Vec9& Z) const override;
  /// λ + 2μ, the largest entry of the small-strain tangent (P-wave modulus).
  double stiffness_scale() const override { return lame_.lambda + 2.0 * lame_.mu; }

  const LameParameters& lame() const { return lame_; }

 private:
  /// S = λ tr(E) I + 2μ E.
  Mat3 get_S(const Mat3& E) const;

  LameParameters lame_;
  Mat6 CC_;  ///< ℂ in the tensor-component Voigt storage of hyperelastic_push.h
};

}  // namespace fe2
