#pragma once
// Myocardial viscosity as a Kelvin–Voigt term on the Green–Lagrange strain rate (the
// paper's Π(Z, Ż), §II):
//
//   S_v = η Ė,   Ė = ½(FᵀḞ + ḞᵀF),   P_v = F S_v,
//
// with the tangents
//   ∂P_v/∂F_kL = δ_ik S_v,LJ + η/2 (F_iL Ḟ_kJ + (FḞᵀ)_ik δ_JL)
//   ∂P_v/∂Ḟ_kL = η/2 (F_iL F_kJ + (FFᵀ)_ik δ_JL)
// The first is unsymmetric (a point with viscosity takes the LU path).
#include "common/tensor9.h"

namespace fe2 {

/// Adds P_v to Pi, ∂P_v/∂Z to A and ∂P_v/∂Ż to A_rate; η in Pa·s.
void add_kelvin_voigt_stress(const Mat3& F, const Mat3& Fdot, double eta, Vec9& Pi, Mat9& A,
                             Mat9& A_rate);

}  // namespace fe2
