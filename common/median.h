#pragma once
// The median of a sample (mean of the middle two for an even count; NaN-free input).
#include <algorithm>
#include <vector>

namespace fe2 {

/// `empty` for an empty sample.
inline double median(std::vector<double> v, double empty) {
  if (v.empty()) return empty;
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace fe2
