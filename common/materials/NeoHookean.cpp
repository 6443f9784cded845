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
  const double lnJ = std::log(checked_jacobian(F, kName));
  const Mat3 F_invT = F.inverse().transpose();
  const auto [lambda, mu] = lame_;
  return as_vec9(mu * (F - F_invT) + lambda * lnJ * F_invT);
}

void NeoHookean::stress_and_tangent(const Vec9& Z, Vec9& Pi, Mat9& A) const {
  const Mat3 F = deformation_gradient(Z);
  const double lnJ = std::log(checked_jacobian(F, kName));
  // H = F⁻ᵀ, so F⁻¹_Li = H_iL and F⁻¹_Jk = H_kJ.
  const Mat3 H = F.inverse().transpose();
  const auto [lambda, mu] = lame_;

  Eigen::Map<Mat3>(Pi.data()) = mu * (F - H) + lambda * lnJ * H;

  // λ F⁻¹_Ji F⁻¹_Lk = λ vec(H) vec(H)ᵀ.
  const Eigen::Map<const Vec9> h(H.data());
  A.noalias() = lambda * h * h.transpose();
  // (μ − λ ln J) H_iL H_kJ: column (k,L), block rows J hold H_kJ · H(:,L).
  const double c = mu - lambda * lnJ;
  for (int L = 0; L < 3; ++L)
    for (int k = 0; k < 3; ++k)
      for (int J = 0; J < 3; ++J)
        A.block<3, 1>(3 * J, index9(k, L)) += (c * H(k, J)) * H.col(L);
  // μ δ_ik δ_JL.
  A.diagonal().array() += mu;
}

}  // namespace fe2
