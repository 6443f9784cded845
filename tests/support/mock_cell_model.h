#pragma once
// A test-only cell model with one state variable s that depends on λ and λ̇ through the
// step, so the tangent's history terms can be checked:
//
//   s_{n+1} = s_n + Δt (k (λ − 1) + m λ̇),   T_a = T0 (1 + s_{n+1}) + a (λ − 1) + b λ̇,
//
// with the exact sensitivities dT_a/dλ = T0 Δt k + a and dT_a/dλ̇ = T0 Δt m + b.
#include "common/cellmodels/CellModel.h"

namespace fe2::test {

class MockCellModel final : public CellModel {
 public:
  double T0 = 2.0e4, k = 3.0, m = 0.5, a = 5.0e3, b = 400.0, s_rest = 0.1;

  std::string name() const override { return "test_mock"; }
  std::string description() const override { return "test mock cell model"; }
  int state_size() const override { return 1; }
  void rest_state(std::span<double> state) const override { state[0] = s_rest; }
  bool rate_dependent() const override { return b != 0.0 || m != 0.0; }
  ActiveTension advance(const CellStep& step, std::span<const double> committed,
                        std::span<double> current) const override {
    const double s = committed[0] + step.dt * (k * (step.lambda - 1.0) + m * step.lambda_dot);
    current[0] = s;
    return {T0 * (1.0 + s) + a * (step.lambda - 1.0) + b * step.lambda_dot,
            T0 * step.dt * k + a, T0 * step.dt * m + b};
  }
};

}  // namespace fe2::test
