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

/// J = det F; an inverted (or NaN) point is a NumericalError, so a Newton driver can
/// cut its step back instead of carrying NaN (Material.h contract).
inline double checked_jacobian(const Mat3& F, std::string_view model) {
  const double J = F.determinant();
  if (!(J > 0.0))
    throw NumericalError(fmt::format("{}: inverted material point: det F = {}", model, J));
  return J;
}

}  // namespace fe2
