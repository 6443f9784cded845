#pragma once
// The points a coordinator evaluates itself, where their element lives
// (farm.macro_law_points "local", FarmLayout::local_unit): a macro-law point costs
// microseconds, less than the ≈ 2 KB job and result that would carry it to a worker and
// back. They live in a UnitStore of their own, the class that holds a worker's units, so
// they run, fail (a failed result, the step is cut back), commit and roll back exactly as
// on a worker and give the same outputs bit for bit; they are never queued, placed,
// moved or counted by the rebalancer.
//
// One iteration: begin() keeps the jobs of the points here and hands back the others
// (for the farm); run() evaluates a few at a time, so the coordinator keeps serving
// workers' pulls in between; results() merges the answers into the job order.
#include "proto/job.h"
#include "worker/UnitStore.h"

#include <vector>

namespace fe2 {

class LocalPoints {
 public:
  /// Creates the points `units`; `models` is lent and must outlive this object.
  LocalPoints(const std::vector<PointModelSpec>& models, std::vector<int> model_of_unit,
              const std::vector<int>& units);

  int size() const { return store_.size(); }
  bool holds(int unit) const { return store_.holds(unit); }

  /// Splits an iteration's `jobs`: those of points here are kept, the others go to
  /// `farm_jobs`, with their positions in `jobs` in `farm_index`.
  void begin(const std::vector<proto::JobInput>& jobs, std::vector<proto::JobInput>& farm_jobs,
             std::vector<size_t>& farm_index);
  /// Evaluates up to `n` more of the kept jobs; true once all are done.
  bool run(int n);
  bool finished() const { return next_ == index_.size(); }
  /// Puts each kept job's result at its position in `out` (sized as `jobs`).
  void results(std::vector<proto::JobOutput>& out) const;

  /// This iteration: jobs evaluated here and their CPU seconds (trace, summary).
  int jobs() const { return static_cast<int>(index_.size()); }
  double cpu_seconds() const { return cpu_; }

  void commit() { store_.commit(); }
  void rollback() { store_.rollback(); }
  /// Checkpoints and restarts: a point's whole state, as a worker's store copies it.
  Bytes copy(int unit, bool with_factor = false) const { return store_.copy(unit, with_factor); }
  void restore(int unit, const Bytes& state) { store_.restore(unit, state); }

 private:
  const std::vector<int> model_of_unit_;  ///< lent to store_: declared before it
  UnitStore store_;
  std::vector<proto::JobInput> jobs_;     ///< kept jobs of this iteration
  std::vector<size_t> index_;             ///< their positions in the iteration's jobs
  std::vector<proto::JobOutput> out_;
  size_t next_ = 0;
  double cpu_ = 0.0;
};

}  // namespace fe2
