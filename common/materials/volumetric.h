#pragma once
// The volumetric part of a law written in the material frame (Guccione,
// Holzapfel–Ogden), chosen per spec:
//
//   penalty:  U(J) = κ/2 (J − 1)²   (near incompressibility by a penalty; the default)
//   none:     U = 0                 (the macro mixed formulation's pressure field
//                                    enforces J̄ = 1, or J̄ − 1 = p/κ, itself)
//
// With U = U(J(C)) and ∂J/∂C = ½ J C⁻¹ (tensor components, Voigt storage of
// hyperelastic_push.h):
//
//   S_vol = U'J C⁻¹
//   ℂ_vol = (U'J + U''J²) C⁻¹⊗C⁻¹ − 2U'J 𝕀_{C⁻¹},
//   𝕀_{C⁻¹,IJKL} = ½(C⁻¹_IK C⁻¹_JL + C⁻¹_IL C⁻¹_JK),   U' = κ(J − 1), U'' = κ.
//
// U'' = κ is constant, so U is convex for every J > 0 (κ/2 (ln J)² is convex only for
// J < e); the price is that U stays bounded as J → 0, so inversion is caught by the
// det F check, not by the energy.
#include "common/materials/hyperelastic_push.h"

#include <array>
#include <string>

namespace fe2 {

enum class Volumetric { penalty, none };

/// Spec names, in the order spec-doc lists them (the first is the default).
inline const std::array<std::string, 2> kVolumetricNames = {"penalty", "none"};

inline Volumetric volumetric_from_name(const std::string& name) {
  return name == "none" ? Volumetric::none : Volumetric::penalty;
}

/// U = κ/2 (J − 1)².
inline double volumetric_penalty_energy(double kappa, double J) {
  return 0.5 * kappa * (J - 1.0) * (J - 1.0);
}

/// Adds S_vol and ℂ_vol of the penalty (header comment) to S and CC; c = C⁻¹ in Voigt.
inline void add_volumetric_penalty(double kappa, double J, const Mat3& C_inv, const Vec6& c,
                                   Vec6& S, Mat6& CC) {
  const double dUJ = kappa * (J - 1.0) * J;  // U' J
  const double d2UJ2 = kappa * J * J;        // U'' J²
  S += dUJ * c;
  CC.noalias() += (dUJ + d2UJ2) * c * c.transpose();
  for (int p = 0; p < 6; ++p)
    for (int q = 0; q < 6; ++q) {
      const int I = voigt6_row(p), Jj = voigt6_col(p), K = voigt6_row(q), L = voigt6_col(q);
      CC(p, q) -= dUJ * (C_inv(I, K) * C_inv(Jj, L) + C_inv(I, L) * C_inv(Jj, K));
    }
}

}  // namespace fe2
