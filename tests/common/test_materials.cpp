// Hyperelastic laws: Π = ∂W/∂Z and 𝔸 = ∂Π/∂Z against central finite differences at
// finite strain, major symmetry, the small-strain limit, inverted points, frame
// objectivity, and the spec factory's error messages.
#include "common/materials/Guccione.h"
#include "common/spec/spec_schemas.h"
#include "common/materials/HolzapfelOgden.h"
#include "common/materials/NeoHookean.h"
#include "common/materials/StVenantKirchhoff.h"
#include "common/materials/material_factory.h"
#include "tests/common/material_finite_differences.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <initializer_list>
#include <iterator>
#include <limits>
#include <random>
#include <string>

namespace fe2 {
namespace {

/// A fixed pseudo-random displacement gradient, entries uniform in [−amplitude,
/// amplitude], redrawn until F = I + Z is comfortably non-inverted.
Vec9 sample_Z(unsigned seed, double amplitude) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-amplitude, amplitude);
  for (;;) {
    Vec9 Z;
    for (int a = 0; a < 9; ++a) Z(a) = u(rng);
    if ((Mat3::Identity() + as_mat3(Z)).determinant() > 0.3) return Z;
  }
}

using testing::fd_stress;
using testing::fd_tangent;

/// λ δ_iJ δ_kL + μ(δ_ik δ_JL + δ_iL δ_Jk), the isotropic small-strain tensor.
Mat9 isotropic_linear_tangent(double lambda, double mu) {
  Mat9 A = Mat9::Zero();
  auto d = [](int a, int b) { return a == b ? 1.0 : 0.0; };
  for (int i = 0; i < 3; ++i)
    for (int J = 0; J < 3; ++J)
      for (int k = 0; k < 3; ++k)
        for (int L = 0; L < 3; ++L)
          A(index9(i, J), index9(k, L)) =
              lambda * d(i, J) * d(k, L) + mu * (d(i, k) * d(J, L) + d(i, L) * d(J, k));
  return A;
}

/// Rotation by `angle` about `axis`.
Mat3 rotation(const Vec3& axis, double angle) {
  return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
}

struct LawCase {
  std::string label;
  std::function<MaterialPtr()> make;
};

std::ostream& operator<<(std::ostream& os, const LawCase& c) { return os << c.label; }

const LawCase kLaws[] = {
    {"neo_hookean", [] { return std::make_shared<NeoHookean>(1.0e4, 0.3); }},
    {"neo_hookean_nearly_incompressible", [] { return std::make_shared<NeoHookean>(1.0e4, 0.49); }},
    {"st_venant_kirchhoff", [] { return std::make_shared<StVenantKirchhoff>(1.0e4, 0.3); }},
    {"guccione", [] { return std::make_shared<Guccione>(GuccioneParameters{}); }},
    // Land et al. 2015 benchmark exponents: shear stiffer than the transverse direction.
    {"guccione_land",
     [] { return std::make_shared<Guccione>(GuccioneParameters{2000, 8, 2, 4, 5e4}); }},
    {"guccione_no_volumetric",
     [] {
       GuccioneParameters p;
       p.volumetric = Volumetric::none;
       return std::make_shared<Guccione>(p);
     }},
    // Full-invariant HO is left out: its reference stress is a I by design
    // (test_holzapfel_ogden.cpp checks that and its derivatives).
    {"holzapfel_ogden", [] { return std::make_shared<HolzapfelOgden>(HolzapfelOgdenParameters{}); }},
    {"holzapfel_ogden_no_volumetric",
     [] {
       HolzapfelOgdenParameters p;
       p.volumetric = Volumetric::none;
       return std::make_shared<HolzapfelOgden>(p);
     }},
};

/// (seed, amplitude) of the finite strains every law is checked at.
const std::pair<unsigned, double> kStrains[] = {{1, 0.1}, {2, 0.2}, {3, 0.3}, {4, 0.15}, {5, 0.25}};

class MaterialLaw : public ::testing::TestWithParam<LawCase> {
 protected:
  MaterialPtr material = GetParam().make();
};

TEST_P(MaterialLaw, StressIsEnergyDerivative) {
  for (const auto& [seed, amplitude] : kStrains) {
    const Vec9 Z = sample_Z(seed, amplitude);
    const Vec9 Pi = material->stress(Z);
    const Vec9 Pi_fd = fd_stress(*material, Z, 1e-6);
    EXPECT_LE((Pi - Pi_fd).norm(), 1e-7 * Pi.norm())
        << "seed " << seed << "\nPi    " << Pi.transpose() << "\nPi_fd " << Pi_fd.transpose();
  }
}

TEST_P(MaterialLaw, TangentIsStressDerivative) {
  for (const auto& [seed, amplitude] : kStrains) {
    const Vec9 Z = sample_Z(seed, amplitude);
    const Mat9 A = material->tangent(Z);
    const Mat9 A_fd = fd_tangent(*material, Z, 1e-6);
    EXPECT_LE((A - A_fd).norm(), 1e-6 * A.norm()) << "seed " << seed << "\nA - A_fd\n" << A - A_fd;
  }
}

TEST_P(MaterialLaw, TangentHasMajorSymmetry) {
  ASSERT_TRUE(material->major_symmetric());
  for (const auto& [seed, amplitude] : kStrains) {
    const Mat9 A = material->tangent(sample_Z(seed, amplitude));
    EXPECT_LE((A - A.transpose()).norm(), 1e-13 * A.norm()) << "seed " << seed;
  }
}

TEST_P(MaterialLaw, ReferenceStateIsStressFreeAndEnergyFree) {
  const Vec9 zero = Vec9::Zero();
  EXPECT_EQ(material->energy(zero), 0.0);
  EXPECT_LE(material->stress(zero).norm(), 1e-12 * material->stiffness_scale());
  EXPECT_GT(material->stiffness_scale(), 0.0);
}

TEST_P(MaterialLaw, InvertedPointThrowsNumericalError) {
  Vec9 reflected = Vec9::Zero();
  reflected(index9(0, 0)) = -2.0;  // F = diag(−1, 1, 1), det F = −1
  const Vec9 collapsed = -as_vec9(Mat3::Identity());  // F = 0
  Vec9 not_a_number = Vec9::Zero();
  not_a_number(3) = std::numeric_limits<double>::quiet_NaN();
  for (const Vec9& Z : {reflected, collapsed, not_a_number}) {
    Vec9 Pi;
    Mat9 A;
    EXPECT_THROW(material->energy(Z), NumericalError);
    EXPECT_THROW(material->stress(Z), NumericalError);
    EXPECT_THROW(material->stress_and_tangent(Z, Pi, A), NumericalError);
  }
  try {
    material->stress(reflected);
  } catch (const NumericalError& e) {
    EXPECT_NE(std::string(e.what()).find("inverted material point: det F = -1"), std::string::npos)
        << e.what();
  }
}

INSTANTIATE_TEST_SUITE_P(Laws, MaterialLaw, ::testing::ValuesIn(kLaws),
                         [](const auto& info) { return info.param.label; });

// Laws with their own stress-only path (cheaper than the pair) must agree with the pair. Guccione has none (stress() is stress_and_tangent()), so it is
// not listed: comparing a function with itself would prove nothing.
class MaterialStressPath : public MaterialLaw {};

TEST_P(MaterialStressPath, StressAloneAgreesWithStressAndTangent) {
  for (const auto& [seed, amplitude] : kStrains) {
    const Vec9 Z = sample_Z(seed, amplitude);
    Vec9 Pi;
    Mat9 A;
    material->stress_and_tangent(Z, Pi, A);
    EXPECT_LE((material->stress(Z) - Pi).norm(), 1e-13 * Pi.norm()) << "seed " << seed;
  }
}

INSTANTIATE_TEST_SUITE_P(OwnStressPath, MaterialStressPath,
                         ::testing::Values(kLaws[0], kLaws[1], kLaws[2]),
                         [](const auto& info) { return info.param.label; });

TEST(MaterialSmallStrain, IsotropicLawsMatchLinearElasticityAtZeroStrain) {
  const NeoHookean nh(1.0e4, 0.3);
  const StVenantKirchhoff svk(1.0e4, 0.3);
  const auto [lambda, mu] = nh.lame();
  EXPECT_NEAR(mu, 1.0e4 / 2.6, 1e-9);
  EXPECT_NEAR(lambda, 1.0e4 * 0.3 / (1.3 * 0.4), 1e-9);
  const Mat9 expected = isotropic_linear_tangent(lambda, mu);
  for (const Material* m : std::initializer_list<const Material*>{&nh, &svk}) {
    const Mat9 A = m->tangent(Vec9::Zero());
    EXPECT_LE((A - expected).norm(), 1e-12 * expected.norm()) << m->name() << "\n" << A;
    EXPECT_DOUBLE_EQ(m->stiffness_scale(), lambda + 2 * mu);
  }
}

TEST(MaterialGuccione, EnergyIsFrameIndifferent) {
  const Guccione law(GuccioneParameters{});
  const Mat3 rotations[] = {rotation(Vec3(1, 0, 0), 0.7), rotation(Vec3(0.3, -1, 2), 2.1),
                            rotation(Vec3(-1, 1, 1), -1.3)};
  for (const auto& [seed, amplitude] : kStrains) {
    const Vec9 Z = sample_Z(seed, amplitude);
    const Mat3 F = Mat3::Identity() + as_mat3(Z);
    for (const Mat3& R : rotations) {
      // F → R F, i.e. Z → R(I + Z) − I: a rigid rotation after the deformation.
      const Vec9 Z_rotated = as_vec9(R * F - Mat3::Identity());
      EXPECT_NEAR(law.energy(Z_rotated), law.energy(Z), 1e-12 * law.energy(Z));
      // and Π, a two-point tensor, rotates with its spatial leg: Π → R Π.
      const Mat3 Pi_expected = R * as_mat3(law.stress(Z));
      EXPECT_LE((as_mat3(law.stress(Z_rotated)) - Pi_expected).norm(), 1e-12 * Pi_expected.norm());
    }
  }
}

TEST(MaterialGuccione, IsAnisotropicAlongTheFibre) {
  // Equal stretch along fibre and sheet: the fibre (b_f > b_t) carries more stress.
  const Guccione law(GuccioneParameters{});
  Vec9 Z_fibre = Vec9::Zero(), Z_sheet = Vec9::Zero();
  Z_fibre(index9(0, 0)) = 0.1;
  Z_sheet(index9(1, 1)) = 0.1;
  EXPECT_GT(law.stress(Z_fibre)(index9(0, 0)), law.stress(Z_sheet)(index9(1, 1)));
}

TEST(MaterialGuccione, OverflowingStrainThrowsNumericalError) {
  const Guccione law(GuccioneParameters{});
  Vec9 Z = Vec9::Zero();
  Z(index9(0, 0)) = 10.0;  // E11 = 60, Q ≈ 6.7e4: e^Q overflows
  Vec9 Pi;
  Mat9 A;
  EXPECT_THROW(law.energy(Z), NumericalError);
  EXPECT_THROW(law.stress_and_tangent(Z, Pi, A), NumericalError);
}

TEST(MaterialConstructors, RejectNonPhysicalParameters) {
  EXPECT_THROW(NeoHookean(-1.0, 0.3), InputError);
  EXPECT_THROW(NeoHookean(1.0, 0.5), InputError);
  EXPECT_THROW(StVenantKirchhoff(1.0, -1.0), InputError);
  GuccioneParameters p;
  p.kappa = 0.0;
  EXPECT_THROW(Guccione{p}, InputError);
}

/// make_material on a spec object at path "/material"; returns the InputError's
/// message, or "" when nothing was thrown.
std::string factory_error(const json& spec) {
  try {
    SpecNode node(spec, "/material", material_schema());
    make_material(node);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(MaterialFactory, BuildsEveryModel) {
  const json specs[] = {
      {{"model", "neo_hookean"}, {"E", 1.0e4}, {"nu", 0.3}},
      {{"model", "st_venant_kirchhoff"}, {"E", 1.0e4}, {"nu", 0.3}},
      {{"model", "guccione"}},
      {{"model", "holzapfel_ogden"}},
  };
  ASSERT_EQ(material_models().size(), std::size(specs));
  for (const json& spec : specs) {
    SpecNode node(spec, "/material", material_schema());
    const MaterialPtr m = make_material(node);
    ASSERT_TRUE(m);
    EXPECT_EQ(json(m->name()), spec["model"]);
  }
}

TEST(MaterialFactory, ReadsGuccioneParametersWithDefaults) {
  const json spec = {{"model", "guccione"}, {"C", 2000.0}};
  SpecNode node(spec, "/material", material_schema());
  const auto m = std::dynamic_pointer_cast<const Guccione>(make_material(node));
  ASSERT_TRUE(m);
  EXPECT_EQ(m->parameters().C, 2000.0);
  EXPECT_EQ(m->parameters().bf, GuccioneParameters{}.bf);
  EXPECT_DOUBLE_EQ(m->stiffness_scale(), 2000.0 * 18.5 + 1.0e5);
}

TEST(MaterialFactory, RejectsNegativeModulusNamingKeyAndValue) {
  const std::string msg = factory_error({{"model", "neo_hookean"}, {"E", -5.0}, {"nu", 0.3}});
  EXPECT_NE(msg.find("/material/E"), std::string::npos) << msg;
  EXPECT_NE(msg.find("-5"), std::string::npos) << msg;
}

TEST(MaterialFactory, RejectsPoissonRatioOfOneHalf) {
  const std::string msg =
      factory_error({{"model", "st_venant_kirchhoff"}, {"E", 1.0e4}, {"nu", 0.5}});
  EXPECT_NE(msg.find("/material/nu"), std::string::npos) << msg;
}

TEST(MaterialFactory, RequiresYoungsModulusForIsotropicLaws) {
  const std::string msg = factory_error({{"model", "neo_hookean"}, {"nu", 0.3}});
  EXPECT_NE(msg.find("/material/E"), std::string::npos) << msg;
}

TEST(MaterialFactory, RejectsNonPositiveGuccioneParameter) {
  const std::string msg = factory_error({{"model", "guccione"}, {"kappa", 0.0}});
  EXPECT_NE(msg.find("/material/kappa"), std::string::npos) << msg;
}

TEST(MaterialFactory, RejectsUnknownModelAndKeys) {
  EXPECT_NE(factory_error({{"model", "neohookean"}}).find("neo_hookean"), std::string::npos);
  // A key of another model is unknown here, not silently ignored.
  const std::string msg = factory_error({{"model", "guccione"}, {"E", 1.0e4}});
  EXPECT_NE(msg.find("unknown key 'E'"), std::string::npos) << msg;
}

}  // namespace
}  // namespace fe2
