#pragma once
// Human cardiac cross-bridge model of Land et al. 2017, "A model of cardiac contraction
// based on novel measurements of tension development in human cardiomyocytes",
// J Mol Cell Cardiol 106:68–83 (equations and Appendix B parameters). States, in the
// order of the state span:
//   0 CaTRPN  fraction of troponin C with Ca²⁺ bound
//   1 B       fraction blocked by tropomyosin (TmB)
//   2 XS      strongly bound (post-powerstroke) cross-bridges
//   3 XW      weakly bound (pre-powerstroke) cross-bridges
//   4 ζs, 5 ζw  their mean distortions
// With λ_m = min(λ, 1.2), XU = 1 − B − XS − XW and the published clamps (CaTRPN, XS, XW
// read as max(·, 0); the unblocking factor CaTRPN^{−n_tm/2} capped at 100):
//   Ca50   = Ca50_ref + β1 (λ_m − 1)
//   CaTRPN' = k_TRPN ((Ca/Ca50)^{n_TRPN} (1 − CaTRPN) − CaTRPN)
//   B'     = k_b min(100, CaTRPN^{−n_tm/2}) XU − k_u CaTRPN^{n_tm/2} B
//   XW'    = k_uw XU − k_wu XW − k_ws XW − γ_wu XW,     γ_wu = γ_w |ζw|
//   XS'    = k_ws XW − k_su XS − γ_su XS,               γ_su = γ_s (ζs if ζs > 0; −ζs − 1 if ζs < −1; else 0)
//   ζs'    = A λ̇ − c_s ζs,   ζw' = A λ̇ − c_w ζw
//   T_a    = h(λ) (T_ref / r_s) ((ζs + 1) XS + ζw XW),
//   h(λ)   = max(0, 1 + β0 (λ_m + min(λ_m, 0.87) − 1.87))
// with the derived rates k_wu = k_uw (1/r_w − 1) − k_ws, k_su = k_ws r_w (1/r_s − 1),
// A = A_eff r_s / ((1 − r_s) r_w + r_s), c_w = φ k_uw (1 − r_w)/r_w,
// c_s = φ k_ws r_w (1 − r_s)/r_s, k_b = k_u TRPN_50^{n_tm} / ((1 − r_s)(1 − r_w)).
// Ca50 shifts additively with λ as in the reference implementations (ToR-ORd–Land of
// Margara et al. 2021, openCARP's Land17). The paper's rates are per ms; here per s.
#include "common/cellmodels/CalciumTransient.h"
#include "common/cellmodels/CellModel.h"

#include <array>
#include <string>

namespace fe2 {

/// Land 2017 parameters in fe2heart units (Pa, µM, 1/s).
struct Land2017Parameters {
  double T_ref = 120e3;    ///< reference tension (Pa)
  double ca50_ref = 0.805; ///< [Ca]T50 at λ = 1 (µM)
  double TRPN_50 = 0.35;   ///< CaTRPN at half tropomyosin unblocking
  double n_TRPN = 2.0;     ///< troponin Hill coefficient
  double k_TRPN = 100.0;   ///< troponin rate (1/s)
  double n_tm = 5.0;       ///< tropomyosin Hill coefficient
  double k_u = 1000.0;     ///< unblocking rate (1/s)
  double r_s = 0.25;       ///< steady-state duty ratio
  double r_w = 0.5;        ///< steady-state weak fraction
  double k_uw = 182.0;     ///< unbound → weak (1/s)
  double k_ws = 12.0;      ///< weak → strong (1/s)
  double gamma_s = 8.5;    ///< distortion-dependent detachment, strong (1/s)
  double gamma_w = 615.0;  ///< distortion-dependent detachment, weak (1/s)
  double phi = 2.23;       ///< distortion decay scaling
  double A_eff = 25.0;     ///< effective distortion per unit stretch
  double beta_0 = 2.3;     ///< length dependence of tension
  double beta_1 = -2.4;    ///< length dependence of calcium sensitivity (µM)

  /// Appendix B's whole-organ column: intact human myocardium at 37 °C, the set used
  /// when the model is coupled to ORd/ToR-ORd (T_ref = 120 kPa).
  static Land2017Parameters intact();
  /// Appendix B's skinned column: skinned human myocytes (ca50_ref 2.5 µM, n_tm 2.2,
  /// k_uw 26 /s, k_ws 4 /s, T_ref 40.5 kPa); the other values are shared.
  static Land2017Parameters skinned();
};

class Land2017 final : public CellModel {
 public:
  static constexpr const char* kName = "land2017";
  static constexpr int kStates = 6;

  /// `set_name` names the parameter set ("intact", "skinned") and `overridden` lists the
  /// keys the spec changed; both only for description().
  Land2017(const Land2017Parameters& p, const CalciumParameters& calcium, double max_substep,
           std::string set_name = "intact", std::string overridden = "");

  std::string name() const override { return kName; }
  std::string description() const override;
  int state_size() const override { return kStates; }
  void rest_state(std::span<double> state) const override;
  ActiveTension advance(const CellStep& step, std::span<const double> committed,
                        std::span<double> current) const override;
  bool rate_dependent() const override { return true; }

  const Land2017Parameters& parameters() const { return p_; }
  const CalciumTransient& calcium() const { return calcium_; }

 private:
  /// The state's time derivative (T = double or Dual).
  template <class T>
  void rhs(double ca, const T& lambda, const T& lambda_dot, const std::array<T, kStates>& y,
           std::array<T, kStates>& dy) const;
  /// T_a at stretch λ from a state.
  template <class T>
  T tension(const T& lambda, const std::array<T, kStates>& y) const;

  Land2017Parameters p_;
  CalciumTransient calcium_;
  double max_substep_;
  std::string set_name_, overridden_;
  // Derived rates (1/s) and constants, once.
  double k_wu_, k_su_, A_, c_w_, c_s_, k_b_;
};

}  // namespace fe2
