#pragma once
// Compressible neo-Hookean law (e.g. Bonet & Wood, Eq. 6.28):
//
//   W(F)     = μ/2 (tr C − 3) − μ ln J + λ/2 (ln J)²,          C = FᵀF, J = det F
//   Π_iJ     = μ (F − F⁻ᵀ)_iJ + λ ln J F⁻ᵀ_iJ
//   𝔸_iJkL   = μ δ_ik δ_JL + (μ − λ ln J) F⁻¹_Li F⁻¹_Jk + λ F⁻¹_Ji F⁻¹_Lk
//
// Written directly in F (no S, ℂ and push-forward): this is the cheapest law per
// Gauss point, and the micro units evaluate it ~75k times per assembly.
// At F = I the tangent is the isotropic small-strain tensor with Lamé λ, μ.
#include "common/materials/Material.h"
#include "common/materials/lame.h"

namespace fe2 {

class NeoHookean final : public Material {
 public:
  static constexpr const char* kName = "neo_hookean";

  /// Young's modulus E (Pa) > 0 and Poisson's ratio −1 < ν < ½.
  NeoHookean(double E, double nu);

  std::string name() const override { return kName; }
  double energy(const Vec9& Z) const override;
  void stress_and_tangent(const Vec9& Z, Vec9& Pi, Mat9& A) const override;
  Vec9 stress(const Vec9& Z) const override;
  /// λ + 2μ, the largest entry of the small-strain tangent (P-wave modulus).
  double stiffness_scale() const override { return lame_.lambda + 2.0 * lame_.mu; }

  const LameParameters& lame() const { return lame_; }

 private:
  LameParameters lame_;
};

}  // namespace fe2
