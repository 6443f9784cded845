#pragma once
// Active stress along the fibres, in the material frame (axis 1 = f₀):
//
//   S_a = T_a [(1 − n_t) f₀⊗f₀ + n_t I],     P_a = F S_a,
//
// i.e. T_a f₀⊗f₀ plus the transverse fraction n_t T_a (I − f₀⊗f₀). T_a comes from a
// cell model (common/cellmodels/CellModel.h) as a function of the fibre stretch
// λ = |F f₀| and its rate λ̇ = (F f₀)·(Ḟ f₀)/λ; the two tangents carry T_a's
// sensitivities through λ(F) and λ̇(F, Ḟ).
#include "common/cellmodels/CellModel.h"
#include "common/tensor9.h"

namespace fe2 {

/// λ and λ̇ of the fibre f₀ = e₁ from F and Ḟ.
struct FibreStretch {
  double lambda = 1.0, lambda_dot = 0.0;
};
FibreStretch fibre_stretch(const Mat3& F, const Mat3& Fdot);

/// Adds P_a to Pi, ∂P_a/∂Z to A and ∂P_a/∂Ż to A_rate.
void add_active_stress(const Mat3& F, const Mat3& Fdot, const ActiveTension& T, double n_t,
                       Vec9& Pi, Mat9& A, Mat9& A_rate);

}  // namespace fe2
