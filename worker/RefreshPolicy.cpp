#include "worker/RefreshPolicy.h"

#include "common/error.h"

#include <algorithm>
#include <cmath>

namespace fe2 {

RefreshPolicy::RefreshPolicy(Kind kind, int N_t, double matvec_flops, double solve_flop_cost)
    : kind_(kind), N_t_(N_t), matvec_flops_(matvec_flops), solve_flop_cost_(solve_flop_cost) {
  FE2_CHECK(N_t >= 1, "refresh policy: N_t = {}, expected >= 1", N_t);
  FE2_CHECK(solve_flop_cost >= 1.0, "refresh policy: solve_flop_cost = {}, expected >= 1", solve_flop_cost);
}

bool RefreshPolicy::due(int step, int iteration) const {
  switch (kind_) {
    case Kind::every_iteration: return true;
    case Kind::fixed: return iteration == 1 && step % N_t_ == 0;
    case Kind::adaptive: return excess_iterations_ * iteration_flops() >= refresh_flops();
    case Kind::collective: return false;  // the job's force flag carries the coordinators' decision
  }
  return true;
}

int RefreshPolicy::stale_gmres_budget(int max_iterations) const {
  const bool rental = kind_ == Kind::adaptive || kind_ == Kind::collective;
  if (!rental || factor_flops_ <= 0.0 || iteration_flops() <= 0.0) return max_iterations;
  const double budget = std::ceil(refresh_flops() / (solve_flop_cost_ * iteration_flops()));
  return static_cast<int>(std::clamp(budget, static_cast<double>(std::min(kMinStaleGmresBudget, max_iterations)),
                                     static_cast<double>(max_iterations)));
}

void RefreshPolicy::refreshed(double factor_flops, double solve_flops) {
  factor_flops_ = factor_flops;
  solve_flops_ = solve_flops;
  excess_iterations_ = 0.0;
}

void RefreshPolicy::reused(int gmres_iterations) {
  excess_iterations_ += std::max(0, gmres_iterations - 1);
}

void RefreshPolicy::write(ByteWriter& w) const {
  w.put(excess_iterations_);
  w.put(factor_flops_);
  w.put(solve_flops_);
}

void RefreshPolicy::read(ByteReader& r) {
  excess_iterations_ = r.get<double>();
  factor_flops_ = r.get<double>();
  solve_flops_ = r.get<double>();
}

}  // namespace fe2
