#pragma once
// The units that live on this rank (a unit runs where its state lives), by global id.
// Builds them fresh, runs their jobs, commits or rolls them back, and moves their
// state out and in as bytes when the rebalancer migrates them.
//
// Factor memory budget (farm.factor_memory_budget): the cached factors of the units
// here may hold at most that many bytes. Before a job whose unit has no factor (first
// job, after a move, a rollback or a drop) and again after it (a factor's true size is
// known once built), the factors of the least recently used other units are dropped
// until the held ones fit; a dropped unit rebuilds its factor from the matrix it was
// made of on its next job (bit for bit: the answer does not change), and that rebuild's
// CPU time lands in the job's measured cost, which the rebalancer reads.
//
// run() may be called for different units at once from the threads of a JobPool
// (farm.threads_per_rank): the bookkeeping (clock, records, drops, peak) is under one
// lock, a unit whose job is running is never dropped, and its factor counts at the size
// it had (or is expected to reach) when its job began. Everything else — create,
// commit, rollback, moves, checkpoints — runs between iterations on the main thread.
#include "proto/job.h"
#include "proto/messages.h"
#include "worker/point_models.h"

#include <map>
#include <mutex>
#include <vector>

namespace fe2 {

class UnitStore {
 public:
  /// `models` and `model_of_unit` are lent and must outlive the store.
  UnitStore(const std::vector<PointModelSpec>& models, const std::vector<int>& model_of_unit);

  void create(int unit);
  bool holds(int unit) const { return units_.count(unit) > 0; }
  int size() const { return static_cast<int>(units_.size()); }
  std::vector<int> units() const;

  /// Runs one job. A NumericalError of the unit comes back as a failed result (the
  /// coordinator cuts the step); anything else propagates (a fatal error).
  proto::JobOutput run(const proto::JobInput& job);
  void commit();
  void rollback();
  /// A unit's micro fields for output (unit_fields.h: before the step's commit); an
  /// fe2::Error if the unit is not here or is not an FE² unit.
  proto::UnitFields fields(int unit, int step) const;

  /// Bytes of factors this rank may hold (0: unlimited).
  void set_factor_budget(double bytes) { budget_ = bytes; }
  double factor_budget() const { return budget_; }
  /// Bytes of the factors held now, and the most held after any job.
  double held_factor_bytes() const;
  double peak_factor_bytes() const { return peak_held_; }
  /// Factors dropped for the budget, and factors rebuilt because they had been.
  struct FactorCounts {
    long long evictions = 0, rebuilds = 0;
  };
  FactorCounts factor_counts() const { return totals_; }  ///< this rank, since it started
  FactorCounts factor_counts(int unit) const;             ///< one unit, while it lives here

  /// Serializes a unit and removes it from this rank.
  Bytes take(int unit);
  /// Rebuilds a unit that arrives from another rank.
  void put(int unit, const Bytes& state);
  /// A copy of a unit's state (checkpoints; with its factor if `with_factor`, see
  /// PointModel::serialize_for_checkpoint); the unit stays here.
  Bytes copy(int unit, bool with_factor = false) const;
  /// Replaces a unit's state with `state` (a restart), creating the unit if it is not here.
  /// A unit restored without its factor counts the rebuild of its next job in
  /// factor_counts(), as one dropped by the budget does.
  void restore(int unit, const Bytes& state);

  /// Test hook FE2HEART_FAULT="unit=K[,step=S][,kind=numerical|fatal|stall|hang|kill]": unit K
  /// fails from step S on, wherever it lives. A malformed value is an InputError naming the
  /// variable and the value (a typo must not silently test nothing).
  struct Fault {
    int unit = -1, step = 0;
    bool fatal = false;
    bool stall = false;  ///< freeze the process (SIGSTOP): the liveness tests
    bool hang = false;   ///< freeze the thread running the job: the thread liveness tests
    bool kill = false;   ///< kill -9 the process: the restart tests
  };
  static Fault parse_fault(const std::string& value);
  /// The hook as set in the environment (unit -1: none).
  static Fault fault_from_env();

 private:
  const std::vector<PointModelSpec>& models_;
  const std::vector<int>& model_of_unit_;
  std::map<int, PointModelPtr> units_;
  Fault fault_;

  /// Drops least recently used factors of units other than `in_use` (and not running)
  /// until those held plus `need` bytes fit the budget; returns how many it dropped.
  /// Callers hold mutex_, as for the other helpers below.
  int make_room(int in_use, double need);
  /// The bytes of factors held, a running unit's counted as when its job began.
  double held_locked() const;
  double held_by(int unit, const PointModel& point) const;
  /// The size a factor of `unit` will have: its own last one, else that of a unit of
  /// the same model here, else 0 (unknown until built; the check after the job fixes it).
  double expected_factor_bytes(int unit) const;
  struct FactorRecord {
    long long last_use = 0;  ///< store clock at its last job
    double bytes = 0;        ///< size of its last factor (0: never built here)
    bool dropped = false;    ///< dropped by the budget and not rebuilt since
    bool running = false;    ///< a job of this unit runs now (on some thread)
    double running_bytes = 0;///< its factor's size, or the expected one, when that job began
    FactorCounts counts;
  };
  mutable std::mutex mutex_;
  double budget_ = 0;
  long long clock_ = 0;
  std::map<int, FactorRecord> factor_;
  FactorCounts totals_;
  double peak_held_ = 0;
};

}  // namespace fe2
