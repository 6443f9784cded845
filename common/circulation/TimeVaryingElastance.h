#pragma once
// A chamber as a time-varying elastance (Regazzoni et al. 2022, J Comput Phys 457:111083,
// Eqs. (3)–(4); Suga & Sagawa 1974):
//   p = E(t) (V − V0),   E(t) = E_min + (E_max − E_min) e(t),
//   e(t) = ½ (1 − cos(π s / T_C))              for 0 ≤ s < T_C        (contraction)
//          ½ (1 + cos(π (s − T_C) / T_R))      for T_C ≤ s < T_C + T_R (relaxation)
//          0                                    otherwise,
// with s = (t − t_onset) mod T the time since the last onset. The activation window
// T_C + T_R must fit in the period T (the reader checks it).
// Units: p in Pa, V in mm³, E in Pa/mm³, times in s.

namespace fe2 {

struct ElastanceParameters {
  double E_min = 0.0;         ///< passive (diastolic) elastance (Pa/mm³)
  double E_max = 0.0;         ///< peak (end-systolic) elastance (Pa/mm³), >= E_min
  double V0 = 0.0;            ///< volume at zero pressure (mm³)
  double V_init = 0.0;        ///< initial volume (mm³)
  double onset = 0.0;         ///< t_onset: start of contraction within the period (s)
  double contraction = 0.0;   ///< T_C (s)
  double relaxation = 0.0;    ///< T_R (s)
};

class TimeVaryingElastance {
 public:
  TimeVaryingElastance() = default;
  TimeVaryingElastance(const ElastanceParameters& p, double period) : p_(p), period_(period) {}

  /// e(t) in [0, 1].
  double activation(double t) const;
  /// E(t) (Pa/mm³).
  double elastance(double t) const { return p_.E_min + (p_.E_max - p_.E_min) * activation(t); }
  /// p = E(t)(V − V0) (Pa).
  double pressure(double t, double V) const { return elastance(t) * (V - p_.V0); }

  const ElastanceParameters& parameters() const { return p_; }
  double period() const { return period_; }

 private:
  ElastanceParameters p_;
  double period_ = 1.0;
};

}  // namespace fe2
