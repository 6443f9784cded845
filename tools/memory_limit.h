#pragma once
// The memory a rank may use (`--memory-limit`) and the check that refuses unit models
// that would not fit, before any of them is built.
#include "common/spec/memory_size.h"
#include "coordinator/RunSpec.h"
#include "worker/MicroModel.h"

#include <string>
#include <vector>

namespace fe2::cli {

using fe2::parse_memory_size;  // common/spec/memory_size.h

struct MemoryLimit {
  double bytes = 0;
  std::string origin;  ///< "--memory-limit 8G", or "MemAvailable 7.6 GB / 2 ranks on this node"
};

/// `text` empty: the machine's available memory (MemAvailable in /proc/meminfo) shared
/// by the ranks of this node (OMPI_COMM_WORLD_LOCAL_SIZE / MPI_LOCALNRANKS, else 1).
MemoryLimit memory_limit(const std::string& text);

/// Refuses (InputError, naming the model's size key, the estimate and the limit) when
/// `units_on_rank[m]` units of each model m (with m's shared model) exceed the limit on
/// some rank. `units_on_rank`: per rank, units per model index of spec.models.
/// `factor_budget` > 0 (farm.factor_memory_budget): a rank's factors count at most that.
void check_unit_memory(const std::vector<PointModelSpec>& models,
                       const std::vector<std::vector<long long>>& units_on_rank,
                       const MemoryLimit& limit, double factor_budget = 0);

/// One model with `units` units on one rank.
void check_unit_memory(const MicroModelPlan& plan, long long units, const MemoryLimit& limit);

}  // namespace fe2::cli
