#pragma once
// The macro constitutive law at a point: 𝔸_hom = 𝔸(Z̄), P̃ = P̄ = Π(Z̄). No micro
// unknowns, so nothing to condense. The law gets the job's context (t, Δt, Ż = Ż̄) and,
// if it keeps history, the point's history, which this point commits, rolls back and
// serializes. The state is the last Z̄ and the history.
#include "common/materials/Material.h"
#include "worker/PointModel.h"

#include <vector>

namespace fe2 {

class MacroLawPoint final : public PointModel {
 public:
  explicit MacroLawPoint(MaterialPtr material);
  proto::JobOutput iterate(const proto::JobInput& in) override;
  void commit_step() override { history_committed_ = history_; }
  void rollback_step() override { history_ = history_committed_; }
  void serialize(Bytes& out) const override;
  void deserialize(const Bytes& in) override;
  std::string kind() const override { return "macro_law"; }
  bool next_refresh(int, int) const override { return false; }  // nothing to factor
  size_t state_bytes() const override;

  /// The law's history at the last job, and at the last commit.
  const std::vector<double>& history() const { return history_; }
  const std::vector<double>& history_committed() const { return history_committed_; }

 private:
  MaterialPtr material_;
  Vec9 Zbar_ = Vec9::Zero();
  std::vector<double> history_;            ///< Material::history_size() doubles
  std::vector<double> history_committed_;
};

}  // namespace fe2
