#include "coordinator/LocalPoints.h"

#include "common/cpu_timer.h"

namespace fe2 {

LocalPoints::LocalPoints(const std::vector<PointModelSpec>& models, std::vector<int> model_of_unit,
                         const std::vector<int>& units)
    : model_of_unit_(std::move(model_of_unit)), store_(models, model_of_unit_) {
  for (int u : units) store_.create(u);
}

void LocalPoints::begin(const std::vector<proto::JobInput>& jobs,
                        std::vector<proto::JobInput>& farm_jobs, std::vector<size_t>& farm_index) {
  jobs_.clear();
  index_.clear();
  farm_jobs.clear();
  farm_index.clear();
  for (size_t k = 0; k < jobs.size(); ++k) {
    if (store_.holds(jobs[k].unit)) {
      jobs_.push_back(jobs[k]);
      index_.push_back(k);
    } else {
      farm_jobs.push_back(jobs[k]);
      farm_index.push_back(k);
    }
  }
  out_.assign(jobs_.size(), proto::JobOutput{});
  next_ = 0;
  cpu_ = 0.0;
}

bool LocalPoints::run(int n) {
  const double c0 = thread_cpu_seconds();
  for (int i = 0; i < n && !finished(); ++i, ++next_) out_[next_] = store_.run(jobs_[next_]);
  cpu_ += thread_cpu_seconds() - c0;
  return finished();
}

void LocalPoints::results(std::vector<proto::JobOutput>& out) const {
  for (size_t i = 0; i < index_.size(); ++i) out[index_[i]] = out_[i];
}

}  // namespace fe2
