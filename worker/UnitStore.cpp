#include "worker/UnitStore.h"

#include "common/error.h"
#include "common/spec/SpecNode.h"
#include "worker/unit_fields.h"

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <string>
#include <thread>

namespace fe2 {

UnitStore::Fault UnitStore::parse_fault(const std::string& value) {
  Fault fault;
  auto bad = [&](const std::string& what) {
    throw InputError(fmt::format("FE2HEART_FAULT='{}': {}; expected "
                                 "unit=K[,step=S][,kind=numerical|fatal|stall|hang|kill] with integers K, S >= 0",
                                 value, what));
  };
  auto integer = [&](const std::string& key, const std::string& v) {
    size_t used = 0;
    int x = -1;
    try {
      x = std::stoi(v, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (v.empty() || used != v.size() || x < 0)
      bad(fmt::format("{}={} is not a non-negative integer", key, v));
    return x;
  };
  bool has_unit = false;
  size_t at = 0;
  while (at <= value.size()) {
    const size_t comma = std::min(value.find(',', at), value.size());
    const std::string item = value.substr(at, comma - at);
    at = comma + 1;
    const size_t eq = item.find('=');
    if (eq == std::string::npos) bad(fmt::format("field '{}' has no '='", item));
    const std::string key = item.substr(0, eq), v = item.substr(eq + 1);
    if (key == "unit") {
      fault.unit = integer(key, v);
      has_unit = true;
    } else if (key == "step") {
      fault.step = integer(key, v);
    } else if (key == "kind") {
      const std::vector<std::string> kinds = {"numerical", "fatal", "stall", "hang", "kill"};
      if (std::find(kinds.begin(), kinds.end(), v) == kinds.end())
        bad(fmt::format("unknown kind '{}'; expected {}", v, known_names("a kind", v, kinds)));
      fault.fatal = v == "fatal";
      fault.stall = v == "stall";
      fault.hang = v == "hang";
      fault.kill = v == "kill";
    } else {
      bad(fmt::format("unknown field '{}'; expected {}", key, known_names("a field", key, {"unit", "step", "kind"})));
    }
  }
  if (!has_unit) bad("no unit=K field");
  return fault;
}

UnitStore::Fault UnitStore::fault_from_env() {
  const char* f = std::getenv("FE2HEART_FAULT");
  return f ? parse_fault(f) : Fault{};
}

UnitStore::UnitStore(const std::vector<PointModelSpec>& models, const std::vector<int>& model_of_unit)
    : models_(models), model_of_unit_(model_of_unit) {
  fault_ = fault_from_env();
}

std::vector<int> UnitStore::units() const {
  std::vector<int> u;
  for (const auto& [id, _] : units_) u.push_back(id);
  return u;
}

void UnitStore::create(int unit) {
  FE2_CHECK(!holds(unit), "unit {} already here", unit);
  units_[unit] = make_point_model(models_.at(model_of_unit_.at(unit)));
  factor_[unit] = FactorRecord{};
}

double UnitStore::held_factor_bytes() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return held_locked();
}

double UnitStore::held_by(int unit, const PointModel& point) const {
  // A running unit's factor is being rebuilt or replaced by another thread: not read.
  const FactorRecord& rec = factor_.at(unit);
  return rec.running ? rec.running_bytes : point.factor_bytes();
}

double UnitStore::held_locked() const {
  double held = 0;
  for (const auto& [id, u] : units_) held += held_by(id, *u);
  return held;
}

UnitStore::FactorCounts UnitStore::factor_counts(int unit) const {
  std::lock_guard<std::mutex> lock(mutex_);
  auto it = factor_.find(unit);
  FE2_CHECK(it != factor_.end(), "factor counts of unit {} which does not live here", unit);
  return it->second.counts;
}

double UnitStore::expected_factor_bytes(int unit) const {
  const FactorRecord& own = factor_.at(unit);
  if (own.bytes > 0) return own.bytes;
  double same_model = 0;
  const int model = model_of_unit_.at(unit);
  for (const auto& [id, rec] : factor_)
    if (model_of_unit_.at(id) == model) same_model = std::max(same_model, rec.bytes);
  return same_model;
}

int UnitStore::make_room(int in_use, double need) {
  double held = 0;
  for (const auto& [id, u] : units_)
    if (id != in_use) held += held_by(id, *u);
  int dropped = 0;
  while (held + need > budget_) {
    // The least recently used other idle unit that holds a factor (ties: the lowest id).
    int victim = -1;
    long long oldest = 0;
    for (const auto& [id, u] : units_) {
      const FactorRecord& rec = factor_.at(id);
      if (id != in_use && !rec.running && u->factor_bytes() > 0 && (victim < 0 || rec.last_use < oldest))
        victim = id, oldest = rec.last_use;
    }
    if (victim < 0) break;  // the units in use alone are over budget: they keep their factors
    PointModel& v = *units_.at(victim);
    held -= v.factor_bytes();
    v.drop_factor();
    FactorRecord& rec = factor_.at(victim);
    rec.dropped = true;
    ++rec.counts.evictions;
    ++totals_.evictions;
    ++dropped;
  }
  return dropped;
}

proto::JobOutput UnitStore::run(const proto::JobInput& job) {
  auto it = units_.find(job.unit);
  FE2_CHECK(it != units_.end(), "job for unit {} which does not live here", job.unit);
  if (job.unit == fault_.unit && job.step >= fault_.step) {
    if (fault_.stall) std::raise(SIGSTOP);  // freeze this rank, as `kill -STOP` does
    while (fault_.hang) std::this_thread::sleep_for(std::chrono::hours(1));  // this thread only
    if (fault_.kill) std::raise(SIGKILL);   // a node that dies: no handler, no cleanup
    if (fault_.fatal)
      throw Error(fmt::format("unit {}: injected fatal fault (FE2HEART_FAULT)", job.unit));
    proto::JobOutput out;
    out.unit = job.unit;
    out.failed = 1;
    out.message = fmt::format("unit {}: injected numerical fault (FE2HEART_FAULT)", job.unit);
    return out;
  }
  PointModel& point = *it->second;
  int evicted = 0;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    FactorRecord& rec = factor_.at(job.unit);
    rec.last_use = ++clock_;
    const bool builds = point.factor_bytes() == 0;  // this job will build a factor
    if (budget_ > 0 && builds) evicted += make_room(job.unit, expected_factor_bytes(job.unit));
    rec.running = true;
    rec.running_bytes = builds ? expected_factor_bytes(job.unit) : point.factor_bytes();
  }
  // After the job (kept if it fails): its factor's true size, and what it was rebuilt for.
  auto account = [&](proto::JobOutput& out) {
    std::lock_guard<std::mutex> lock(mutex_);
    FactorRecord& rec = factor_.at(job.unit);
    rec.running = false;
    if (budget_ > 0) evicted += make_room(job.unit, point.factor_bytes());
    out.factor_evictions = evicted;
    out.factor_rebuilt = out.factor_rebuilt && rec.dropped;  // not after a move or rollback
    if (out.factor_rebuilt) ++rec.counts.rebuilds, ++totals_.rebuilds;
    if (point.factor_bytes() > 0) {
      rec.bytes = point.factor_bytes();
      rec.dropped = false;
    }
    // Only a job that holds a factor can raise the total (a sum over every unit here:
    // O(units) per job, so not for the thousands of macro-law points a store may hold).
    if (point.factor_bytes() > 0) peak_held_ = std::max(peak_held_, held_locked());
  };
  try {
    proto::JobOutput out = point.iterate(job);
    // What the scheduler needs to plan moves, from the point itself (its policy and
    // its state), for each job that can follow this one.
    out.next_refresh = static_cast<uint8_t>(
        (point.next_refresh(job.step, job.iteration + 1) ? proto::next_iteration : 0) |
        (point.next_refresh(job.step, 1) ? proto::restart_step : 0) |
        (point.next_refresh(job.step + 1, 1) ? proto::next_step : 0));
    out.state_bytes = point.state_bytes();
    account(out);
    return out;
  } catch (const NumericalError& e) {
    proto::JobOutput out;
    out.unit = job.unit;
    out.failed = 1;
    out.message = e.what();
    account(out);
    return out;
  } catch (...) {  // fatal: the run stops; the unit is no longer in a job
    std::lock_guard<std::mutex> lock(mutex_);
    factor_.at(job.unit).running = false;
    throw;
  }
}

void UnitStore::commit() {
  for (auto& [_, u] : units_) u->commit_step();
}

void UnitStore::rollback() {
  for (auto& [_, u] : units_) u->rollback_step();
}

proto::UnitFields UnitStore::fields(int unit, int step) const {
  auto it = units_.find(unit);
  FE2_CHECK(it != units_.end(), "fields of unit {} which does not live here", unit);
  const auto* micro = dynamic_cast<const MicroUnit*>(it->second.get());
  FE2_CHECK(micro, "fields of unit {}: a {} point has no micro fields", unit, it->second->kind());
  return micro_fields(*micro, unit, step);
}

Bytes UnitStore::take(int unit) {
  auto it = units_.find(unit);
  FE2_CHECK(it != units_.end(), "cannot send unit {}: not here", unit);
  Bytes b;
  it->second->serialize(b);
  units_.erase(it);
  factor_.erase(unit);
  return b;
}

void UnitStore::put(int unit, const Bytes& state) {
  create(unit);
  units_[unit]->deserialize(state);
}

Bytes UnitStore::copy(int unit, bool with_factor) const {
  auto it = units_.find(unit);
  FE2_CHECK(it != units_.end(), "cannot copy the state of unit {}: not here", unit);
  Bytes b;
  it->second->serialize_for_checkpoint(b, with_factor);
  return b;
}

void UnitStore::restore(int unit, const Bytes& state) {
  if (holds(unit)) {
    units_.erase(unit);
    factor_.erase(unit);
  }
  put(unit, state);
  // A restart's rebuild is counted (summary.factor_memory.rebuilds) like the budget's.
  factor_[unit].dropped = units_[unit]->factor_bytes() == 0;
}

}  // namespace fe2
