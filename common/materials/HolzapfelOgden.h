#pragma once
// Holzapfel & Ogden's orthotropic law for passive myocardium (Phil. Trans. R. Soc. A
// 367 (2009) 3445–3475), in the material frame of the unit (axis 1 = fibre
// f₀, 2 = sheet s₀, 3 = sheet-normal n₀), with a volumetric part U:
//
//   Ψ = a/(2b) (e^{b(I₁* − 3)} − 1)
//     + Σ_{i=f,s} a_i/(2b_i) (e^{b_i (I_4i − 1)²} − 1)   [only while I_4i ≥ 1]
//     + a_fs/(2b_fs) (e^{b_fs I_8fs²} − 1)
//     + U(J)
//
//   I₁ = tr C,  I_4f = f₀·C f₀ = C₁₁,  I_4s = s₀·C s₀ = C₂₂,  I_8fs = f₀·C s₀ = C₁₂,
//   C = FᵀF = I + 2E (the invariants are formed from E, to keep digits at small strain).
//
// The fibre and sheet terms act only in tension: collagen and myocytes buckle rather
// than bear compression, as the paper argues. W and S are C¹ across I_4i = 1 (ψ' = 0
// there from both sides); ℂ jumps by 4a_i. At I_4i = 1 exactly (the reference state)
// the tangent takes the tension side: a Newton step from the reference then sees the
// fibre stiffness 4a_f instead of only the matrix (~2a, 600 times softer), which
// sends a first step under fibre tension far into the exponential.
//
// Isotropic invariant I₁* (key "isotropic"):
//   "isochoric" (default)  I₁* = Ī₁ = J^{-2/3} I₁: the reference is stress free with
//                          any U, and the term carries no volume change.
//   "full"                 I₁* = I₁, as in the paper's incompressible setting; it has a
//                          reference stress S = a I (a pure pressure), which the mixed
//                          formulation's pressure takes up, so it requires
//                          "volumetric": "none" (with a penalty the reference would
//                          not be stress free: refused).
// The anisotropic terms always use the full I_4f, I_4s, I_8fs: with isochoric
// anisotropic invariants a fibre-stretched body does not resist volume change the way
// the tissue does (Sansour 2008; Helfenstein et al. 2010), the known flaw of the
// fully split form, which is why the split is made on the isotropic term only.
//
// U (volumetric.h): penalty κ/2 (J − 1)² (default) or none.
//
// Stress and tangent. Each term is ψ(I) for an invariant I(C): with G = ∂I/∂C and
// H = ∂²I/∂C∂C,  S = 2 ψ' G,  ℂ = ∂S/∂E = 4 (ψ'' G⊗G + ψ' H):
//
//   isotropic   ψ' = a/2 e^{b(I₁*−3)},   ψ'' = ab/2 e^{b(I₁*−3)}
//               full:      G = I,  H = 0
//               isochoric: G = J^{-2/3}(I − ⅓ I₁ C⁻¹),
//                          H = J^{-2/3}(−⅓(I⊗C⁻¹ + C⁻¹⊗I) + ⅑ I₁ C⁻¹⊗C⁻¹ + ⅓ I₁ 𝕀_{C⁻¹})
//   fibre i     ψ' = a_i (I_4i − 1) e^{b_i(I_4i−1)²},  ψ'' = a_i (1 + 2b_i (I_4i−1)²) e^{…}
//               G = e_i⊗e_i, H = 0  (the term is absent while I_4i < 1)
//   fibre–sheet ψ' = a_fs I_8fs e^{b_fs I_8fs²},  ψ'' = a_fs (1 + 2b_fs I_8fs²) e^{…}
//               G = ½(f₀⊗s₀ + s₀⊗f₀), H = 0
//
// Small-strain limit (isochoric, penalty), from the tension side: ℂ(0) = 2a(𝕀 − ⅓ I⊗I)
// + κ I⊗I + 4a_fs G_fs⊗G_fs + 4a_f on ℂ₁₁₁₁ + 4a_s on ℂ₂₂₂₂ (ℂ₁₂₁₂ gains a_fs); from
// the compression side without the last two. Π and 𝔸 by push_forward (hyperelastic_push.h). Moduli in
// Pa, exponents dimensionless. An exponent that overflows is a NumericalError.
#include "common/materials/Material.h"
#include "common/materials/hyperelastic_push.h"
#include "common/materials/volumetric.h"

#include <array>
#include <string>

namespace fe2 {

enum class IsotropicInvariant { isochoric, full };

/// Spec names of IsotropicInvariant, the default first.
inline const std::array<std::string, 2> kIsotropicInvariantNames = {"isochoric", "full"};

struct HolzapfelOgdenParameters {
  // Holzapfel & Ogden 2009, Table 1 (simple shear data of Dokos et al. 2002, the
  // orthotropic fit), converted from kPa to Pa.
  double a = 59.0;       ///< Pa, isotropic matrix
  double b = 8.023;      ///< isotropic exponent
  double af = 18472.0;   ///< Pa, fibre
  double bf = 16.026;    ///< fibre exponent
  double as = 2481.0;    ///< Pa, sheet
  double bs = 11.12;     ///< sheet exponent
  double afs = 216.0;    ///< Pa, fibre–sheet coupling
  double bfs = 11.436;   ///< fibre–sheet exponent
  /// Pa, volumetric penalty: as Guccione's default, κ/a ≈ 1700. Benchmarks with HO use
  /// 1e6 with mixed elements; in a penalty-only unit of soft ECM (E = 2 kPa) that
  /// contrast inverts ECM points in the first Newton step, 1e5 converges.
  double kappa = 1.0e5;
  IsotropicInvariant isotropic = IsotropicInvariant::isochoric;
  Volumetric volumetric = Volumetric::penalty;  ///< none: κ is unused
};

class HolzapfelOgden final : public Material {
 public:
  static constexpr const char* kName = "holzapfel_ogden";

  /// a, b, b_f, b_s, b_fs > 0; a_f, a_s, a_fs >= 0 (zero drops the term: the
  /// transversely isotropic fits); κ > 0 with the penalty; the full I₁ only without
  /// the penalty. InputError otherwise.
  explicit HolzapfelOgden(const HolzapfelOgdenParameters& p);

  std::string name() const override { return kName; }
  double energy(const Vec9& Z) const override;
  void stress_and_tangent(const Vec9& Z, Vec9& Pi, Mat9& A) const override;
  /// 2a + 4 max(a_f, a_s) + κ: ℂ₁₁₁₁ at E = 0 from the tension side, rounded up
  /// (without κ when volumetric is none).
  double stiffness_scale() const override;

  const HolzapfelOgdenParameters& parameters() const { return p_; }

 private:
  /// e^x, checked finite (`term` names the exponential in the error).
  double get_exp(double x, const char* term) const;

  HolzapfelOgdenParameters p_;
};

}  // namespace fe2
