#include "common/materials/NeoHookean.h"

#include "common/materials/kinematics.h"

#include <cmath>

namespace fe2 {

NeoHookean::NeoHookean(double E, double nu) : lame_(lame_from_young_poisson(E, nu, kName)) {}

double NeoHookean::energy(const Vec9& Z) const {
  const double lnJ = std::log(checked_jacobian(deformation_gradient(Z), kName));
  // tr C − 3 = 2 tr Z + Z:Z, exact without the cancellation of forming C.
  const double trC_minus_3 = 2.0 * (Z(0) + Z(4) + Z(8)) + Z.squaredNorm();
  const auto [lambda, mu] = lame_;
  return 0.5 * mu * trC_minus_3 - mu * lnJ + 0.5 * lambda * lnJ * lnJ;
}

Vec9 NeoHookean::stress(const Vec9& Z) const {
  const Mat3 F = deformation_gradient(Z);
  const auto [cof, J] = checked_cofactor(F, kName);
  const double lnJ = std::log(J);
  const Mat3 F_invT = cof / J;
  const auto [lambda, mu] = lame_;
  return as_vec9(mu * (F - F_invT) + lambda * lnJ * F_invT);
}

void NeoHookean::stress_and_tangent(const Vec9& Z, Vec9& Pi, Mat9& A) const {
  // Every Gauss point of a unit calls this (7 of a unit iteration's 30 ms of assembly):
  // F⁻ᵀ from the cofactors that also give J, and 𝔸 written once, entry by entry.
  const Mat3 F = deformation_gradient(Z);
  const auto [cof, J] = checked_cofactor(F, kName);
  const double lnJ = std::log(J);
  const Mat3 H = cof / J;  // H = F⁻ᵀ, so F⁻¹_Li = H_iL and F⁻¹_Jk = H_kJ
  const auto [lambda, mu] = lame_;

  Eigen::Map<Mat3>(Pi.data()) = mu * (F - H) + lambda * lnJ * H;

  // 𝔸_iJkL = λ H_iJ H_kL + (μ − λ ln J) H_iL H_kJ + μ δ_ik δ_JL, column (k,L) at a time.
  const double c = mu - lambda * lnJ;
  const double* h = H.data();  // h[index9(i, J)] = H_iJ
  for (int L = 0; L < 3; ++L)
    for (int k = 0; k < 3; ++k) {
      double* column = A.col(index9(k, L)).data();
      const double lambda_hkL = lambda * h[index9(k, L)];
      for (int J = 0; J < 3; ++J) {
        const double c_hkJ = c * h[index9(k, J)];
        for (int i = 0; i < 3; ++i)
          column[index9(i, J)] = lambda_hkL * h[index9(i, J)] + c_hkJ * h[index9(i, L)];
      }
    }
  for (int t = 0; t < 9; ++t) A(t, t) += mu;  // μ δ_ik δ_JL
}

}  // namespace fe2
