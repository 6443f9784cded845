#include "common/materials/StVenantKirchhoff.h"

#include "common/materials/kinematics.h"

namespace fe2 {

StVenantKirchhoff::StVenantKirchhoff(double E, double nu)
    : lame_(lame_from_young_poisson(E, nu, kName)) {
  const auto [lambda, mu] = lame_;
  CC_.setZero();
  CC_.topLeftCorner<3, 3>().setConstant(lambda);
  // 2μ 𝕀: 2μ on normal pairs (𝕀_1111 = 1), μ on shear pairs (𝕀_2323 = ½).
  CC_.diagonal() += Vec6(2 * mu, 2 * mu, 2 * mu, mu, mu, mu);
}

Mat3 StVenantKirchhoff::get_S(const Mat3& E) const {
  return lame_.lambda * E.trace() * Mat3::Identity() + 2.0 * lame_.mu * E;
}

double StVenantKirchhoff::energy(const Vec9& Z) const {
  checked_jacobian(deformation_gradient(Z), kName);
  const Mat3 E = green_lagrange_strain(Z);
  const double trE = E.trace();
  return 0.5 * lame_.lambda * trE * trE + lame_.mu * E.squaredNorm();
}

Vec9 StVenantKirchhoff::stress(const Vec9& Z) const {
  const Mat3 F = deformation_gradient(Z);
  checked_jacobian(F, kName);
  return as_vec9(F * get_S(green_lagrange_strain(Z)));
}

void StVenantKirchhoff::stress_and_tangent(const Vec9& Z, Vec9& Pi, Mat9& A) const {
  const Mat3 F = deformation_gradient(Z);
  checked_jacobian(F, kName);
  push_forward(F, get_S(green_lagrange_strain(Z)), CC_, Pi, A);
}

}  // namespace fe2
