#pragma once
// A prescribed Ca²⁺ transient per material point: a bi-exponential template started at
// the point's activation time t_act (no electrophysiology). With s = t − t_act (taken
// modulo `period` when period > 0, so beats repeat; s < 0 is rest):
//
//   Ca(s) = Ca_rest + (Ca_peak − Ca_rest) (e^{−s/τ_decay} − e^{−s/τ_rise}) / N,
//   N = max_s (e^{−s/τ_decay} − e^{−s/τ_rise}) = e^{−s*/τ_decay} − e^{−s*/τ_rise},
//   s* = τ_rise τ_decay ln(τ_decay/τ_rise) / (τ_decay − τ_rise),
//
// so the peak is exactly Ca_peak at s = s*. This is the template of Rice et al. 2008
// (Biophys J 95:2368, their τ1, τ2), which the Land 2017 model is distributed with for
// runs with prescribed calcium. The normalized activation f = (Ca − rest)/(peak − rest)
// lies in [0, 1] and drives the Bestel–Clément–Sorine law.
//
// Units: time in s, calcium in µM.
#include <string>

namespace fe2 {

struct CalciumParameters {
  // Defaults: τ_rise = 20 ms, τ_decay = 110 ms as in Rice et al. 2008's template;
  // diastolic 0.1 µM (the O'Hara–Rudy human model's resting [Ca]i) and a human-like
  // systolic peak of 1 µM.
  double rest = 0.1;     ///< diastolic [Ca²⁺]i (µM)
  double peak = 1.0;     ///< systolic peak [Ca²⁺]i (µM), > rest
  double rise = 0.020;   ///< τ_rise (s), < τ_decay
  double decay = 0.110;  ///< τ_decay (s)
  double period = 0.0;   ///< beat period (s); 0: one beat
};

class CalciumTransient {
 public:
  /// Checks 0 < rise < decay, 0 < rest < peak, period >= 0 (an internal error if not:
  /// the spec reader refuses bad values first, naming the key).
  explicit CalciumTransient(const CalciumParameters& p);

  const CalciumParameters& parameters() const { return p_; }

  /// [Ca²⁺]i (µM) at time t for a point activated at t_act.
  double value(double t, double t_act) const;
  /// Normalized activation f = (Ca − rest)/(peak − rest) ∈ [0, 1].
  double activation(double t, double t_act) const;
  /// s* = the time after onset of the peak (s).
  double peak_time() const { return s_peak_; }
  /// The first beat onset (t_act + k·period, k ≥ 0) strictly after t, or +∞. The
  /// template has a kink there, so integrators start a substep at it.
  double next_onset(double t, double t_act) const;

  /// "bi-exponential calcium: rest 0.1 µM, peak 1 µM, rise 20 ms, decay 110 ms, one beat"
  std::string description() const;

 private:
  /// (e^{−s/τ_decay} − e^{−s/τ_rise}) / N for s ≥ 0 within a beat.
  double shape(double s) const;

  CalciumParameters p_;
  double s_peak_ = 0.0;
  double inv_norm_ = 0.0;  ///< 1/N
};

}  // namespace fe2
