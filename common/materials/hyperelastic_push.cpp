#include "common/materials/hyperelastic_push.h"

namespace fe2 {

void push_forward(const Mat3& F, const Mat3& S, const Mat6& CC, Vec9& Pi, Mat9& A) {
  Eigen::Map<Mat3>(Pi.data()) = F * S;

  // Stage 1: T_{iJ,b} = F_iI ℂ_{IJ,b}, b the Voigt pair (KL). Only 6 of the 9 KL
  // columns exist thanks to the minor symmetry ℂ_IJKL = ℂ_IJLK.
  Eigen::Matrix<double, 9, 6> T;
  for (int b = 0; b < 6; ++b)
    for (int J = 0; J < 3; ++J)
      for (int i = 0; i < 3; ++i)
        T(index9(i, J), b) = F(i, 0) * CC(voigt6(0, J), b) + F(i, 1) * CC(voigt6(1, J), b) +
                             F(i, 2) * CC(voigt6(2, J), b);

  // Stage 2: 𝔸_{iJ,kL} = F_kK T_{iJ,KL}, one 9-column of 𝔸 at a time.
  for (int L = 0; L < 3; ++L)
    for (int k = 0; k < 3; ++k)
      A.col(index9(k, L)) = F(k, 0) * T.col(voigt6(0, L)) + F(k, 1) * T.col(voigt6(1, L)) +
                            F(k, 2) * T.col(voigt6(2, L));

  // Geometric (initial-stress) part δ_ik S_JL.
  for (int L = 0; L < 3; ++L)
    for (int J = 0; J < 3; ++J)
      for (int i = 0; i < 3; ++i) A(index9(i, J), index9(i, L)) += S(J, L);
}

}  // namespace fe2
