#pragma once
// Prescribed active tension, for verification and for scenes that only need a load:
//  - ConstantTension: T_a = T₀ at all times;
//  - TableTension: T_a(s) piecewise linear in s = t − t_act through the pairs
//    (s_i, T_i), s strictly increasing, held at T_0 before s_0 and at T_last after.
// Neither keeps state nor depends on λ or λ̇.
#include "common/cellmodels/CellModel.h"

#include <utility>
#include <vector>

namespace fe2 {

class ConstantTension final : public CellModel {
 public:
  static constexpr const char* kName = "constant";
  explicit ConstantTension(double Ta) : Ta_(Ta) {}

  std::string name() const override { return kName; }
  std::string description() const override;
  int state_size() const override { return 0; }
  void rest_state(std::span<double>) const override {}
  ActiveTension advance(const CellStep&, std::span<const double>,
                        std::span<double>) const override {
    return {Ta_, 0.0, 0.0};
  }
  bool rate_dependent() const override { return false; }

 private:
  double Ta_;
};

class TableTension final : public CellModel {
 public:
  static constexpr const char* kName = "table";
  /// Pairs (s, T_a) with s strictly increasing (an internal error otherwise: the spec
  /// reader refuses bad tables first, naming the key).
  explicit TableTension(std::vector<std::pair<double, double>> table);

  std::string name() const override { return kName; }
  std::string description() const override;
  int state_size() const override { return 0; }
  void rest_state(std::span<double>) const override {}
  ActiveTension advance(const CellStep& step, std::span<const double>,
                        std::span<double>) const override;
  bool rate_dependent() const override { return false; }

  /// T_a at s = t − t_act.
  double tension(double s) const;

 private:
  std::vector<std::pair<double, double>> table_;
};

}  // namespace fe2
