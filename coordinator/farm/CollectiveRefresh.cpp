#include "coordinator/farm/CollectiveRefresh.h"

#include "common/error.h"

#include <algorithm>
#include <cmath>

namespace fe2 {

CollectiveRefresh::CollectiveRefresh(std::vector<int> model_of_point, std::vector<bool> collective)
    : model_of_point_(std::move(model_of_point)),
      collective_(std::move(collective)),
      active_(std::find(collective_.begin(), collective_.end(), true) != collective_.end()),
      excess_(collective_.size(), 0),
      refresh_cost_(collective_.size(), 0),
      due_(collective_.size(), false),
      excess_committed_(collective_.size(), 0),
      due_committed_(collective_.size(), false) {
  for (int m : model_of_point_)
    FE2_CHECK(m >= 0 && m < static_cast<int>(collective_.size()), "point model {} of {}", m, collective_.size());
}

int CollectiveRefresh::due_models() const {
  return static_cast<int>(std::count(due_.begin(), due_.end(), true));
}

int CollectiveRefresh::account(const std::vector<proto::JobOutput>& results, bool forced_all,
                               const SumOverCoordinators& sum) {
  const int M = static_cast<int>(collective_.size());
  // The models whose units all refreshed in this iteration start over.
  for (int m = 0; m < M; ++m)
    if (due_[m] || forced_all) excess_[m] = 0, due_[m] = false;
  // [E_0 .. E_{M−1}, R_0 .. R_{M−1}] of this coordinator's units, in whole flops.
  std::vector<int64_t> totals(2 * static_cast<size_t>(M), 0);
  for (const auto& r : results) {
    const int m = model_of_point_[r.unit];
    if (!collective_[m]) continue;
    totals[m] += std::llround(r.excess_flops);
    totals[M + m] += std::llround(r.refresh_flops);
  }
  sum(totals.data(), 2 * M);
  int became_due = 0;
  for (int m = 0; m < M; ++m) {
    if (!collective_[m]) continue;
    excess_[m] += totals[m];
    refresh_cost_[m] = totals[M + m];
    // A unit without a factor refreshes anyway (R counts only factored units): R_m = 0
    // means nothing to rent yet.
    if (refresh_cost_[m] > 0 && excess_[m] >= refresh_cost_[m]) {
      due_[m] = true;
      ++became_due;
    }
  }
  return became_due;
}

void CollectiveRefresh::commit() {
  excess_committed_ = excess_;
  due_committed_ = due_;
}

void CollectiveRefresh::rollback() {
  excess_ = excess_committed_;
  due_ = due_committed_;
}

void CollectiveRefresh::save(ByteWriter& w) const {
  w.put<uint64_t>(collective_.size());
  for (size_t m = 0; m < collective_.size(); ++m) {
    w.put(excess_committed_[m]);
    w.put(static_cast<uint8_t>(due_committed_[m]));
  }
}

void CollectiveRefresh::restore(ByteReader& r) {
  const auto M = r.get<uint64_t>();
  if (M != collective_.size())
    throw InputError(fmt::format("{}: collective refresh state for {} point models where this run has {}",
                                 r.what(), M, collective_.size()));
  for (size_t m = 0; m < M; ++m) {
    const auto E = r.get<int64_t>();
    const auto due = r.get<uint8_t>();
    if (E < 0 || due > 1)
      throw InputError(fmt::format("{}: collective refresh state of model {} out of range (excess {}, due {})",
                                   r.what(), m, E, due));
    excess_committed_[m] = E;
    due_committed_[m] = due == 1;
  }
  rollback();
}

}  // namespace fe2
