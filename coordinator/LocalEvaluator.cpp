#include "coordinator/PointEvaluator.h"

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

}  // namespace fe2
