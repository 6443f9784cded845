#pragma once
// Haemodynamic figures of one cavity over a window of a run (usually the last beat), from
// its pressure and volume samples: EDV, ESV, SV, EF, peak pressure, dP/dt extremes and
// the stroke work −∮ p dV. Shared by `fe2heart circulation` and the coupled beat.
#include <cstddef>
#include <vector>

namespace fe2 {

struct BeatFigures {
  double EDV = 0.0, ESV = 0.0;   ///< max and min volume in the window (mm³)
  double SV = 0.0, EF = 0.0;     ///< EDV − ESV (mm³); SV/EDV
  double peak_pressure = 0.0;    ///< Pa
  double dpdt_max = 0.0, dpdt_min = 0.0;  ///< Pa/s, by differences of the samples
  double stroke_work = 0.0;      ///< −∮ p dV (Pa·mm³ = 1e-9 J), trapezoidal; > 0 for a heart
};

/// Over samples [first, last] of t, p, V (inclusive).
BeatFigures beat_figures(const std::vector<double>& t, const std::vector<double>& p,
                         const std::vector<double>& V, std::size_t first, std::size_t last);

}  // namespace fe2
