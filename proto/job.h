#pragma once
// A job is one unit-iteration (DESIGN §3): in, the macro gradient and its rate in the
// unit's frame plus step data; out, the unit's condensed contribution (𝔸_hom, P̃), the
// true averaged stress P̄ for the convergence test, norms and measured cost.
#include "common/tensor9.h"

#include <cstdint>
#include <string>

namespace fe2::proto {

struct JobInput {
  int32_t unit = -1;          ///< global unit (integration point) id
  int32_t step = 0;           ///< time step index, from 0
  int32_t iteration = 1;      ///< Newton iteration within the step, from 1
  double time = 0.0;          ///< time at the end of the step
  double dt = 0.0;
  uint8_t apply_update = 0;   ///< apply the pending δw (Steps 1 and 4) before assembling
  uint8_t force_refresh = 0;  ///< refactor K and recompute χ whatever the policy says
  Vec9 Zbar = Vec9::Zero();       ///< Z̄_μ, macro displacement gradient in the unit frame
  Vec9 Zbar_dot = Vec9::Zero();   ///< Ż̄_μ
  /// c = ∂Ż̄/∂Z̄ of the macro time integrator (1/Δt quasi-static, γ/(βΔt) Newmark, 0
  /// without a step): the point's tangent is 𝔸 = ∂Π/∂Z + c ∂Π/∂Ż (Material.h).
  double Zbar_dot_coefficient = 0.0;
  double activation_time = 0.0;   ///< when the point's cells are excited (s)
  /// The point starts afresh under a finite Z̄ (a restart with --fresh-units): before
  /// the job it is brought to equilibrium at this Z̄, quasi-statically from its committed
  /// state and committed there, so that the job's Newton update starts from equilibrium.
  uint8_t settle = 0;
};

enum class Refresh : uint8_t { reuse = 0, refresh = 1 };

/// After a job at (s, i) a point's next job is one of three; the point says for each
/// whether it would refresh (PointModel::next_refresh), as bits of
/// JobOutput::next_refresh, so the scheduler need not know the point's policy. A
/// rollback changes the point's state, so the bits say nothing about a retry.
enum NextJob : uint8_t {
  next_iteration = 1,  ///< (s, i + 1): Newton goes on
  restart_step = 2,    ///< (s, 1) after a commit: the next part of a cut step
  next_step = 4,       ///< (s + 1, 1)
  all_next_jobs = 7,
};

/// Whether the job at (step, iteration), following one at (last_step, last_iteration)
/// with bits `next_refresh`, refreshes; false when it is none of the three (unknown:
/// the scheduler then charges a move the factor rebuild).
inline bool refreshes_next(uint8_t next_refresh, int last_step, int last_iteration, int step,
                           int iteration) {
  if (step == last_step && iteration == last_iteration + 1) return next_refresh & next_iteration;
  if (step == last_step && iteration == 1) return next_refresh & restart_step;
  if (step == last_step + 1 && iteration == 1) return next_refresh & next_step;
  return false;
}

struct JobOutput;
/// A unit's residual as convergence tests read it: ‖r‖ / r_ref, or 0 once ‖r‖ is at the
/// round-off floor of its assembly (a tight micro_rtol on a high-contrast unit is then met).
double relative_residual(const JobOutput& o);

struct JobOutput {
  int32_t unit = -1;
  Mat9 A_hom = Mat9::Zero();  ///< Eq. (7): 𝔸_hom = Ā − Hχ
  Vec9 P_tilde = Vec9::Zero();///< Eq. (9): P̃ = P̄ + H δw₁
  Vec9 P_bar = Vec9::Zero();  ///< ⟨Π⟩ at the assembled state (true stress, for the residual)
  double r_norm = 0.0;        ///< ‖r‖ of the micro out-of-balance force
  double r_ref = 1.0;         ///< its scale: converged when r_norm <= rtol * r_ref
  double r_floor = 0.0;       ///< ‖r‖ of round-off: below it the unit cannot reduce r further
  int32_t gmres_iterations = 0;
  Refresh kind = Refresh::reuse;
  double cpu_seconds = 0.0;   ///< whole job, thread CPU time
  double cpu_assembly = 0.0;
  double cpu_refresh = 0.0;   ///< factorization + characteristic modes
  double cpu_solve = 0.0;     ///< Step 1 GMRES
  uint8_t next_refresh = 0;   ///< NextJob bits: which possible next jobs would refresh
  uint64_t state_bytes = 0;   ///< the point's serialized state now (what a move sends)
  double active_tension = 0.0;///< T_a of the point's contracting cells (mean over a unit's cells), Pa
  /// farm.factor_memory_budget (worker/UnitStore.h): factors of other units the rank
  /// dropped to make room for this job's, and whether this job rebuilt its own factor
  /// because the budget had dropped it (that rebuild's CPU time is in cpu_refresh).
  int32_t factor_evictions = 0;
  uint8_t factor_rebuilt = 0;
  /// The refresh policy's cost model (worker/RefreshPolicy.h), in flops: this job's GMRES
  /// work beyond one iteration (0 if it refreshed), and what a refresh of the unit costs.
  /// Coordinators sum them to decide collective refreshes (coordinator/farm/CollectiveRefresh.h).
  double excess_flops = 0.0;
  double refresh_flops = 0.0;
  uint8_t failed = 0;         ///< the unit could not do this iteration (NumericalError)
  std::string message;        ///< why, when failed
};

inline double relative_residual(const JobOutput& o) {
  return o.r_norm <= o.r_floor ? 0.0 : o.r_norm / o.r_ref;
}

}  // namespace fe2::proto
