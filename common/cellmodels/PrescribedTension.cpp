#include "common/cellmodels/PrescribedTension.h"

#include "common/error.h"

#include <algorithm>

namespace fe2 {

std::string ConstantTension::description() const {
  return fmt::format("constant active tension T_a = {} Pa", Ta_);
}

TableTension::TableTension(std::vector<std::pair<double, double>> table)
    : table_(std::move(table)) {
  FE2_CHECK(!table_.empty(), "empty tension table");
  for (size_t i = 1; i < table_.size(); ++i)
    FE2_CHECK(table_[i].first > table_[i - 1].first, "table s not increasing at entry {}", i);
}

std::string TableTension::description() const {
  return fmt::format("tabulated active tension T_a(t - t_act): {} points over [{}, {}] s, "
                     "held at the ends",
                     table_.size(), table_.front().first, table_.back().first);
}

double TableTension::tension(double s) const {
  if (s <= table_.front().first) return table_.front().second;
  if (s >= table_.back().first) return table_.back().second;
  // The first entry with s_i > s; its predecessor has s_{i-1} <= s.
  const auto hi = std::upper_bound(table_.begin(), table_.end(), s,
                                   [](double x, const auto& e) { return x < e.first; });
  const auto lo = hi - 1;
  const double w = (s - lo->first) / (hi->first - lo->first);
  return lo->second + w * (hi->second - lo->second);
}

ActiveTension TableTension::advance(const CellStep& step, std::span<const double>,
                                    std::span<double>) const {
  return {tension(step.time - step.activation_time), 0.0, 0.0};
}

}  // namespace fe2
