#include "common/materials/Guccione.h"

#include "common/materials/kinematics.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace fe2 {
namespace {

/// Voigt vector of the tensor components of a symmetric 3x3 matrix.
Vec6 to_voigt(const Mat3& M) {
  Vec6 v;
  for (int a = 0; a < 6; ++a) v(a) = M(voigt6_row(a), voigt6_col(a));
  return v;
}

/// Symmetric 3x3 matrix of a Voigt vector of tensor components.
Mat3 from_voigt(const Vec6& v) {
  Mat3 M;
  for (int I = 0; I < 3; ++I)
    for (int J = 0; J < 3; ++J) M(I, J) = v(voigt6(I, J));
  return M;
}

/// Weight of Voigt entry a in a full double sum over (I, J): 1 normal, 2 shear.
constexpr double kShearPairs[6] = {1, 1, 1, 2, 2, 2};

}  // namespace

Guccione::Guccione(const GuccioneParameters& p) : p_(p) {
  const std::pair<const char*, double> checks[] = {
      {"C", p.C}, {"bf", p.bf}, {"bt", p.bt}, {"bfs", p.bfs}, {"kappa", p.kappa}};
  for (const auto& [key, value] : checks)
    if (!(value > 0.0))
      throw InputError(fmt::format("{}: parameter {} = {}, expected > 0", kName, key, value));
  b_ << p.bf, p.bt, p.bt, p.bt, p.bfs, p.bfs;
}

double Guccione::stiffness_scale() const {
  return p_.C * std::max({p_.bf, p_.bt, p_.bfs}) + p_.kappa;
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
  return 0.5 * p_.C * std::expm1(Q) + 0.5 * p_.kappa * (J - 1.0) * (J - 1.0);
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

  // Volumetric penalty, U' J and U'' J² with U = κ/2 (J − 1)².
  const Mat3 F_inv = F.inverse();
  const Mat3 C_inv = F_inv * F_inv.transpose();
  const Vec6 c = to_voigt(C_inv);
  const double dUJ = p_.kappa * (J - 1.0) * J;
  const double d2UJ2 = p_.kappa * J * J;
  S += dUJ * c;
  CC.noalias() += (dUJ + d2UJ2) * c * c.transpose();
  for (int p = 0; p < 6; ++p)
    for (int q = 0; q < 6; ++q) {
      const int I = voigt6_row(p), Jj = voigt6_col(p), K = voigt6_row(q), L = voigt6_col(q);
      CC(p, q) -= dUJ * (C_inv(I, K) * C_inv(Jj, L) + C_inv(I, L) * C_inv(Jj, K));
    }

  push_forward(F, from_voigt(S), CC, Pi, A);
}

}  // namespace fe2
