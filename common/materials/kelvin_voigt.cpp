#include "common/materials/kelvin_voigt.h"

namespace fe2 {

void add_kelvin_voigt_stress(const Mat3& F, const Mat3& Fdot, double eta, Vec9& Pi, Mat9& A,
                             Mat9& A_rate) {
  const Mat3 E_dot = 0.5 * (F.transpose() * Fdot + Fdot.transpose() * F);
  const Mat3 S_v = eta * E_dot;
  Pi += as_vec9(F * S_v);
  const Mat3 FFdt = F * Fdot.transpose(), FFt = F * F.transpose();
  const double h = 0.5 * eta;
  for (int i = 0; i < 3; ++i)
    for (int J = 0; J < 3; ++J)
      for (int k = 0; k < 3; ++k)
        for (int L = 0; L < 3; ++L) {
          const double dJL = J == L ? 1.0 : 0.0;
          A(index9(i, J), index9(k, L)) +=
              (i == k ? S_v(L, J) : 0.0) + h * (F(i, L) * Fdot(k, J) + FFdt(i, k) * dJL);
          A_rate(index9(i, J), index9(k, L)) += h * (F(i, L) * F(k, J) + FFt(i, k) * dJL);
        }
}

}  // namespace fe2
