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
  out.H.setZero();
  if (need_G) out.G.setZero();
  out.Abar.setZero();
  out.Pbar.setZero();

  Vec9 Pi;                              // Π at the Gauss point
  Mat9 A;                               // 𝔸 at the Gauss point (toward w)
  Mat9 A_rate, A_Zbar;                  // ∂Π/∂Ż and 𝔸 toward Z̄ (rate-dependent laws)
  Mat9 Ap;                              // ω𝔸 with rows and columns reordered (i,J) -> 3i+J
  Eigen::Matrix<double, 9, 24> M;       // ω(𝔸 B̃) with rows in 3i+J order
  Eigen::Matrix<double, 8, 3> R;        // ∇Nᵀ Πᵀ: r_e(8i+a) = R(a,i)
  for (int q = 0; q < 8; ++q) {
    const Eigen::Matrix<double, 3, 8>& g = geo.grad[q];  // g(J,a) = ∂N_a/∂X_J
    const double omega = geo.weight[q] * inv_volume;

    // Z = Z̄ + B̃w: Z_iJ = Z̄_iJ + Σ_a w_ai ∂N_a/∂X_J
    Mat3 Z = as_mat3(Zbar) + w_e * g.transpose();
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
      material.stress_and_tangent_at(as_vec9(Z), context, history, Pi, A, A_rate);
      if (material.rate_dependent()) {
        A_Zbar.noalias() = A + point->Zbar_dot_coefficient * A_rate;
        if (point->dt > 0.0) A.noalias() += (1.0 / point->dt) * A_rate;
        A_toward_Zbar = &A_Zbar;
      }
    } else {
      material.stress_and_tangent(as_vec9(Z), Pi, A);
    }

    for (int i = 0; i < 3; ++i)
      for (int J = 0; J < 3; ++J)
        for (int k = 0; k < 3; ++k)
          for (int L = 0; L < 3; ++L)
            Ap(3 * i + J, 3 * k + L) = omega * A(i + 3 * J, k + 3 * L);

    // M(3i+J, 8k+b) = ω Σ_L 𝔸_iJkL ∂N_b/∂X_L
    for (int k = 0; k < 3; ++k) M.middleCols<8>(8 * k).noalias() = Ap.middleCols<3>(3 * k) * g;
    // K(8i+a, 8k+b) += Σ_J ∂N_a/∂X_J M(3i+J, 8k+b). With major symmetry K is
    // symmetric: only the blocks k >= i are computed here, the rest mirrored below.
    if (need_G) {
      for (int i = 0; i < 3; ++i)
        out.K.middleRows<8>(8 * i).noalias() += g.transpose() * M.middleRows<3>(3 * i);
    } else {
      out.K.block<8, 24>(0, 0).noalias() += g.transpose() * M.block<3, 24>(0, 0);
      out.K.block<8, 16>(8, 8).noalias() += g.transpose() * M.block<3, 16>(3, 8);
      out.K.block<8, 8>(16, 16).noalias() += g.transpose() * M.block<3, 8>(6, 16);
    }
    // H(iJ, ·) += M(3i+J, ·)
    for (int i = 0; i < 3; ++i)
      for (int J = 0; J < 3; ++J) out.H.row(i + 3 * J) += M.row(3 * i + J);
    if (need_G) {
      // G(8i+a, m) += ω Σ_J ∂N_a/∂X_J 𝔸(iJ, m)
      for (int i = 0; i < 3; ++i) {
        Eigen::Matrix<double, 3, 9> rows;
        for (int J = 0; J < 3; ++J) rows.row(J) = omega * A_toward_Zbar->row(i + 3 * J);
        out.G.middleRows<8>(8 * i).noalias() += g.transpose() * rows;
      }
    }
    const Mat3 P = as_mat3(Pi);
    R.noalias() = g.transpose() * P.transpose();
    for (int i = 0; i < 3; ++i) out.r.segment<8>(8 * i) += omega * R.col(i);
    out.Abar += omega * *A_toward_Zbar;
    out.Pbar += omega * Pi;
  }
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
