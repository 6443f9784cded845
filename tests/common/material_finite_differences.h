#pragma once
// Central finite differences of a Material's energy and stress, for the tests that
// check Π = ∂W/∂Z and 𝔸 = ∂Π/∂Z (truncation O(h²), round-off O(ε W / h)).
#include "common/materials/Material.h"

#include <utility>
#include <vector>

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

/// Π at a point with a context, from the committed history `h_n` (the current history
/// goes to scratch).
inline Vec9 stress_at(const Material& m, const Vec9& Z, const MaterialPointContext& c,
                      const std::vector<double>& h_n) {
  std::vector<double> h(h_n.size());
  Vec9 Pi;
  Mat9 A, A_rate;
  m.stress_and_tangent_at(Z, c, {h_n, h}, Pi, A, A_rate);
  return Pi;
}

/// ∂Π/∂Z at fixed Ż and ∂Π/∂Ż at fixed Z by central differences, through the history
/// update (Material::stress_and_tangent_at).
inline std::pair<Mat9, Mat9> fd_tangents_at(const Material& m, const Vec9& Z,
                                            const MaterialPointContext& c,
                                            const std::vector<double>& h_n, double h_Z,
                                            double h_Zdot) {
  Mat9 A, A_rate;
  for (int b = 0; b < 9; ++b) {
    Vec9 Zp = Z, Zm = Z;
    Zp(b) += h_Z;
    Zm(b) -= h_Z;
    A.col(b) = (stress_at(m, Zp, c, h_n) - stress_at(m, Zm, c, h_n)) / (2 * h_Z);
    MaterialPointContext cp = c, cm = c;
    cp.Zdot(b) += h_Zdot;
    cm.Zdot(b) -= h_Zdot;
    A_rate.col(b) = (stress_at(m, Z, cp, h_n) - stress_at(m, Z, cm, h_n)) / (2 * h_Zdot);
  }
  return {A, A_rate};
}

}  // namespace fe2::testing
