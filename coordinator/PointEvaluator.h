#pragma once
// Evaluates one Newton iteration at every macro integration point: jobs in, results
// out, indexed by point. The one-process form (LocalEvaluator) runs the points in a
// loop; the MPI task farm implements the same interface across worker ranks.
#include "proto/job.h"
#include "proto/messages.h"
#include "worker/point_models.h"

#include <functional>
#include <vector>

namespace fe2 {

class PointEvaluator {
 public:
  virtual ~PointEvaluator() = default;
  /// out[k] answers jobs[k]. Throws NumericalError if any point fails.
  virtual void evaluate(const std::vector<proto::JobInput>& jobs,
                        std::vector<proto::JobOutput>& out) = 0;
  virtual void commit_step() = 0;
  virtual void rollback_step() = 0;
  /// The micro fields of FE² units `units` (output.units) at the state of the last
  /// evaluate, labelled output step `step`: call after a step's converged iteration and
  /// before commit_step (worker/unit_fields.h). In `units` order on the first
  /// coordinator, empty on the others. @note Collective on the coordinator group.
  virtual std::vector<proto::UnitFields> unit_fields(const std::vector<int>& units, int step) = 0;

  /// Checkpoints: a copy of every point's state (its whole history) goes to `sink` on the
  /// first coordinator, each point once, in no fixed order. At a step boundary (after
  /// commit_step). `with_factors`: points store their factors where they can
  /// (output.checkpoint_factors). @note Collective on the coordinator group.
  using StateSink = std::function<void(int point, const Bytes& state)>;
  virtual void save_states(const StateSink& sink, bool with_factors) = 0;
  /// Restarts: replaces the state of each point of `points` (every point once; significant
  /// on the first coordinator) with `read(point)`, which is called there in that order.
  /// Before the first evaluate. @note Collective on the coordinator group.
  using StateSource = std::function<Bytes(int point)>;
  virtual void restore_states(const std::vector<int>& points, const StateSource& read) = 0;
};

/// All points on this process, evaluated in order.
class LocalEvaluator final : public PointEvaluator {
 public:
  /// One point per entry of `model_of_point` (an index into `models`).
  LocalEvaluator(const std::vector<PointModelSpec>& models, const std::vector<int>& model_of_point);
  void evaluate(const std::vector<proto::JobInput>& jobs,
                std::vector<proto::JobOutput>& out) override;
  void commit_step() override;
  void rollback_step() override;
  std::vector<proto::UnitFields> unit_fields(const std::vector<int>& units, int step) override;
  void save_states(const StateSink& sink, bool with_factors) override;
  void restore_states(const std::vector<int>& points, const StateSource& read) override;
  PointModel& point(int k) { return *points_[k]; }
  int size() const { return static_cast<int>(points_.size()); }

 private:
  std::vector<PointModelPtr> points_;
};

}  // namespace fe2
