#include "common/materials/active_stress.h"

namespace fe2 {

FibreStretch fibre_stretch(const Mat3& F, const Mat3& Fdot) {
  const Vec3 a = F.col(0);
  const double lambda = a.norm();
  return {lambda, a.dot(Fdot.col(0)) / lambda};
}

void add_active_stress(const Mat3& F, const Mat3& Fdot, const ActiveTension& T, double n_t,
                       Vec9& Pi, Mat9& A, Mat9& A_rate) {
  const Vec3 a = F.col(0), a_dot = Fdot.col(0);
  const FibreStretch s = fibre_stretch(F, Fdot);
  Mat3 M = n_t * Mat3::Identity();
  M(0, 0) += 1.0 - n_t;
  const Mat3 FM = F * M;
  Pi += T.Ta * as_vec9(FM);
  // ∂λ/∂F_k1 = a_k/λ,  ∂λ̇/∂F_k1 = ȧ_k/λ − λ̇ a_k/λ²,  ∂λ̇/∂Ḟ_k1 = a_k/λ  (zero for L ≠ 1)
  const Vec3 dT_dF1 = T.dTa_dlambda * a / s.lambda +
                      T.dTa_dlambda_dot * (a_dot / s.lambda - s.lambda_dot * a / (s.lambda * s.lambda));
  const Vec3 dT_dFdot1 = T.dTa_dlambda_dot * a / s.lambda;
  const Vec9 fm = as_vec9(FM);
  for (int k = 0; k < 3; ++k) {
    A.col(index9(k, 0)) += fm * dT_dF1[k];
    A_rate.col(index9(k, 0)) += fm * dT_dFdot1[k];
  }
  // T_a δ_ik M_LJ from ∂F/∂F
  for (int i = 0; i < 3; ++i)
    for (int J = 0; J < 3; ++J)
      for (int L = 0; L < 3; ++L) A(index9(i, J), index9(i, L)) += T.Ta * M(L, J);
}

}  // namespace fe2
