#pragma once
// The units that live on this rank (a unit runs where its state lives), by global id.
// Builds them fresh, runs their jobs, commits or rolls them back, and moves their
// state out and in as bytes when the rebalancer migrates them.
#include "proto/job.h"
#include "proto/messages.h"
#include "worker/point_models.h"

#include <map>
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

  /// Serializes a unit and removes it from this rank.
  Bytes take(int unit);
  /// Rebuilds a unit that arrives from another rank.
  void put(int unit, const Bytes& state);

  /// Test hook FE2HEART_FAULT="unit=K[,step=S][,kind=numerical|fatal|stall]": unit K fails
  /// from step S on, wherever it lives. A malformed value is an InputError naming the
  /// variable and the value (a typo must not silently test nothing).
  struct Fault {
    int unit = -1, step = 0;
    bool fatal = false;
    bool stall = false;  ///< freeze the process (SIGSTOP): the liveness tests
  };
  static Fault parse_fault(const std::string& value);
  /// The hook as set in the environment (unit -1: none).
  static Fault fault_from_env();

 private:
  const std::vector<PointModelSpec>& models_;
  const std::vector<int>& model_of_unit_;
  std::map<int, PointModelPtr> units_;
  Fault fault_;
};

}  // namespace fe2
