#pragma once
// The material response at one macro integration point, however it is computed: an
// FE² micro unit (MicroUnit) or the macro constitutive law itself (MacroLawPoint).
// This is the first of a scene's effects (DESIGN §4): the macro problem and the task
// farm see only this interface, in the point's own material frame.
#include "common/bytes.h"
#include "proto/job.h"

#include <cstddef>
#include <memory>
#include <string>

namespace fe2 {

class PointModel {
 public:
  virtual ~PointModel() = default;
  /// One Newton iteration at this point (DESIGN §2, steps 1–5).
  virtual proto::JobOutput iterate(const proto::JobInput& in) = 0;
  /// The step converged: the current state is the one to come back to.
  virtual void commit_step() = 0;
  /// The step is being cut back: return to the last committed state.
  virtual void rollback_step() = 0;
  /// Whole state to bytes and back (migration between ranks, checkpoints).
  virtual void serialize(Bytes& out) const = 0;
  virtual void deserialize(const Bytes& in) = 0;
  /// serialize() for a checkpoint: with `with_factor` (output.checkpoint_factors) a point
  /// that holds a factor it can write out also stores it, and deserialize() takes it back
  /// instead of refactoring. Migration never sends factors (16× the bytes of the matrix).
  virtual void serialize_for_checkpoint(Bytes& out, bool with_factor) const {
    (void)with_factor;
    serialize(out);
  }
  virtual std::string kind() const = 0;

  /// Whether the next job, if it is (step, iteration) and not forced, refactors: the
  /// scheduler charges a migration a factor rebuild only when it does not.
  virtual bool next_refresh(int step, int iteration) const = 0;
  /// Bytes serialize() writes now: what a migration of this point sends.
  virtual size_t state_bytes() const = 0;

  /// Bytes of the cached factor this point holds now (0: none). The factor is a cache:
  /// drop_factor() frees it and the point rebuilds it, unchanged, on its next job
  /// (the factor memory budget, worker/UnitStore.h).
  virtual double factor_bytes() const { return 0.0; }
  virtual void drop_factor() {}
};

using PointModelPtr = std::unique_ptr<PointModel>;

}  // namespace fe2
