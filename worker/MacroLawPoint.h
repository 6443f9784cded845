#pragma once
// The macro constitutive law at a point: 𝔸_hom = 𝔸(Z̄), P̃ = P̄ = Π(Z̄). No micro
// unknowns, so nothing to condense; the state is only the last Z̄ (for symmetry with
// units in checkpoints).
#include "common/materials/Material.h"
#include "worker/PointModel.h"

namespace fe2 {

class MacroLawPoint final : public PointModel {
 public:
  explicit MacroLawPoint(MaterialPtr material) : material_(std::move(material)) {}
  proto::JobOutput iterate(const proto::JobInput& in) override;
  void commit_step() override {}
  void rollback_step() override {}
  void serialize(Bytes& out) const override;
  void deserialize(const Bytes& in) override;
  std::string kind() const override { return "macro_law"; }
  bool next_refresh(int, int) const override { return false; }  // nothing to factor
  size_t state_bytes() const override;

 private:
  MaterialPtr material_;
  Vec9 Zbar_ = Vec9::Zero();
};

}  // namespace fe2
