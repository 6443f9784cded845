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
  out.K.setZero();
  out.r.setZero();
  if (need_G) out.G.setZero();
  out.Abar.setZero();
  out.Pbar.setZero();

  Vec9 Pi;                              // Π at the Gauss point
  Mat9 A;                               // 𝔸 at the Gauss point (toward w)
  Mat9 A_rate, A_Zbar;                  // ∂Π/∂Ż and 𝔸 toward Z̄ (rate-dependent laws)
  // Every update below is an 8-vector (over the node index a or b) times at most 3
  // coefficients: fixed-size, vectorized, no packing. Eigen's products of the 24-wide
  // shapes went through its general GEMM (packing per call): 40 % of an assembly.
  using Vec8 = Eigen::Matrix<double, 8, 1>;
  Eigen::Matrix<double, 8, 3> gt;       // gt(a, J) = ∂N_a/∂X_J at the Gauss point
  alignas(64) double Mt[3][9][8];       // Mt[k][3i+J][b] = ω Σ_L 𝔸_iJkL ∂N_b/∂X_L  (ω𝔸B̃)
  double* K = out.K.data();             // K(8i+a, 8k+b) at (8k+b)·24 + 8i + a
  alignas(64) double Hsum[3][9][8] = {};  // Hsum[k][3i+J][b] = H(iJ, 8k+b)
  for (int q = 0; q < 8; ++q) {
    const Eigen::Matrix<double, 3, 8>& g = geo.grad[q];  // g(J,a) = ∂N_a/∂X_J
    const double omega = geo.weight[q] * inv_volume;
    gt = g.transpose();

    // Z = Z̄ + B̃w: Z_iJ = Z̄_iJ + Σ_a w_ai ∂N_a/∂X_J
    Vec9 Zq;
    for (int i = 0; i < 3; ++i)
      for (int J = 0; J < 3; ++J) {
        double z = Zbar[index9(i, J)];
        for (int a = 0; a < 8; ++a) z += w_e(i, a) * gt(a, J);
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

    // Mt[k][3i+J][b] = ω Σ_L 𝔸_iJkL ∂N_b/∂X_L
    for (int k = 0; k < 3; ++k)
      for (int i = 0; i < 3; ++i)
        for (int J = 0; J < 3; ++J) {
          const Eigen::Vector3d c(omega * A(index9(i, J), index9(k, 0)),
                                  omega * A(index9(i, J), index9(k, 1)),
                                  omega * A(index9(i, J), index9(k, 2)));
          Eigen::Map<Vec8>(Mt[k][3 * i + J]).noalias() = gt.lazyProduct(c);
        }
    // K(8i+a, 8k+b) += Σ_J ∂N_a/∂X_J Mt[k][3i+J][b]. With major symmetry K is
    // symmetric: only the blocks k >= i are computed here, the rest mirrored below.
    for (int k = 0; k < 3; ++k)
      for (int i = 0; i < (need_G ? 3 : k + 1); ++i)
        for (int b = 0; b < 8; ++b) {
          const Eigen::Vector3d m(Mt[k][3 * i][b], Mt[k][3 * i + 1][b], Mt[k][3 * i + 2][b]);
          Eigen::Map<Vec8>(K + (8 * k + b) * 24 + 8 * i).noalias() += gt.lazyProduct(m);
        }
    // H(iJ, 8k+b) = Σ_q Mt[k][3i+J][b], summed in Mt's layout and transposed once below
    for (int k = 0; k < 3; ++k)
      for (int iJ = 0; iJ < 9; ++iJ)
        Eigen::Map<Vec8>(Hsum[k][iJ]) += Eigen::Map<const Vec8>(Mt[k][iJ]);
    if (need_G) {
      // G(8i+a, m) += ω Σ_J ∂N_a/∂X_J 𝔸(iJ, m)
      double* G = out.G.data();  // G(8i+a, m) at 24m + 8i + a
      for (int m = 0; m < 9; ++m)
        for (int i = 0; i < 3; ++i) {
          const Eigen::Vector3d c(omega * (*A_toward_Zbar)(index9(i, 0), m),
                                  omega * (*A_toward_Zbar)(index9(i, 1), m),
                                  omega * (*A_toward_Zbar)(index9(i, 2), m));
          Eigen::Map<Vec8>(G + 24 * m + 8 * i).noalias() += gt.lazyProduct(c);
        }
    }
    // r(8i+a) += ω Σ_J ∂N_a/∂X_J Π_iJ
    for (int i = 0; i < 3; ++i) {
      const Eigen::Vector3d p(omega * Pi[index9(i, 0)], omega * Pi[index9(i, 1)],
                              omega * Pi[index9(i, 2)]);
      out.r.segment<8>(8 * i).noalias() += gt.lazyProduct(p);
    }
    // ⟨𝔸⟩ += ω𝔸 as a flat loop: Eigen treats the 81-double Mat9 as unaligned and ran
    // it two doubles at a time with a peeling prologue (10 % of the kernel).
    const double* Aq = A_toward_Zbar->data();
    double* Abar = out.Abar.data();
    for (int t = 0; t < 81; ++t) Abar[t] += omega * Aq[t];
    out.Pbar += omega * Pi;
  }
  for (int k = 0; k < 3; ++k)
    for (int b = 0; b < 8; ++b)
      for (int i = 0; i < 3; ++i)
        for (int J = 0; J < 3; ++J) out.H(index9(i, J), 8 * k + b) = Hsum[k][3 * i + J][b];
  if (!need_G)
    for (int i = 0; i < 3; ++i)
      for (int k = i + 1; k < 3; ++k)
        out.K.block<8, 8>(8 * k, 8 * i) = out.K.block<8, 8>(8 * i, 8 * k).transpose();
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
