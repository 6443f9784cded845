#pragma once
// Central finite differences of a Material's energy and stress, for the tests that
// check Π = ∂W/∂Z and 𝔸 = ∂Π/∂Z (truncation O(h²), round-off O(ε W / h)).
#include "common/materials/Material.h"

namespace fe2::testing {

/// Π_a ≈ (W(Z + h e_a) − W(Z − h e_a)) / 2h.
inline Vec9 fd_stress(const Material& m, const Vec9& Z, double h) {
  Vec9 Pi;
  for (int a = 0; a < 9; ++a) {
    Vec9 Zp = Z, Zm = Z;
    Zp(a) += h;
    Zm(a) -= h;
    Pi(a) = (m.energy(Zp) - m.energy(Zm)) / (2 * h);
  }
  return Pi;
}

/// Column b of 𝔸 ≈ (Π(Z + h e_b) − Π(Z − h e_b)) / 2h.
inline Mat9 fd_tangent(const Material& m, const Vec9& Z, double h) {
  Mat9 A;
  for (int b = 0; b < 9; ++b) {
    Vec9 Zp = Z, Zm = Z;
    Zp(b) += h;
    Zm(b) -= h;
    A.col(b) = (m.stress(Zp) - m.stress(Zm)) / (2 * h);
  }
  return A;
}

}  // namespace fe2::testing
