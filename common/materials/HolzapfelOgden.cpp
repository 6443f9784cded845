#include "common/materials/HolzapfelOgden.h"

#include "common/materials/kinematics.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace fe2 {
namespace {

/// The identity in Voigt storage: G of I₁.
const Vec6 kIdentity = (Vec6() << 1, 1, 1, 0, 0, 0).finished();

/// The arguments of the four exponentials, formed from E (C − I = 2E keeps digits).
struct Arguments {
  double I1;      ///< I₁ = tr C
  double x_iso;   ///< I₁* − 3 (I₁* = Ī₁ or I₁)
  double x_f;     ///< I_4f − 1 = 2E₁₁
  double x_s;     ///< I_4s − 1 = 2E₂₂
  double x_fs;    ///< I_8fs = C₁₂ = 2E₁₂
  double J_m23;   ///< J^{-2/3} (1 for the full invariant)
};

Arguments get_arguments(const Mat3& E, double J, IsotropicInvariant isotropic) {
  Arguments r;
  r.I1 = 3.0 + 2.0 * E.trace();
  if (isotropic == IsotropicInvariant::full) {
    r.J_m23 = 1.0;
    r.x_iso = 2.0 * E.trace();
  } else {
    r.J_m23 = std::pow(J, -2.0 / 3.0);
    r.x_iso = r.J_m23 * r.I1 - 3.0;
  }
  r.x_f = 2.0 * E(0, 0);
  r.x_s = 2.0 * E(1, 1);
  r.x_fs = 2.0 * E(0, 1);
  return r;
}

/// 𝕀_{C⁻¹,IJKL} = ½(C⁻¹_IK C⁻¹_JL + C⁻¹_IL C⁻¹_JK) = −∂C⁻¹/∂C, in Voigt storage.
Mat6 get_I_Cinv(const Mat3& C_inv) {
  Mat6 M;
  for (int p = 0; p < 6; ++p)
    for (int q = 0; q < 6; ++q) {
      const int I = voigt6_row(p), J = voigt6_col(p), K = voigt6_row(q), L = voigt6_col(q);
      M(p, q) = 0.5 * (C_inv(I, K) * C_inv(J, L) + C_inv(I, L) * C_inv(J, K));
    }
  return M;
}

}  // namespace

HolzapfelOgden::HolzapfelOgden(const HolzapfelOgdenParameters& p) : p_(p) {
  auto require = [](const char* key, double value, bool zero_allowed) {
    if (!(value > 0.0 || (zero_allowed && value == 0.0)))
      throw InputError(fmt::format("{}: parameter {} = {}, expected {}", kName, key, value,
                                   zero_allowed ? ">= 0" : "> 0"));
  };
  require("a", p.a, false);
  require("b", p.b, false);
  require("af", p.af, true);
  require("bf", p.bf, false);
  require("as", p.as, true);
  require("bs", p.bs, false);
  require("afs", p.afs, true);
  require("bfs", p.bfs, false);
  if (p.volumetric == Volumetric::penalty) require("kappa", p.kappa, false);
  if (p.isotropic == IsotropicInvariant::full && p.volumetric == Volumetric::penalty)
    throw InputError(fmt::format("{}: isotropic = full needs volumetric = none (its reference "
                                 "stress a I is a pressure only a mixed formulation takes up)",
                                 kName));
}

double HolzapfelOgden::stiffness_scale() const {
  const double scale = 2.0 * p_.a + 4.0 * std::max(p_.af, p_.as);
  return p_.volumetric == Volumetric::penalty ? scale + p_.kappa : scale;
}

double HolzapfelOgden::get_exp(double x, const char* term) const {
  const double e = std::exp(x);
  if (!std::isfinite(e))
    throw NumericalError(
        fmt::format("{}: strain too large, the {} exponent {} overflows", kName, term, x));
  return e;
}

double HolzapfelOgden::energy(const Vec9& Z) const {
  const double J = checked_jacobian(deformation_gradient(Z), kName);
  const Arguments x = get_arguments(green_lagrange_strain(Z), J, p_.isotropic);
  // a/(2b)(e^{bx} − 1) with expm1: keeps W's digits at small strain.
  auto term = [&](double a, double b, double bx, const char* name) {
    get_exp(bx, name);  // same overflow check as the stress
    return a / (2.0 * b) * std::expm1(bx);
  };
  double W = term(p_.a, p_.b, p_.b * x.x_iso, "isotropic");
  if (x.x_f >= 0.0) W += term(p_.af, p_.bf, p_.bf * x.x_f * x.x_f, "fibre");
  if (x.x_s >= 0.0) W += term(p_.as, p_.bs, p_.bs * x.x_s * x.x_s, "sheet");
  W += term(p_.afs, p_.bfs, p_.bfs * x.x_fs * x.x_fs, "fibre-sheet");
  if (p_.volumetric == Volumetric::penalty) W += volumetric_penalty_energy(p_.kappa, J);
  return W;
}

void HolzapfelOgden::stress_and_tangent(const Vec9& Z, Vec9& Pi, Mat9& A) const {
  const Mat3 F = deformation_gradient(Z);
  const double J = checked_jacobian(F, kName);
  const Arguments x = get_arguments(green_lagrange_strain(Z), J, p_.isotropic);
  const Mat3 F_inv = F.inverse();
  const Mat3 C_inv = F_inv * F_inv.transpose();
  const Vec6 c = to_voigt(C_inv);

  Vec6 S = Vec6::Zero();   // 2nd Piola–Kirchhoff, Voigt tensor components
  Mat6 CC = Mat6::Zero();  // ℂ = ∂S/∂E

  // Isotropic term: S = 2ψ'G, ℂ = 4(ψ''G⊗G + ψ'H).
  {
    const double e = get_exp(p_.b * x.x_iso, "isotropic");
    const double dpsi = 0.5 * p_.a * e;
    const double d2psi = 0.5 * p_.a * p_.b * e;
    Vec6 G = kIdentity;
    if (p_.isotropic == IsotropicInvariant::isochoric) {
      G = x.J_m23 * (kIdentity - (x.I1 / 3.0) * c);
      const Mat6 H = x.J_m23 * (-(1.0 / 3.0) * (kIdentity * c.transpose() + c * kIdentity.transpose()) +
                                (x.I1 / 9.0) * c * c.transpose() + (x.I1 / 3.0) * get_I_Cinv(C_inv));
      CC.noalias() += (4.0 * dpsi) * H;
    }
    S += (2.0 * dpsi) * G;
    CC.noalias() += (4.0 * d2psi) * G * G.transpose();
  }

  // Fibre (Voigt 0) and sheet (Voigt 1): G = e_i⊗e_i, only in tension.
  const std::pair<double, double> ab[2] = {{p_.af, p_.bf}, {p_.as, p_.bs}};
  const double x4[2] = {x.x_f, x.x_s};
  for (int i = 0; i < 2; ++i) {
    if (!(x4[i] >= 0.0)) continue;  // I_4i < 1: no stress, no stiffness (= 1: tension side)
    const auto [a, b] = ab[i];
    const double e = get_exp(b * x4[i] * x4[i], i == 0 ? "fibre" : "sheet");
    const double dpsi = a * x4[i] * e;
    const double d2psi = a * (1.0 + 2.0 * b * x4[i] * x4[i]) * e;
    S(i) += 2.0 * dpsi;
    CC(i, i) += 4.0 * d2psi;
  }

  // Fibre–sheet coupling: G = ½(f₀⊗s₀ + s₀⊗f₀), Voigt entry 12 = 5 holds ½.
  {
    const double e = get_exp(p_.bfs * x.x_fs * x.x_fs, "fibre-sheet");
    const double dpsi = p_.afs * x.x_fs * e;
    const double d2psi = p_.afs * (1.0 + 2.0 * p_.bfs * x.x_fs * x.x_fs) * e;
    S(5) += dpsi;       // 2ψ'·½
    CC(5, 5) += d2psi;  // 4ψ''·½·½
  }

  if (p_.volumetric == Volumetric::penalty) add_volumetric_penalty(p_.kappa, J, C_inv, c, S, CC);

  push_forward(F, from_voigt(S), CC, Pi, A);
}

}  // namespace fe2
