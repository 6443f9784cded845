#pragma once
// A test-only law whose tangent lacks major symmetry (no strain energy), so a unit
// built from it takes the unsymmetric path: H ≠ Gᵀ and an LU factor (active
// contraction will take the same path). Neo-Hookean plus a linear coupling
//
//   Π_iJ = Π^NH_iJ(Z) + c μ Z_iK M_KJ,    𝔸_iJkL = 𝔸^NH_iJkL + c μ δ_ik M_LJ,
//
// with M a fixed non-symmetric 3×3 matrix: 𝔸_iJkL − 𝔸_kLiJ = c μ δ_ik (M_LJ − M_JL) ≠ 0.
// Π(0) = 0, and small c keeps the unit's K invertible.
#include "common/materials/NeoHookean.h"

namespace fe2::test {

class NonPotentialLaw final : public Material {
 public:
  NonPotentialLaw(double E, double nu, double c) : nh_(E, nu), c_mu_(c * nh_.lame().mu) {
    M_ << 0.0, 0.6, -0.2,  //
        -0.3, 0.0, 0.4,    //
        0.5, -0.1, 0.0;
  }
  std::string name() const override { return "test_non_potential"; }
  /// Only the potential part: this law has no energy (its tangent is not symmetric).
  double energy(const Vec9& Z) const override { return nh_.energy(Z); }
  void stress_and_tangent(const Vec9& Z, Vec9& Pi, Mat9& A) const override {
    nh_.stress_and_tangent(Z, Pi, A);
    Pi += c_mu_ * as_vec9(as_mat3(Z) * M_);
    for (int i = 0; i < 3; ++i)
      for (int J = 0; J < 3; ++J)
        for (int L = 0; L < 3; ++L) A(index9(i, J), index9(i, L)) += c_mu_ * M_(L, J);
  }
  double stiffness_scale() const override { return nh_.stiffness_scale(); }
  bool major_symmetric() const override { return false; }

 private:
  NeoHookean nh_;
  double c_mu_;
  Mat3 M_;
};

}  // namespace fe2::test
