#pragma once
// The spec keys of the circulation, declared once for the reader
// (circulation_factory.cpp, standalone_spec.cpp) and the schema (circulation_schema.cpp):
// each parameter group is a table of {key, member, range, help}; the schema builds its
// keys from the tables and the default structs below, the reader reads the same
// tables by that schema.
//
// Defaults are human, in fe2heart units (Pa, mm³, s), converted from the sources'
// mmHg and mL (1 mmHg = 133.322 Pa, 1 mL = 1000 mm³):
//  - valves, atria, ventricles, closed loop: Regazzoni, Salvador, Africa, Fedele, Dedè,
//    Quarteroni 2022, "A cardiac electromechanical model coupled with a lumped-parameter
//    model for closed-loop blood circulation", J Comput Phys 457:111083 (arXiv 2011.15040),
//    the parameters of the authors' reference implementation; timings are their
//    fractions of the period (atria: onset 0.8 T, T_C = T_R = 0.17 T; ventricles: onset
//    0, T_C = 0.34 T, T_R = 0.17 T) at T = 0.8 s;
//  - the 3-element Windkessel: Westerhof, Lankhaar, Westerhof 2009, "The arterial
//    Windkessel", Med Biol Eng Comput 47:131–141 (human aorta: Z_c ≈ 0.05 mmHg·s/mL,
//    C ≈ 1.5 mL/mmHg) with Regazzoni 2022's systemic arterial resistance R_p = 0.8
//    mmHg·s/mL (R_p C = 1.2 s); the pulmonary one from Regazzoni 2022's pulmonary
//    resistances and compliance.
#include "common/circulation/TimeVaryingElastance.h"
#include "common/circulation/smooth_valve.h"
#include "common/spec/SpecNode.h"

#include <string>
#include <vector>

namespace fe2::circulation_keys {

inline constexpr double kMmHg = 133.322387415;  ///< Pa
inline constexpr double kMl = 1000.0;           ///< mm³
/// mmHg·s/mL (also mmHg/mL, mmHg·s²/mL) → Pa·s/mm³ (Pa/mm³, Pa·s²/mm³).
inline constexpr double kR = kMmHg / kMl;
/// mL/mmHg → mm³/Pa.
inline constexpr double kC = kMl / kMmHg;
inline constexpr double kPeriod = 0.8;          ///< s (75 beats per minute)

/// A number key of a parameter struct P.
template <class P>
struct Key {
  const char* key;
  double P::*member;
  Range range;
  const char* help;
};

/// Reads every key of `keys` (each default from the node's schema, which
/// circulation_schema.cpp builds from the default structs below).
template <class P>
P read_keys(SpecNode& node, const std::vector<Key<P>>& keys) {
  P p{};
  for (const auto& k : keys) p.*k.member = node.number(k.key);
  return p;
}

// --- Top level.
inline const char* const kCirculationHelp =
    "0D blood circulation coupled to the cavities: windkessel (per cavity: preload, inflow "
    "valve, outflow valve, 3-element Windkessel) or closed_loop (Regazzoni et al. 2022: "
    "atria, valves, systemic and pulmonary arteries and veins)";
inline const std::vector<std::string>& kinds() {
  static const std::vector<std::string> k = {"windkessel", "closed_loop"};
  return k;
}
inline const char* const kKindHelp =
    "windkessel: each cavity fills from a preload and ejects into its own Windkessel; "
    "closed_loop: one closed circuit that conserves the blood volume";
inline const char* const kPeriodHelp =
    "heart period T (s): every time-varying elastance (atria, elastance ventricles) repeats "
    "with it";
inline const char* const kCavitiesHelp =
    "the cavities coupled to the circulation: lv (required) and rv (optional), each with its "
    "own keys";
inline const char* const kLvHelp = "left ventricle";
inline const char* const kRvHelp = "right ventricle (optional)";

// --- Valves (smooth_valve.h).
inline const std::vector<Key<ValveParameters>>& valve_keys() {
  using P = ValveParameters;
  static const std::vector<Key<P>> k = {
      {"R_open", &P::R_open, Range::positive(),
       "resistance of the open valve (Pa s/mm^3); Regazzoni 2022: R_min = 0.0075 mmHg s/mL"},
      {"R_closed", &P::R_closed, Range::positive(),
       "resistance of the closed valve (Pa s/mm^3), above R_open; Regazzoni 2022: R_max = "
       "75006.2 mmHg s/mL"},
      {"width", &P::width, Range::positive(),
       "pressure width w over which the valve switches (Pa): Q = dp/R_closed + (1/R_open - "
       "1/R_closed) w ln(1 + exp(dp/w))"},
  };
  return k;
}
/// Regazzoni's R_min = 0.0075 and R_max = 75006.2 mmHg·s/mL are 1e-3 and 1e4 Pa·s/mm³
/// (to 1e-4 relative): the round values are the defaults.
inline ValveParameters default_valve() { return {1e-3, 1e4, 10.0}; }
inline const char* const kInflowValveHelp = "inflow valve (mitral for lv, tricuspid for rv)";
inline const char* const kOutflowValveHelp = "outflow valve (aortic for lv, pulmonary for rv)";

// --- Time-varying elastances (TimeVaryingElastance.h): atria, ventricles.
inline const std::vector<Key<ElastanceParameters>>& elastance_keys() {
  using P = ElastanceParameters;
  static const std::vector<Key<P>> k = {
      {"E_min", &P::E_min, Range::positive(), "passive (diastolic) elastance E_min (Pa/mm^3)"},
      {"E_max", &P::E_max, Range::positive(),
       "peak elastance E_max (Pa/mm^3), >= E_min: E(t) = E_min + (E_max - E_min) e(t)"},
      {"V0", &P::V0, Range::non_negative(), "volume at zero pressure V0 (mm^3): p = E(t)(V - V0)"},
      {"V_init", &P::V_init, Range::non_negative(), "initial volume (mm^3)"},
      {"onset", &P::onset, Range::non_negative(),
       "onset of contraction within each period (s), below the period"},
      {"contraction", &P::contraction, Range::positive(),
       "contraction time T_C (s): e rises as (1 - cos(pi s/T_C))/2"},
      {"relaxation", &P::relaxation, Range::positive(),
       "relaxation time T_R (s): e falls as (1 + cos(pi (s - T_C)/T_R))/2; T_C + T_R <= period"},
  };
  return k;
}
/// Regazzoni 2022 (EB = E_min, EA = E_max − E_min); timings at T = 0.8 s (onset 0.8 T,
/// T_C = T_R = 0.17 T for the atria; 0, 0.34 T, 0.17 T for the ventricles).
inline ElastanceParameters left_atrium() {
  return {0.09 * kR, 0.16 * kR, 4.0 * kMl, 65.0 * kMl, 0.64, 0.136, 0.136};
}
inline ElastanceParameters right_atrium() {
  return {0.07 * kR, 0.13 * kR, 4.0 * kMl, 65.0 * kMl, 0.64, 0.136, 0.136};
}
inline ElastanceParameters left_ventricle() {
  return {0.08 * kR, 2.83 * kR, 5.0 * kMl, 120.0 * kMl, 0.0, 0.272, 0.136};
}
inline ElastanceParameters right_ventricle() {
  return {0.05 * kR, 0.60 * kR, 10.0 * kMl, 145.0 * kMl, 0.0, 0.272, 0.136};
}

// --- Windkessel kind: preload and the 3-element Windkessel of one cavity.
struct PreloadParameters {
  double pressure = 0.0;     ///< constant preload (Pa)
  double p_venous = 0.0;     ///< atrium: venous pressure feeding it (Pa)
  double R_venous = 0.0;     ///< atrium: venous resistance (Pa·s/mm³)
};
inline const std::vector<std::string>& preload_kinds() {
  static const std::vector<std::string> k = {"pressure", "atrium"};
  return k;
}
inline const char* const kPreloadHelp =
    "what fills the cavity through its inflow valve: a constant pressure, or an atrium "
    "(time-varying elastance) fed from a constant venous pressure through a resistance";
inline const char* const kPreloadKindHelp =
    "pressure: constant filling pressure; atrium: a contracting atrium (atrial kick)";
inline const Key<PreloadParameters> kPreloadPressure = {
    "pressure", &PreloadParameters::pressure, Range::any(),
    "filling pressure (Pa); default lv: left atrial 10 mmHg, rv: right atrial 4 mmHg"};
inline const std::vector<Key<PreloadParameters>>& atrium_feed_keys() {
  using P = PreloadParameters;
  static const std::vector<Key<P>> k = {
      {"p_venous", &P::p_venous, Range::any(),
       "venous pressure feeding the atrium (Pa); default lv: pulmonary veins 10 mmHg, rv: "
       "systemic veins 4 mmHg"},
      {"R_venous", &P::R_venous, Range::positive(),
       "venous resistance into the atrium (Pa s/mm^3); Regazzoni 2022 R_VEN: lv 0.1625, rv "
       "0.26 mmHg s/mL"},
  };
  return k;
}
inline PreloadParameters lv_preload() { return {10.0 * kMmHg, 10.0 * kMmHg, 0.1625 * kR}; }
inline PreloadParameters rv_preload() { return {4.0 * kMmHg, 4.0 * kMmHg, 0.26 * kR}; }

struct WindkesselParameters {
  double Zc = 0.0;        ///< characteristic impedance (Pa·s/mm³)
  double Rp = 0.0;        ///< peripheral resistance (Pa·s/mm³)
  double C = 0.0;         ///< compliance (mm³/Pa)
  double p_distal = 0.0;  ///< distal (venous) pressure p_d (Pa)
  double p0 = 0.0;        ///< initial pressure of the compliance (Pa)
};
inline const char* const kWindkesselHelp =
    "3-element Windkessel after the outflow valve: Q = (p_out - p_C)/Z_c, C dp_C/dt = Q - "
    "(p_C - p_distal)/R_p";
inline const std::vector<Key<WindkesselParameters>>& windkessel_keys() {
  using P = WindkesselParameters;
  static const std::vector<Key<P>> k = {
      {"Zc", &P::Zc, Range::positive(),
       "characteristic impedance Z_c (Pa s/mm^3); default lv 0.05 mmHg s/mL (Westerhof 2009), "
       "rv 0.01 mmHg s/mL"},
      {"Rp", &P::Rp, Range::positive(),
       "peripheral resistance R_p (Pa s/mm^3); default lv 0.8 mmHg s/mL (Regazzoni 2022 "
       "R_AR systemic), rv 0.15 mmHg s/mL (Regazzoni 2022 pulmonary R_AR + R_VEN, less Z_c)"},
      {"C", &P::C, Range::positive(),
       "arterial compliance C (mm^3/Pa); default lv 1.5 mL/mmHg (Westerhof 2009), rv 10 "
       "mL/mmHg (Regazzoni 2022 C_AR pulmonary)"},
      {"p_distal", &P::p_distal, Range::any(),
       "distal (venous) pressure p_d the periphery drains to (Pa); default lv 5, rv 8 mmHg"},
      {"p0", &P::p0, Range::any(), "initial pressure of the compliance (Pa); default lv 80, rv 15 mmHg"},
  };
  return k;
}
inline WindkesselParameters lv_windkessel() {
  return {0.05 * kR, 0.8 * kR, 1.5 * kC, 5.0 * kMmHg, 80.0 * kMmHg};
}
inline WindkesselParameters rv_windkessel() {
  return {0.01 * kR, 0.15 * kR, 10.0 * kC, 8.0 * kMmHg, 15.0 * kMmHg};
}

// --- Closed loop (Regazzoni 2022).
struct VesselParameters {
  double R_ar = 0.0, C_ar = 0.0, L_ar = 0.0;     ///< arteries
  double R_ven = 0.0, C_ven = 0.0, L_ven = 0.0;  ///< veins
  double p_ar_init = 0.0, p_ven_init = 0.0;      ///< initial pressures (Pa)
};
inline const std::vector<Key<VesselParameters>>& vessel_keys() {
  using P = VesselParameters;
  static const std::vector<Key<P>> k = {
      {"R_ar", &P::R_ar, Range::positive(), "arterial resistance (Pa s/mm^3)"},
      {"C_ar", &P::C_ar, Range::positive(), "arterial compliance (mm^3/Pa)"},
      {"L_ar", &P::L_ar, Range::non_negative(),
       "arterial inertance (Pa s^2/mm^3); 0: a plain resistance"},
      {"R_ven", &P::R_ven, Range::positive(), "venous resistance (Pa s/mm^3)"},
      {"C_ven", &P::C_ven, Range::positive(), "venous compliance (mm^3/Pa)"},
      {"L_ven", &P::L_ven, Range::non_negative(),
       "venous inertance (Pa s^2/mm^3); 0: a plain resistance"},
      {"p_ar_init", &P::p_ar_init, Range::any(), "initial arterial pressure (Pa)"},
      {"p_ven_init", &P::p_ven_init, Range::any(), "initial venous pressure (Pa)"},
  };
  return k;
}
/// Regazzoni 2022: systemic R_AR 0.8, C_AR 1.2, L_AR 5e-3, R_VEN 0.26, C_VEN 60, L_VEN
/// 5e-4; initial p_AR 80, p_VEN 30 mmHg.
inline VesselParameters systemic() {
  return {0.8 * kR, 1.2 * kC, 5e-3 * kR, 0.26 * kR, 60.0 * kC, 5e-4 * kR, 80.0 * kMmHg, 30.0 * kMmHg};
}
/// Regazzoni 2022: pulmonary R_AR 0.1625, C_AR 10, L_AR 5e-4, R_VEN 0.1625, C_VEN 16,
/// L_VEN 5e-4; initial p_AR 35, p_VEN 24 mmHg.
inline VesselParameters pulmonary() {
  return {0.1625 * kR, 10.0 * kC, 5e-4 * kR, 0.1625 * kR, 16.0 * kC, 5e-4 * kR, 35.0 * kMmHg, 24.0 * kMmHg};
}
inline const char* const kSystemicHelp =
    "systemic arteries and veins (RLC compartments); defaults Regazzoni 2022: R_ar 0.8, "
    "R_ven 0.26 mmHg s/mL, C_ar 1.2, C_ven 60 mL/mmHg, L_ar 5e-3, L_ven 5e-4 mmHg s^2/mL, "
    "p_ar 80, p_ven 30 mmHg";
inline const char* const kPulmonaryHelp =
    "pulmonary arteries and veins (RLC compartments); defaults Regazzoni 2022: R_ar = R_ven "
    "0.1625 mmHg s/mL, C_ar 10, C_ven 16 mL/mmHg, L 5e-4 mmHg s^2/mL, p_ar 35, p_ven 24 mmHg";
inline const char* const kLeftAtriumHelp =
    "left atrium, a time-varying elastance; defaults Regazzoni 2022: E_min 0.09, E_max 0.16 "
    "mmHg/mL, V0 4 mL, V_init 65 mL, onset 0.8 T, T_C = T_R = 0.17 T";
inline const char* const kRightAtriumHelp =
    "right atrium, a time-varying elastance; defaults Regazzoni 2022: E_min 0.07, E_max 0.13 "
    "mmHg/mL, V0 4 mL, V_init 65 mL, onset 0.8 T, T_C = T_R = 0.17 T";
inline const char* const kInternalRvHelp =
    "the right ventricle as a time-varying elastance inside the loop, used when cavities has "
    "no rv; defaults Regazzoni 2022: E_min 0.05, E_max 0.60 mmHg/mL, V0 10 mL, V_init 145 mL, "
    "onset 0, T_C 0.34 T, T_R 0.17 T";
inline const char* const kLoopCavityHelp =
    "a cavity of the loop with its valves (lv: mitral and aortic; rv: tricuspid and pulmonary)";

// --- Standalone runs (`fe2heart circulation`, standalone_spec.h).
inline const char* const kVentriclesHelp =
    "time-varying elastance ventricles standing in for the wall, one per cavity of the "
    "circulation";
inline const char* const kLvElastanceHelp =
    "left ventricle; defaults Regazzoni 2022: E_min 0.08, E_max 2.83 mmHg/mL, V0 5 mL, "
    "V_init 120 mL, onset 0, T_C 0.34 T, T_R 0.17 T";
inline const char* const kRvElastanceHelp =
    "right ventricle; defaults Regazzoni 2022: E_min 0.05, E_max 0.60 mmHg/mL, V0 10 mL, "
    "V_init 145 mL, onset 0, T_C 0.34 T, T_R 0.17 T";

}  // namespace fe2::circulation_keys
