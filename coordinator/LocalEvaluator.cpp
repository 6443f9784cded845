#include "coordinator/PointEvaluator.h"

#include "common/error.h"
#include "worker/unit_fields.h"

namespace fe2 {

LocalEvaluator::LocalEvaluator(const std::vector<PointModelSpec>& models,
                               const std::vector<int>& model_of_point) {
  points_.reserve(model_of_point.size());
  for (int m : model_of_point) points_.push_back(make_point_model(models[m]));
}

void LocalEvaluator::evaluate(const std::vector<proto::JobInput>& jobs,
                              std::vector<proto::JobOutput>& out) {
  out.resize(jobs.size());
  for (size_t k = 0; k < jobs.size(); ++k) out[k] = points_[jobs[k].unit]->iterate(jobs[k]);
}

void LocalEvaluator::commit_step() {
  for (auto& p : points_) p->commit_step();
}

void LocalEvaluator::rollback_step() {
  for (auto& p : points_) p->rollback_step();
}

std::vector<proto::UnitFields> LocalEvaluator::unit_fields(const std::vector<int>& units, int step) {
  std::vector<proto::UnitFields> out;
  for (int u : units) {
    FE2_CHECK(u >= 0 && u < size(), "fields of unit {}: there are {} points", u, size());
    const auto* micro = dynamic_cast<const MicroUnit*>(points_[u].get());
    FE2_CHECK(micro, "fields of unit {}: a {} point has no micro fields", u, points_[u]->kind());
    out.push_back(micro_fields(*micro, u, step));
  }
  return out;
}

void LocalEvaluator::save_states(const StateSink& sink, bool with_factors) {
  for (int k = 0; k < size(); ++k) {
    Bytes b;
    points_[k]->serialize_for_checkpoint(b, with_factors);
    sink(k, b);
  }
}

void LocalEvaluator::restore_states(const std::vector<int>& points, const StateSource& read) {
  for (int k : points) {
    FE2_CHECK(k >= 0 && k < size(), "restoring point {}: there are {} points", k, size());
    points_[k]->deserialize(read(k));
  }
}

}  // namespace fe2
