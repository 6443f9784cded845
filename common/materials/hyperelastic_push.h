#pragma once
// Push-forward of a material-frame (S, ℂ) pair to the two-point pair (Π, 𝔸) that the
// kernels use (DESIGN §1):
//
//   Π_iJ     = F_iI S_IJ
//   𝔸_iJkL   = ∂Π_iJ/∂Z_kL = δ_ik S_JL + F_iI F_kK ℂ_IJKL,
//
// with S the second Piola–Kirchhoff stress and ℂ = ∂S/∂E = 2 ∂S/∂C the material
// tangent. Laws written in the Green–Lagrange strain E = ½(FᵀF − I) (St Venant–
// Kirchhoff, Guccione) supply (S, ℂ) and call push_forward once per Gauss point.
//
// Storage of ℂ (the Mat6 below): Voigt pairs in the order 11, 22, 33, 23, 13, 12
// holding the TENSOR components, CC(a, b) = ℂ_IJKL with a ~ (IJ), b ~ (KL). There is
// no engineering-shear factor 2 and no Mandel √2: the minor symmetries
// ℂ_IJKL = ℂ_JIKL = ℂ_IJLK are what make 6x6 enough, nothing else is folded in.
#include "common/tensor9.h"

namespace fe2 {

using Mat6 = Eigen::Matrix<double, 6, 6>;
using Vec6 = Eigen::Matrix<double, 6, 1>;

/// Voigt index of the symmetric pair (I, J): 11→0, 22→1, 33→2, 23→3, 13→4, 12→5.
inline constexpr int kVoigt6[3][3] = {{0, 5, 4}, {5, 1, 3}, {4, 3, 2}};
/// The pair (I, J), I <= J, of each Voigt index: the inverse of kVoigt6.
inline constexpr int kVoigt6Row[6] = {0, 1, 2, 1, 0, 0};
inline constexpr int kVoigt6Col[6] = {0, 1, 2, 2, 2, 1};

constexpr int voigt6(int I, int J) { return kVoigt6[I][J]; }
constexpr int voigt6_row(int a) { return kVoigt6Row[a]; }
constexpr int voigt6_col(int a) { return kVoigt6Col[a]; }

/// Voigt vector of the tensor components of a symmetric 3x3 matrix.
inline Vec6 to_voigt(const Mat3& M) {
  Vec6 v;
  for (int a = 0; a < 6; ++a) v(a) = M(voigt6_row(a), voigt6_col(a));
  return v;
}

/// Symmetric 3x3 matrix of a Voigt vector of tensor components.
inline Mat3 from_voigt(const Vec6& v) {
  Mat3 M;
  for (int I = 0; I < 3; ++I)
    for (int J = 0; J < 3; ++J) M(I, J) = v(voigt6(I, J));
  return M;
}

/// Π = F S and 𝔸_iJkL = δ_ik S_JL + F_iI F_kK ℂ_IJKL (see the header comment).
/// Contracts in two stages, T_iJ,KL = F_iI ℂ_IJKL (162 multiplies) and then
/// 𝔸_iJkL = F_kK T_iJ,KL (243 multiplies), all on the stack: it runs once per
/// micro Gauss point.
void push_forward(const Mat3& F, const Mat3& S, const Mat6& CC, Vec9& Pi, Mat9& A);

}  // namespace fe2
