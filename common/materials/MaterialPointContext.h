#pragma once
// What a material point knows besides its displacement gradient Z: the time, the step
// and the rate Ż at that point, and its history (internal variables). A law stays a
// pure function of (Z, context, committed history); the point model that owns the
// history commits, rolls back and serializes it (deal.II step-44's PointHistory).
//
//   history_committed  the law's internal variables at the end of the last converged
//                      step (read-only: the law integrates from these over Δt)
//   history            the same variables at the current iterate, written by the law
//                      (recomputed from history_committed at every evaluation, so a
//                      Newton iteration can be repeated or rolled back at no risk)
//
// Both spans hold Material::history_size() doubles; empty for laws without history.
// A law returns ∂Π/∂Z at fixed Ż and ∂Π/∂Ż at fixed Z, each through its history update
// (Material::stress_and_tangent_at); the point model, which knows how its Ż follows
// from Z (backward Euler, Newmark), combines them into the step's tangent.
#include "common/tensor9.h"

#include <span>

namespace fe2 {

struct MaterialPointContext {
  double time = 0.0;          ///< t at the end of the step (the state being solved for)
  double dt = 0.0;            ///< Δt of the step; 0 when there is no step (a lone evaluation)
  Vec9 Zdot = Vec9::Zero();   ///< Ż at this point, column-major as Z (DESIGN §1)
  double activation_time = 0.0;  ///< when this point's cells are excited (s)
};

/// One point's history: the committed values (read-only) and the current ones (written).
struct PointHistory {
  std::span<const double> committed;
  std::span<double> current;
};

}  // namespace fe2
