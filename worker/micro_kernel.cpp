#include "worker/micro_kernel.h"

namespace fe2 {

namespace {

/// The kernel, compiled once per path so the stateless one (kContext = false) is the
/// plain loop without a branch per Gauss point.
template <bool kContext>
void hex_contribution_impl(const HexGeometry& geo, double inv_volume,
                           const Eigen::Matrix<double, 3, 8>& w_e, const Vec9& Zbar,
                           const Material& material, bool need_G, HexContribution& out,
                           const HexPointContext* point) {
  // Two phases. Per Gauss point q: the law, and Mt_q = ω𝔸B̃ (what K, H and the rest
  // are built from). Then K, one 8x8 block (i, k) at a time, summed over all 8 points
  // in registers: K(8i+a, 8k+b) = Σ_q Σ_J ∂N_a/∂X_J Mt_q[k][3i+J][b]. Each column
  // segment of K is stored once, not read and written at every point, and every update
  // is an 8-vector (over the node index) times a broadcast scalar.
  using Vec8 = Eigen::Matrix<double, 8, 1>;
  alignas(64) double gT[8][3][8];       // gT[q][J][a] = ∂N_a/∂X_J at point q
  alignas(64) double Mt[8][3][9][8];    // Mt[q][k][3i+J][b] = ω Σ_L 𝔸_iJkL ∂N_b/∂X_L
  out.r.setZero();
  if (need_G) out.G.setZero();
  out.Abar.setZero();
  out.Pbar.setZero();

  Vec9 Pi;                              // Π at the Gauss point
  Mat9 A;                               // 𝔸 at the Gauss point (toward w)
  Mat9 A_rate, A_Zbar;                  // ∂Π/∂Ż and 𝔸 toward Z̄ (rate-dependent laws)
  for (int q = 0; q < 8; ++q) {
    const Eigen::Matrix<double, 3, 8>& g = geo.grad[q];  // g(J,a) = ∂N_a/∂X_J
    const double omega = geo.weight[q] * inv_volume;
    for (int J = 0; J < 3; ++J)
      for (int a = 0; a < 8; ++a) gT[q][J][a] = g(J, a);

    // Z = Z̄ + B̃w: Z_iJ = Z̄_iJ + Σ_a w_ai ∂N_a/∂X_J
    Vec9 Zq;
    for (int i = 0; i < 3; ++i)
      for (int J = 0; J < 3; ++J) {
        double z = Zbar[index9(i, J)];
        for (int a = 0; a < 8; ++a) z += w_e(i, a) * gT[q][J][a];
        Zq[index9(i, J)] = z;
      }
    // 𝔸 toward w (K, H) and toward Z̄ (G, Ā): equal unless Π depends on Ż, whose
    // coefficients differ, ∂Ż/∂w = B̃/Δt (backward Euler) and ∂Ż/∂Z̄ = c of the macro
    // integrator: 𝔸_w = A + A_rate/Δt, 𝔸_Z̄ = A + c·A_rate.
    const Mat9* A_toward_Zbar = &A;
    if constexpr (kContext) {
      MaterialPointContext context{point->time, point->dt, Vec9::Zero(), point->activation_time};
      // Ż = Ż̄ + B̃ẇ: Ż_iJ = Ż̄_iJ + Σ_a ẇ_ai ∂N_a/∂X_J
      Eigen::Map<Mat3>(context.Zdot.data()) = as_mat3(point->Zbar_dot) + point->w_dot_e * g.transpose();
      const size_t h = static_cast<size_t>(material.history_size());
      PointHistory history;
      if (h > 0)
        history = {{point->history_committed + q * h, h}, {point->history + q * h, h}};
      material.stress_and_tangent_at(Zq, context, history, Pi, A, A_rate);
      if (material.rate_dependent()) {
        A_Zbar.noalias() = A + point->Zbar_dot_coefficient * A_rate;
        if (point->dt > 0.0) A.noalias() += (1.0 / point->dt) * A_rate;
        A_toward_Zbar = &A_Zbar;
      }
    } else {
      material.stress_and_tangent(Zq, Pi, A);
    }

    // ω∂N/∂X_J as three 8-vectors: every product below is one of them times a scalar
    const Vec8 wg0 = omega * Eigen::Map<const Vec8>(gT[q][0]);
    const Vec8 wg1 = omega * Eigen::Map<const Vec8>(gT[q][1]);
    const Vec8 wg2 = omega * Eigen::Map<const Vec8>(gT[q][2]);
    // Mt[q][k][3i+J][b] = Σ_L ω𝔸(iJ, kL) ∂N_b/∂X_L
    const double* Ad = A.data();  // 𝔸(m, n) at 9n + m
    for (int k = 0; k < 3; ++k)
      for (int i = 0; i < 3; ++i)
        for (int J = 0; J < 3; ++J) {
          const int m = index9(i, J);
          Eigen::Map<Vec8>(Mt[q][k][3 * i + J]).noalias() = wg0 * Ad[9 * index9(k, 0) + m] +
                                                            wg1 * Ad[9 * index9(k, 1) + m] +
                                                            wg2 * Ad[9 * index9(k, 2) + m];
        }
    if (need_G) {
      // G(8i+a, m) += ω Σ_J ∂N_a/∂X_J 𝔸(iJ, m)
      double* G = out.G.data();  // G(8i+a, m) at 24m + 8i + a
      const double* Az = A_toward_Zbar->data();
      for (int m = 0; m < 9; ++m)
        for (int i = 0; i < 3; ++i)
          Eigen::Map<Vec8>(G + 24 * m + 8 * i) += wg0 * Az[9 * m + index9(i, 0)] +
                                                  wg1 * Az[9 * m + index9(i, 1)] +
                                                  wg2 * Az[9 * m + index9(i, 2)];
    }
    // r(8i+a) += ω Σ_J ∂N_a/∂X_J Π_iJ
    for (int i = 0; i < 3; ++i)
      out.r.segment<8>(8 * i) += wg0 * Pi[index9(i, 0)] + wg1 * Pi[index9(i, 1)] +
                                 wg2 * Pi[index9(i, 2)];
    // ⟨𝔸⟩ += ω𝔸 as a flat loop: Eigen treats the 81-double Mat9 as unaligned and ran
    // it two doubles at a time with a peeling prologue.
    const double* Aq = A_toward_Zbar->data();
    double* Abar = out.Abar.data();
    for (int t = 0; t < 81; ++t) Abar[t] += omega * Aq[t];
    out.Pbar += omega * Pi;
  }

  // K(8i+a, 8k+b) = Σ_q Σ_J ∂N_a/∂X_J Mt[q][k][3i+J][b], eight accumulators (b) per
  // block. With major symmetry K is symmetric: only the blocks k >= i, mirrored below.
  double* K = out.K.data();  // K(8i+a, 8k+b) at (8k+b)·24 + 8i + a
  for (int k = 0; k < 3; ++k)
    for (int i = 0; i < (need_G ? 3 : k + 1); ++i) {
      Vec8 acc[8];
      for (int b = 0; b < 8; ++b) acc[b].setZero();
      for (int q = 0; q < 8; ++q)
        for (int J = 0; J < 3; ++J) {
          const Vec8 gJ = Eigen::Map<const Vec8>(gT[q][J]);
          const double* m = Mt[q][k][3 * i + J];
          for (int b = 0; b < 8; ++b) acc[b] += gJ * m[b];
        }
      for (int b = 0; b < 8; ++b) Eigen::Map<Vec8>(K + (8 * k + b) * 24 + 8 * i) = acc[b];
    }
  if (!need_G)
    for (int i = 0; i < 3; ++i)
      for (int k = i + 1; k < 3; ++k)
        out.K.block<8, 8>(8 * k, 8 * i) = out.K.block<8, 8>(8 * i, 8 * k).transpose();
  // H(iJ, 8k+b) = Σ_q Mt[q][k][3i+J][b]
  for (int k = 0; k < 3; ++k)
    for (int iJ = 0; iJ < 9; ++iJ) {
      Vec8 h = Eigen::Map<const Vec8>(Mt[0][k][iJ]);
      for (int q = 1; q < 8; ++q) h += Eigen::Map<const Vec8>(Mt[q][k][iJ]);
      const int i = iJ / 3, J = iJ % 3;
      for (int b = 0; b < 8; ++b) out.H(index9(i, J), 8 * k + b) = h[b];
    }
}

}  // namespace

void hex_contribution(const HexGeometry& geo, double inv_volume,
                      const Eigen::Matrix<double, 3, 8>& w_e, const Vec9& Zbar,
                      const Material& material, bool need_G, HexContribution& out,
                      const HexPointContext* point) {
  if (point)
    hex_contribution_impl<true>(geo, inv_volume, w_e, Zbar, material, need_G, out, point);
  else
    hex_contribution_impl<false>(geo, inv_volume, w_e, Zbar, material, need_G, out, nullptr);
}

}  // namespace fe2
