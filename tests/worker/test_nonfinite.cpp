// Non-finite is failure everywhere: a unit whose residual norm or its
// scale overflows must not "converge" on inf <= inf; it fails with a NumericalError
// that says "non-finite", which the run turns into a cut-back and `unit` into exit 3.
#include "tests/worker/unit_fixtures.h"
#include "worker/unit_equilibrium.h"

#include <gtest/gtest.h>

namespace fe2 {
namespace {

/// Π = s Z (a linear law of huge modulus s): every stress entry is finite, but
/// ‖P̄‖ overflows, so the unit's residual scale r_ref = ‖P̄‖·h is inf.
class HugeLinear final : public Material {
 public:
  explicit HugeLinear(double s) : s_(s) {}
  std::string name() const override { return "huge_linear"; }
  double energy(const Vec9& Z) const override { return 0.5 * s_ * Z.squaredNorm(); }
  void stress_and_tangent(const Vec9& Z, Vec9& Pi, Mat9& A) const override {
    Pi = s_ * Z;
    A = s_ * Mat9::Identity();
  }
  double stiffness_scale() const override { return s_; }

 private:
  double s_;
};

TEST(NonFinite, OverflowingResidualScaleIsANumericalFailure) {
  CellLayout c;
  c.kind = "homogeneous";
  c.resolution = {2, 2, 2};
  auto law = std::make_shared<HugeLinear>(1e300);
  MicroUnit unit(test::make_unit_model(c, {law}));
  const Vec9 Z = test::gradient({0.0, 0.0, 0.0, 0.5, 0.0, 0.0, 0.0, 0.0, 0.0});
  ASSERT_TRUE((1e300 * Z).allFinite());
  ASSERT_FALSE(std::isfinite((1e300 * Z).norm())) << "the test needs ‖P̄‖ to overflow";
  try {
    equilibrate(unit, Z, 1e-10, 5);
    FAIL() << "an overflowing residual scale converged";
  } catch (const NumericalError& e) {
    EXPECT_NE(std::string(e.what()).find("non-finite"), std::string::npos) << e.what();
  }
  // The same law at a sane modulus equilibrates: the failure above is the overflow.
  MicroUnit sane(test::make_unit_model(c, {std::make_shared<HugeLinear>(1e3)}));
  EXPECT_NO_THROW(equilibrate(sane, Z, 1e-10, 5));
}

}  // namespace
}  // namespace fe2
