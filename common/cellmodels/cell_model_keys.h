#pragma once
// The spec keys of the cell models, declared once for the reader
// (cell_model_factory.cpp) and the schema (cell_model_schema.cpp): names, ranges, help
// texts and defaults, so the two cannot drift apart.
#include "common/cellmodels/BestelClementSorine.h"
#include "common/cellmodels/CalciumTransient.h"
#include "common/cellmodels/Land2017.h"
#include "common/spec/SpecNode.h"

#include <spdlog/fmt/fmt.h>

#include <string>
#include <vector>

namespace fe2::cell_keys {

inline const std::vector<std::string>& model_names() {
  static const std::vector<std::string> names = {Land2017::kName, BestelClementSorine::kName,
                                                 "constant", "table"};
  return names;
}
inline const char* const kModelHelp =
    "cell model giving the active fibre tension T_a: land2017 (Land et al. 2017 human "
    "cross-bridges), bestel_clement_sorine (phenomenological), constant or table (prescribed)";

// Calcium transient (CalciumTransient.h), µM and s.
inline const char* const kCalciumHelp =
    "Ca2+ transient per point: bi-exponential template (Rice et al. 2008) started at the "
    "point's activation time";
inline const char* const kRestHelp = "diastolic [Ca2+]i (µM)";
inline const char* const kPeakHelp = "systolic peak [Ca2+]i (µM), above rest";
inline const char* const kRiseHelp = "rise time constant tau_rise (s), below decay";
inline const char* const kDecayHelp = "decay time constant tau_decay (s)";
inline const char* const kPeriodHelp = "beat period (s): beats repeat every period; 0: one beat";

// Read by the material that owns the cell model (common/materials/material_factory.cpp).
inline const char* const kTransverseHelp =
    "transverse fraction n_t of the active stress: S_a = T_a [(1 - n_t) f0 f0 + n_t I]";

inline const char* const kMaxSubstepHelp =
    "longest RK4 substep of the cell ODE inside one time step (s); a step is split into "
    "ceil(dt / max_substep) equal substeps";
inline constexpr double kMaxSubstep = 1e-4;

// Land 2017 (Land2017.h). Each parameter may override the chosen set's value.
inline const char* const kParameterSetHelp =
    "Land 2017 Appendix B parameter set: intact (human intact myocardium, 37 °C, T_ref = "
    "120 kPa, as coupled to ORd/ToR-ORd) or skinned (skinned human myocytes, T_ref = 40.5 kPa)";
inline const std::vector<std::string>& parameter_sets() {
  static const std::vector<std::string> s = {"intact", "skinned"};
  return s;
}

struct LandKey {
  const char* key;
  double Land2017Parameters::*member;
  Range range;
  const char* what;  ///< symbol and unit
};

inline const std::vector<LandKey>& land_keys() {
  using P = Land2017Parameters;
  const Range pos = Range::positive(), nonneg = Range::non_negative(), unit{0.0, 1.0, true, true};
  static const std::vector<LandKey> keys = {
      {"T_ref", &P::T_ref, pos, "reference tension T_ref (Pa)"},
      {"ca50_ref", &P::ca50_ref, pos, "[Ca]T50 at lambda = 1 (µM)"},
      {"TRPN_50", &P::TRPN_50, unit, "CaTRPN at half tropomyosin unblocking"},
      {"n_TRPN", &P::n_TRPN, pos, "troponin Hill coefficient"},
      {"k_TRPN", &P::k_TRPN, pos, "troponin Ca2+ binding rate (1/s; the paper's 0.1/ms = 100/s)"},
      {"n_tm", &P::n_tm, pos, "tropomyosin Hill coefficient"},
      {"k_u", &P::k_u, pos, "tropomyosin unblocking rate (1/s)"},
      {"r_s", &P::r_s, unit, "steady-state duty ratio"},
      {"r_w", &P::r_w, unit, "steady-state weakly bound fraction"},
      {"k_uw", &P::k_uw, pos, "unbound to weak rate (1/s)"},
      {"k_ws", &P::k_ws, pos, "weak to strong rate (1/s)"},
      {"gamma_s", &P::gamma_s, nonneg, "distortion-dependent detachment of strong bridges (1/s)"},
      {"gamma_w", &P::gamma_w, nonneg, "distortion-dependent detachment of weak bridges (1/s)"},
      {"phi", &P::phi, nonneg, "distortion decay scaling phi"},
      {"A_eff", &P::A_eff, nonneg, "effective distortion per unit stretch A_eff"},
      {"beta_0", &P::beta_0, nonneg, "length dependence of tension beta_0"},
      {"beta_1", &P::beta_1, Range::any(), "length dependence of calcium sensitivity beta_1 (µM)"},
  };
  return keys;
}

/// "reference tension T_ref (Pa); default: intact 120000, skinned 40500"
inline std::string land_help(const LandKey& k) {
  return fmt::format("{}; default: intact {}, skinned {}", k.what,
                     Land2017Parameters::intact().*k.member,
                     Land2017Parameters::skinned().*k.member);
}

// Bestel–Clément–Sorine (BestelClementSorine.h).
inline const char* const kSigma0Help = "contractility sigma_0 (Pa)";
inline const char* const kAlphaMaxHelp = "activation rate alpha_max (1/s), > 0";
inline const char* const kAlphaMinHelp = "relaxation rate alpha_min (1/s), < 0";
inline const Range kNegative{-std::numeric_limits<double>::infinity(), 0.0, false, true};

// Prescribed tension (PrescribedTension.h).
inline const char* const kTaHelp = "constant active fibre tension T_a (Pa)";
inline const char* const kTableType = "array of [s, T_a] pairs";
inline const char* const kTableHelp =
    "T_a (Pa) piecewise linear in s = t - t_act (s): pairs [[s0, T0], [s1, T1], ...], s "
    "strictly increasing, T_a >= 0, held at the ends";

}  // namespace fe2::cell_keys
