#include "common/materials/Guccione.h"

#include "common/materials/kinematics.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace fe2 {
namespace {

/// Weight of Voigt entry a in a full double sum over (I, J): 1 normal, 2 shear.
constexpr double kShearPairs[6] = {1, 1, 1, 2, 2, 2};

}  // namespace

Guccione::Guccione(const GuccioneParameters& p) : p_(p) {
  // κ is checked only where it is used: without the penalty it is never read.
  const bool penalty = p.volumetric == Volumetric::penalty;
  const std::pair<const char*, double> checks[] = {
      {"C", p.C}, {"bf", p.bf}, {"bt", p.bt}, {"bfs", p.bfs}, {"kappa", penalty ? p.kappa : 1.0}};
  for (const auto& [key, value] : checks)
    if (!(value > 0.0))
      throw InputError(fmt::format("{}: parameter {} = {}, expected > 0", kName, key, value));
  b_ << p.bf, p.bt, p.bt, p.bt, p.bfs, p.bfs;
}

double Guccione::stiffness_scale() const {
  const double scale = p_.C * std::max({p_.bf, p_.bt, p_.bfs});
  return p_.volumetric == Volumetric::penalty ? scale + p_.kappa : scale;
}

double Guccione::get_Q(const Vec6& e) const {
  double Q = 0.0;
  for (int a = 0; a < 6; ++a) Q += kShearPairs[a] * b_(a) * e(a) * e(a);
  return Q;
}

double Guccione::get_exp_Q(double Q) const {
  const double expQ = std::exp(Q);
  if (!std::isfinite(expQ))
    throw NumericalError(fmt::format("{}: strain too large, Q = {} overflows e^Q", kName, Q));
  return expQ;
}

double Guccione::energy(const Vec9& Z) const {
  const double J = checked_jacobian(deformation_gradient(Z), kName);
  const double Q = get_Q(to_voigt(green_lagrange_strain(Z)));
  get_exp_Q(Q);  // same overflow check as the stress
  // expm1 keeps W's digits at small strain, where e^Q − 1 ≈ Q.
  const double W = 0.5 * p_.C * std::expm1(Q);
  return p_.volumetric == Volumetric::penalty ? W + volumetric_penalty_energy(p_.kappa, J) : W;
}

void Guccione::stress_and_tangent(const Vec9& Z, Vec9& Pi, Mat9& A) const {
  const Mat3 F = deformation_gradient(Z);
  const double J = checked_jacobian(F, kName);
  const Vec6 e = to_voigt(green_lagrange_strain(Z));
  const double CexpQ = p_.C * get_exp_Q(get_Q(e));

  // Exponential part (Q is a diagonal quadratic form in the Voigt strain).
  const Vec6 a = b_.cwiseProduct(e);
  Vec6 S = CexpQ * a;
  Mat6 CC = (2.0 * CexpQ) * a * a.transpose();
  // b_IJ 𝕀_IJKL: 𝕀 is 1 on normal pairs and ½ on shear pairs.
  for (int p = 0; p < 6; ++p) CC(p, p) += CexpQ * b_(p) / kShearPairs[p];

  if (p_.volumetric == Volumetric::penalty) {
    const Mat3 F_inv = F.inverse();
    const Mat3 C_inv = F_inv * F_inv.transpose();
    add_volumetric_penalty(p_.kappa, J, C_inv, to_voigt(C_inv), S, CC);
  }

  push_forward(F, from_voigt(S), CC, Pi, A);
}

}  // namespace fe2
