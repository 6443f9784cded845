#include "worker/UnitStore.h"

#include "common/error.h"

#include <cstdlib>
#include <string>

namespace fe2 {

UnitStore::UnitStore(const std::vector<PointModelSpec>& models, const std::vector<int>& model_of_unit)
    : models_(models), model_of_unit_(model_of_unit) {
  // Test hook: FE2HEART_FAULT="unit=K,step=S,kind=numerical|fatal" makes unit K fail
  // from step S on, wherever it lives (the failure-handling tests use it).
  if (const char* f = std::getenv("FE2HEART_FAULT")) {
    const std::string s(f);
    auto field = [&](const std::string& key) -> std::string {
      const auto at = s.find(key + "=");
      if (at == std::string::npos) return "";
      const auto end = s.find(',', at);
      return s.substr(at + key.size() + 1, end == std::string::npos ? std::string::npos : end - at - key.size() - 1);
    };
    if (!field("unit").empty()) fault_.unit = std::stoi(field("unit"));
    if (!field("step").empty()) fault_.step = std::stoi(field("step"));
    fault_.fatal = field("kind") == "fatal";
  }
}

std::vector<int> UnitStore::units() const {
  std::vector<int> u;
  for (const auto& [id, _] : units_) u.push_back(id);
  return u;
}

void UnitStore::create(int unit) {
  FE2_CHECK(!holds(unit), "unit {} already here", unit);
  units_[unit] = make_point_model(models_.at(model_of_unit_.at(unit)));
}

proto::JobOutput UnitStore::run(const proto::JobInput& job) {
  auto it = units_.find(job.unit);
  FE2_CHECK(it != units_.end(), "job for unit {} which does not live here", job.unit);
  if (job.unit == fault_.unit && job.step >= fault_.step) {
    if (fault_.fatal)
      throw Error(fmt::format("unit {}: injected fatal fault (FE2HEART_FAULT)", job.unit));
    proto::JobOutput out;
    out.unit = job.unit;
    out.failed = 1;
    out.message = fmt::format("unit {}: injected numerical fault (FE2HEART_FAULT)", job.unit);
    return out;
  }
  try {
    return it->second->iterate(job);
  } catch (const NumericalError& e) {
    proto::JobOutput out;
    out.unit = job.unit;
    out.failed = 1;
    out.message = e.what();
    return out;
  }
}

void UnitStore::commit() {
  for (auto& [_, u] : units_) u->commit_step();
}

void UnitStore::rollback() {
  for (auto& [_, u] : units_) u->rollback_step();
}

Bytes UnitStore::take(int unit) {
  auto it = units_.find(unit);
  FE2_CHECK(it != units_.end(), "cannot send unit {}: not here", unit);
  Bytes b;
  it->second->serialize(b);
  units_.erase(it);
  return b;
}

void UnitStore::put(int unit, const Bytes& state) {
  create(unit);
  units_[unit]->deserialize(state);
}

}  // namespace fe2
