#include "coordinator/farm/timing_noise.h"

#include "common/error.h"
#include "common/median.h"

#include <algorithm>
#include <cmath>
#include <map>

namespace fe2 {
namespace {

/// m(i, k) for each job, and how many jobs of its kind its iteration had (0: no job).
struct KindMedians {
  std::vector<std::vector<double>> median;
  std::vector<std::vector<int>> members;
};

KindMedians kind_medians(const FarmSimInput& in) {
  FE2_CHECK(in.gmres.size() == in.cost.size(), "gmres counts for {} of {} iterations", in.gmres.size(),
            in.cost.size());
  KindMedians k;
  for (size_t i = 0; i < in.cost.size(); ++i) {
    const size_t units = in.cost[i].size();
    std::map<std::pair<char, int>, std::vector<size_t>> kinds;
    for (size_t v = 0; v < units; ++v)
      if (in.cost[i][v] > 0.0) kinds[{in.refreshed[i][v], in.gmres[i][v]}].push_back(v);
    k.median.emplace_back(units, 0.0);
    k.members.emplace_back(units, 0);
    for (const auto& [kind, jobs] : kinds) {
      std::vector<double> c;
      for (size_t v : jobs) c.push_back(in.cost[i][v]);
      const double m = median(c, 0.0);
      for (size_t v : jobs) {
        k.median[i][v] = m;
        k.members[i][v] = static_cast<int>(jobs.size());
      }
    }
  }
  return k;
}

bool modelled(const KindMedians& k, size_t i, size_t v) { return k.members[i][v] >= kMinJobsOfAKind; }

double std_dev(const std::vector<double>& x) {
  if (x.size() < 2) return 0.0;
  double mean = 0.0, s = 0.0;
  for (double e : x) mean += e;
  mean /= static_cast<double>(x.size());
  for (double e : x) s += (e - mean) * (e - mean);
  return std::sqrt(s / static_cast<double>(x.size() - 1));
}

/// log a(v): the mean of log(c / m) over the unit's n(v) modelled jobs (0 for a unit with
/// none), shrunk toward 0 by the share of its spread over units that noise explains: a
/// mean of n noisy jobs scatters by σ_ε² / n even between identical units, and the
/// slowest of thousands of such means would otherwise keep the noise in the replay
/// (empirical Bayes: s = 1 − mean(σ_ε² / n(v)) / var(log a), clipped to [0, 1]).
std::vector<double> log_persistent(const FarmSimInput& in, const KindMedians& k) {
  const size_t units = in.cost.empty() ? 0 : in.cost.front().size();
  std::vector<double> sum(units, 0.0), n(units, 0.0);
  for (size_t i = 0; i < in.cost.size(); ++i)
    for (size_t v = 0; v < units; ++v)
      if (modelled(k, i, v)) {
        sum[v] += std::log(in.cost[i][v] / k.median[i][v]);
        n[v] += 1.0;
      }
  std::vector<double> means, residuals;
  double noise_of_means = 0.0;
  for (size_t v = 0; v < units; ++v) {
    sum[v] = n[v] > 0.0 ? sum[v] / n[v] : 0.0;
    if (n[v] > 0.0) means.push_back(sum[v]);
  }
  for (size_t i = 0; i < in.cost.size(); ++i)
    for (size_t v = 0; v < units; ++v)
      if (modelled(k, i, v)) residuals.push_back(std::log(in.cost[i][v] / k.median[i][v]) - sum[v]);
  const double noise = std_dev(residuals);
  for (size_t v = 0; v < units; ++v)
    if (n[v] > 0.0) noise_of_means += noise * noise / n[v] / static_cast<double>(means.size());
  const double spread = std_dev(means);
  const double shrink = spread > 0.0 ? std::clamp(1.0 - noise_of_means / (spread * spread), 0.0, 1.0) : 1.0;
  for (double& a : sum) a *= shrink;
  return sum;
}

}  // namespace

CostSpread cost_spread(const FarmSimInput& in) {
  const KindMedians k = kind_medians(in);
  const std::vector<double> log_a = log_persistent(in, k);
  const size_t units = log_a.size();
  CostSpread s;
  std::vector<double> eps, a_of_units;
  std::vector<char> seen(units, 0);
  std::vector<double> previous(units, 0.0);
  std::vector<char> has_previous(units, 0);
  double sxy = 0.0, sxx = 0.0, syy = 0.0;
  for (size_t i = 0; i < in.cost.size(); ++i)
    for (size_t v = 0; v < units; ++v) {
      if (in.cost[i][v] > 0.0) ++s.all_jobs;
      if (!modelled(k, i, v)) continue;
      ++s.jobs;
      const double e = std::log(in.cost[i][v] / k.median[i][v]) - log_a[v];
      eps.push_back(e);
      if (!seen[v]) a_of_units.push_back(log_a[v]);
      seen[v] = 1;
      if (has_previous[v]) {
        sxy += previous[v] * e;
        sxx += previous[v] * previous[v];
        syy += e * e;
      }
      previous[v] = e;
      has_previous[v] = 1;
    }
  s.persistent = std_dev(a_of_units);
  s.noise = std_dev(eps);
  // ε has mean zero per unit by construction: the correlation about zero.
  s.lag1 = sxx > 0.0 && syy > 0.0 ? sxy / std::sqrt(sxx * syy) : 0.0;
  return s;
}

void remove_timing_noise(FarmSimInput& in) {
  const KindMedians k = kind_medians(in);
  const std::vector<double> log_a = log_persistent(in, k);
  for (size_t i = 0; i < in.cost.size(); ++i)
    for (size_t v = 0; v < log_a.size(); ++v) {
      if (!modelled(k, i, v)) continue;
      const double c = k.median[i][v] * std::exp(log_a[v]);
      in.refresh_part[i][v] *= c / in.cost[i][v];
      in.cost[i][v] = c;
    }
}

}  // namespace fe2
