#pragma once
// The error of a run against a reference run on one quantity (`fe2heart study`).
//
// A quantity is read from a run folder's summary.json (and spec.json, for the probes'
// reference positions) as a series: per step time, a flat vector of numbers
//   displacement      probe displacements u = x - X, every probe, 3 each
//   probes            deformed probe positions x
//   cavity_volumes    history[*].cavity_volumes
//   cavity_pressures  history[*].circulation.<cavity>.pressure
//   load_pressures    history[*].load_pressures
//   "/a/json/pointer" a number (or array or object of numbers) of summary.json, once
// The error is max |q - q_ref| / max |q_ref| over every compared time and entry (the
// absolute max |q - q_ref| if q_ref is 0 throughout). The reference is interpolated
// linearly in time at each of the run's step times (exact where the times coincide);
// run times outside the reference's are not compared.
#include "common/spec/SpecNode.h"

#include <string>
#include <vector>

namespace fe2 {

struct QuantitySeries {
  std::vector<double> time;                ///< empty for a once-only quantity
  std::vector<std::vector<double>> value;  ///< per time (or one)
};

/// The quantity of the run in `dir` (its summary.json, spec.json); an InputError
/// naming the file and quantity if the run has none of it.
QuantitySeries read_quantity(const std::string& dir, const std::string& quantity);

struct QuantityError {
  double error = -1;  ///< relative; < 0: not comparable (see `note`)
  int times = 0;      ///< times compared
  std::string note;   ///< why not comparable, or "absolute (reference 0)"
};

QuantityError compare_quantity(const QuantitySeries& run, const QuantitySeries& reference);

}  // namespace fe2
