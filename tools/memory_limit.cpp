#include "tools/memory_limit.h"

#include "common/error.h"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <sstream>

namespace fe2::cli {

namespace {

double mem_available() {
  std::ifstream in("/proc/meminfo");
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream s(line);
    std::string key;
    double kb = 0;
    if (s >> key >> kb && key == "MemAvailable:") return kb * 1024.0;
  }
  return std::numeric_limits<double>::infinity();  // unknown: no limit
}

int ranks_on_this_node() {
  for (const char* var : {"OMPI_COMM_WORLD_LOCAL_SIZE", "MPI_LOCALNRANKS"})
    if (const char* v = std::getenv(var)) {
      const int n = std::atoi(v);
      if (n > 0) return n;
    }
  return 1;
}

}  // namespace

MemoryLimit memory_limit(const std::string& text) {
  if (!text.empty()) return {parse_memory_size(text, "--memory-limit"), "--memory-limit " + text};
  const double avail = mem_available();
  const int ranks = ranks_on_this_node();
  if (ranks == 1) return {avail, "MemAvailable of this machine"};
  return {avail / ranks, fmt::format("MemAvailable {} shared by {} ranks on this node",
                                     format_bytes(avail), ranks)};
}

namespace {

std::string size_value(const MicroModelPlan& p) {
  if (p.layout)
    return fmt::format("[{}, {}, {}]", p.layout->resolution[0], p.layout->resolution[1],
                       p.layout->resolution[2]);
  return "'" + p.source + "'";
}

[[noreturn]] void refuse(const MicroModelPlan& p, long long units, double need, int rank,
                         const MemoryLimit& limit) {
  const std::string who = rank >= 0 ? fmt::format("rank {} would hold {} unit(s) of this model, "
                                                  "needing ≈ {} in all",
                                                  rank, units, format_bytes(need))
                                    : fmt::format("{} unit(s) of this model need ≈ {}", units,
                                                  format_bytes(need));
  throw InputError(fmt::format("{}: got {}; {} ({}), above the memory limit of {} ({}); expected "
                               "a coarser unit, more ranks, a larger --memory-limit, or a smaller "
                               "farm.factor_memory_budget",
                               p.size_key, size_value(p), who, p.memory.describe(),
                               format_bytes(limit.bytes), limit.origin));
}

}  // namespace

void check_unit_memory(const MicroModelPlan& plan, long long units, const MemoryLimit& limit) {
  const double need = plan.memory.bytes_for(units);
  if (need > limit.bytes) refuse(plan, units, need, -1, limit);
}

void check_unit_memory(const std::vector<PointModelSpec>& models,
                       const std::vector<std::vector<long long>>& units_on_rank,
                       const MemoryLimit& limit, double factor_budget) {
  for (size_t r = 0; r < units_on_rank.size(); ++r) {
    double need = 0, worst = -1, factors = 0;
    size_t worst_m = 0;
    for (size_t m = 0; m < models.size(); ++m) {
      if (!models[m].plan) continue;
      const double b = models[m].plan->memory.bytes_for(units_on_rank[r][m]);
      need += b;
      factors += static_cast<double>(units_on_rank[r][m]) * models[m].plan->memory.factor_bytes;
      if (b > worst) worst = b, worst_m = m;
    }
    // A budget below the rank's factors holds only the budget's worth of them.
    if (factor_budget > 0 && factors > factor_budget) need -= factors - factor_budget;
    // Name the model that takes the most: its size key is what to change.
    if (need > limit.bytes)
      refuse(*models[worst_m].plan, units_on_rank[r][worst_m], need, static_cast<int>(r), limit);
  }
}

}  // namespace fe2::cli
