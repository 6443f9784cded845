#pragma once
// The spread of a replayed run's job costs, split into what the work explains and what
// the machine added (timing noise), and a replay with the noise taken out.
//
// Jobs of one Newton iteration that report the same work (both refresh or both reuse,
// the same GMRES iteration count) do the same arithmetic up to the unit's own state: a
// unit-iteration of identical factorization pattern and solve count. Their costs are
// modelled as
//   c(v, i) = m(i, k) · a(v) · ε(v, i),    k = (refreshed, GMRES count) of the job,
// m(i, k) the median of the jobs of kind k in iteration i, a(v) the unit's persistent
// factor (geometric mean of c / m over its jobs, shrunk by the part of its spread over
// units that the noise of a mean of that many jobs explains), ε what is left. A persistent cost
// difference (a harder unit) shows in a(v); noise in ε, and noise does not repeat: the
// lag-one correlation of a unit's log ε over its successive jobs is near zero.
//
// With a single unit per worker the iteration waits for its slowest job, so on a noisy
// machine the replay's makespan is the maximum of the noise: the spread of ε, not of the
// work, sets the efficiency (BENCHMARKS.md, "The refresh policy at one unit per worker").
#include "coordinator/farm/farm_sim.h"

namespace fe2 {

/// Jobs whose kind has fewer members than this in their iteration keep their measured
/// cost (their median would be the job itself, or one of two).
inline constexpr int kMinJobsOfAKind = 3;

struct CostSpread {
  double persistent = 0.0;  ///< std of log a(v) over units (0.03: units differ by 3 %)
  double noise = 0.0;       ///< std of log ε over jobs in groups of kMinJobsOfAKind or more
  double lag1 = 0.0;        ///< correlation of log ε(v, i) with log ε(v, next job of v)
  long long jobs = 0;       ///< jobs in such groups (the rest keep their cost)
  long long all_jobs = 0;
};

/// The decomposition above of `in`'s job costs (needs `in.gmres` sized like `in.cost`).
CostSpread cost_spread(const FarmSimInput& in);

/// Replaces each cost in a group of kMinJobsOfAKind or more by m(i, k) · a(v) (and its
/// factorization part in proportion): the replay without the machine's timing noise.
void remove_timing_noise(FarmSimInput& in);

}  // namespace fe2
