#include "common/circulation/beat_summary.h"

#include "common/error.h"

#include <algorithm>
#include <limits>

namespace fe2 {

BeatFigures beat_figures(const std::vector<double>& t, const std::vector<double>& p,
                         const std::vector<double>& V, size_t first, size_t last) {
  FE2_CHECK(first < last && last < t.size() && t.size() == p.size() && t.size() == V.size(),
            "beat_figures: window [{}, {}] of {} samples", first, last, t.size());
  BeatFigures b;
  b.EDV = -std::numeric_limits<double>::infinity();
  b.ESV = std::numeric_limits<double>::infinity();
  b.peak_pressure = -std::numeric_limits<double>::infinity();
  b.dpdt_max = -std::numeric_limits<double>::infinity();
  b.dpdt_min = std::numeric_limits<double>::infinity();
  double work = 0.0;
  for (size_t i = first; i <= last; ++i) {
    b.EDV = std::max(b.EDV, V[i]);
    b.ESV = std::min(b.ESV, V[i]);
    b.peak_pressure = std::max(b.peak_pressure, p[i]);
    if (i == first) continue;
    const double rate = (p[i] - p[i - 1]) / (t[i] - t[i - 1]);
    b.dpdt_max = std::max(b.dpdt_max, rate);
    b.dpdt_min = std::min(b.dpdt_min, rate);
    work += 0.5 * (p[i] + p[i - 1]) * (V[i] - V[i - 1]);
  }
  b.SV = b.EDV - b.ESV;
  b.EF = b.EDV > 0.0 ? b.SV / b.EDV : 0.0;
  b.stroke_work = -work;
  return b;
}

}  // namespace fe2
