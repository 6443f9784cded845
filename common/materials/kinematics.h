#pragma once
// Kinematics of one material point, shared by the hyperelastic laws:
//
//   F = I + Z,   J = det F,   E = ½(FᵀF − I) = ½(Z + Zᵀ + ZᵀZ).
//
// E is formed from Z rather than from C − I so that small strains keep their digits.
#include "common/error.h"
#include "common/tensor9.h"

#include <string_view>

namespace fe2 {

/// F = I + Z.
inline Mat3 deformation_gradient(const Vec9& Z) { return Mat3::Identity() + as_mat3(Z); }

/// E = ½(Z + Zᵀ + ZᵀZ).
inline Mat3 green_lagrange_strain(const Vec9& Z) {
  const Mat3 Zm = as_mat3(Z);
  return 0.5 * (Zm + Zm.transpose() + Zm.transpose() * Zm);
}

/// An inverted (or NaN) point, J = det F not > 0, is a NumericalError, so a Newton
/// driver can cut its step back instead of carrying NaN (Material.h contract).
inline void require_positive_jacobian(double J, std::string_view model) {
  if (!(J > 0.0))
    throw NumericalError(fmt::format("{}: inverted material point: det F = {}", model, J));
}

/// J = det F, checked (require_positive_jacobian).
inline double checked_jacobian(const Mat3& F, std::string_view model) {
  const double J = F.determinant();
  require_positive_jacobian(J, model);
  return J;
}

/// cof F = J F⁻ᵀ and J = det F expanded along its first row, checked: a law that needs
/// F⁻ᵀ = cof F / J gets both from one set of 2×2 minors.
struct CofactorJacobian {
  Mat3 cof;
  double J;
};
inline CofactorJacobian checked_cofactor(const Mat3& F, std::string_view model) {
  Mat3 cof;
  cof(0, 0) = F(1, 1) * F(2, 2) - F(1, 2) * F(2, 1);
  cof(0, 1) = F(1, 2) * F(2, 0) - F(1, 0) * F(2, 2);
  cof(0, 2) = F(1, 0) * F(2, 1) - F(1, 1) * F(2, 0);
  cof(1, 0) = F(0, 2) * F(2, 1) - F(0, 1) * F(2, 2);
  cof(1, 1) = F(0, 0) * F(2, 2) - F(0, 2) * F(2, 0);
  cof(1, 2) = F(0, 1) * F(2, 0) - F(0, 0) * F(2, 1);
  cof(2, 0) = F(0, 1) * F(1, 2) - F(0, 2) * F(1, 1);
  cof(2, 1) = F(0, 2) * F(1, 0) - F(0, 0) * F(1, 2);
  cof(2, 2) = F(0, 0) * F(1, 1) - F(0, 1) * F(1, 0);
  const double J = F(0, 0) * cof(0, 0) + F(0, 1) * cof(0, 1) + F(0, 2) * cof(0, 2);
  require_positive_jacobian(J, model);
  return {cof, J};
}

}  // namespace fe2
