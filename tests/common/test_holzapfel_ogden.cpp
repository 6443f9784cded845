// Holzapfel–Ogden (common/materials/HolzapfelOgden.h) and the volumetric option of the
// laws in the material frame: 𝔸 = FD of Π and Π = FD of W at general deformations
// with fibres and sheets in tension and in compression, no fibre stress in fibre
// compression (exactly the law with a_f = 0), the reference state, the small-strain
// limit against the linearized law, and Guccione without its volumetric term.
#include "common/materials/Guccione.h"
#include "common/spec/spec_schemas.h"
#include "common/materials/HolzapfelOgden.h"
#include "common/materials/material_factory.h"
#include "tests/common/material_finite_differences.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace fe2 {
namespace {

using testing::fd_stress;
using testing::fd_tangent;

struct Variant {
  std::string label;
  HolzapfelOgdenParameters p;
};

std::vector<Variant> variants() {
  Variant dflt{"isochoric_penalty", {}};
  Variant none{"isochoric_none", {}};
  none.p.volumetric = Volumetric::none;
  Variant full{"full_none", {}};
  full.p.isotropic = IsotropicInvariant::full;
  full.p.volumetric = Volumetric::none;
  return {dflt, none, full};
}

/// Z = F − I of a row-major 3x3 F.
Vec9 Z_of(std::initializer_list<double> F_rows) {
  Mat3 F;
  auto it = F_rows.begin();
  for (int i = 0; i < 3; ++i)
    for (int J = 0; J < 3; ++J) F(i, J) = *it++;
  return as_vec9(F - Mat3::Identity());
}

struct Deformation {
  std::string label;
  Vec9 Z;
  bool fibre_tension, sheet_tension;
};

/// General deformations (all nine entries of F nonzero off the diagonal somewhere),
/// one per tension/compression combination of fibre and sheet.
std::vector<Deformation> deformations() {
  return {
      {"fibre_tension_sheet_compression",
       Z_of({1.15, 0.05, -0.03, 0.04, 0.93, 0.06, -0.02, 0.03, 0.95}), true, false},
      {"fibre_compression_sheet_tension",
       Z_of({0.88, 0.06, 0.02, 0.03, 1.12, -0.05, 0.05, 0.02, 1.02}), false, true},
      {"both_tension", Z_of({1.10, 0.10, 0.0, -0.05, 1.08, 0.04, 0.02, -0.03, 0.86}), true, true},
      {"both_compression", Z_of({0.90, 0.08, 0.03, 0.02, 0.92, 0.10, -0.04, 0.05, 1.20}), false,
       false},
  };
}

double I4(const Vec9& Z, int i) {
  const Mat3 F = Mat3::Identity() + as_mat3(Z);
  return (F.transpose() * F)(i, i);
}

TEST(HolzapfelOgden, DeformationsAreInTheStatedTensionOrCompression) {
  for (const auto& d : deformations()) {
    EXPECT_EQ(I4(d.Z, 0) > 1.0, d.fibre_tension) << d.label << " I4f = " << I4(d.Z, 0);
    EXPECT_EQ(I4(d.Z, 1) > 1.0, d.sheet_tension) << d.label << " I4s = " << I4(d.Z, 1);
    // Far enough from the kink at I4 = 1 for a central difference of step 1e-6.
    EXPECT_GT(std::abs(I4(d.Z, 0) - 1.0), 0.05);
    EXPECT_GT(std::abs(I4(d.Z, 1) - 1.0), 0.05);
  }
}

TEST(HolzapfelOgden, TangentEqualsFiniteDifferencesOfStress) {
  for (const auto& v : variants()) {
    const HolzapfelOgden law(v.p);
    for (const auto& d : deformations()) {
      const Mat9 A = law.tangent(d.Z);
      const Mat9 A_fd = fd_tangent(law, d.Z, 1e-6);
      EXPECT_LE((A - A_fd).norm(), 1e-6 * A.norm())
          << v.label << " " << d.label << "\nA - A_fd\n" << A - A_fd;
      EXPECT_LE((A - A.transpose()).norm(), 1e-13 * A.norm()) << v.label << " " << d.label;
    }
  }
}

TEST(HolzapfelOgden, StressEqualsFiniteDifferencesOfEnergy) {
  for (const auto& v : variants()) {
    const HolzapfelOgden law(v.p);
    for (const auto& d : deformations()) {
      const Vec9 Pi = law.stress(d.Z);
      const Vec9 Pi_fd = fd_stress(law, d.Z, 1e-6);
      EXPECT_LE((Pi - Pi_fd).norm(), 1e-7 * Pi.norm())
          << v.label << " " << d.label << "\nPi    " << Pi.transpose() << "\nPi_fd "
          << Pi_fd.transpose();
    }
  }
}

/// Uniaxial stretch λ along axis `i`, the two lateral axes at 1/√λ (isochoric).
Vec9 uniaxial(int i, double lambda) {
  Mat3 F = Mat3::Identity() / std::sqrt(lambda);
  F(i, i) = lambda;
  return as_vec9(F - Mat3::Identity());
}

/// W, Π and 𝔸 agree bit for bit.
void expect_identical(const Material& a, const Material& b, const Vec9& Z, const std::string& what) {
  Vec9 Pa, Pb;
  Mat9 Aa, Ab;
  a.stress_and_tangent(Z, Pa, Aa);
  b.stress_and_tangent(Z, Pb, Ab);
  EXPECT_EQ(a.energy(Z), b.energy(Z)) << what;
  EXPECT_TRUE(Pa == Pb) << what << "\n" << (Pa - Pb).transpose();
  EXPECT_TRUE(Aa == Ab) << what << "\n" << Aa - Ab;
}

TEST(HolzapfelOgden, FibresAndSheetsInCompressionCarryNoStress) {
  for (const auto& v : variants()) {
    HolzapfelOgdenParameters no_fibre = v.p, no_sheet = v.p;
    no_fibre.af = 0.0;
    no_sheet.as = 0.0;
    const HolzapfelOgden law(v.p), law_no_fibre(no_fibre), law_no_sheet(no_sheet);
    // Compressed along the fibre (sheet stretched laterally): the fibre term adds
    // exactly nothing, so the law equals the one without it, bit for bit.
    expect_identical(law, law_no_fibre, uniaxial(0, 0.85), v.label + " fibre compression");
    expect_identical(law, law_no_sheet, uniaxial(1, 0.85), v.label + " sheet compression");
    for (const auto& d : deformations()) {
      if (!d.fibre_tension) expect_identical(law, law_no_fibre, d.Z, v.label + " " + d.label);
      if (!d.sheet_tension) expect_identical(law, law_no_sheet, d.Z, v.label + " " + d.label);
    }
    // Control: stretched along the fibre, the fibre term is there (Π₁₁ grows by
    // more than a_f · 0.1), so the comparison above can fail.
    const Vec9 Z = uniaxial(0, 1.05);
    EXPECT_GT(law.stress(Z)(index9(0, 0)) - law_no_fibre.stress(Z)(index9(0, 0)), 0.1 * v.p.af)
        << v.label;
    const Vec9 Zs = uniaxial(1, 1.05);
    EXPECT_GT(law.stress(Zs)(index9(1, 1)) - law_no_sheet.stress(Zs)(index9(1, 1)), 0.1 * v.p.as)
        << v.label;
  }
}

TEST(HolzapfelOgden, ReferenceStateIsStressFreeExceptTheFullInvariantsPressure) {
  const Vec9 zero = Vec9::Zero();
  for (const auto& v : variants()) {
    const HolzapfelOgden law(v.p);
    EXPECT_EQ(law.energy(zero), 0.0) << v.label;
    const Mat3 Pi = as_mat3(law.stress(zero));
    if (v.p.isotropic == IsotropicInvariant::isochoric) {
      EXPECT_LE(Pi.norm(), 1e-12 * law.stiffness_scale()) << v.label << "\n" << Pi;
    } else {
      // S = 2ψ'(3) I = a I: the pure pressure the mixed formulation's p takes up.
      EXPECT_LE((Pi - v.p.a * Mat3::Identity()).norm(), 1e-12 * v.p.a) << v.label << "\n" << Pi;
    }
  }
}

/// The linearized law at E = 0 written out on indices (header comment):
/// ℂ = 2a(𝕀 − ⅓ I⊗I) + κ I⊗I + 4a_fs G⊗G, G = ½(f⊗s + s⊗f); in tension along the
/// fibre (sheet) the one-sided modulus adds 4a_f (4a_s) to ℂ₁₁₁₁ (ℂ₂₂₂₂).
Mat9 linearized_tangent(const HolzapfelOgdenParameters& p, double fibre_side, double sheet_side) {
  auto d = [](int a, int b) { return a == b ? 1.0 : 0.0; };
  const double kappa = p.volumetric == Volumetric::penalty ? p.kappa : 0.0;
  Mat3 G = Mat3::Zero();
  G(0, 1) = G(1, 0) = 0.5;
  Mat9 A;
  for (int i = 0; i < 3; ++i)
    for (int J = 0; J < 3; ++J)
      for (int k = 0; k < 3; ++k)
        for (int L = 0; L < 3; ++L) {
          const double sym = 0.5 * (d(i, k) * d(J, L) + d(i, L) * d(J, k));
          double c = 2 * p.a * (sym - d(i, J) * d(k, L) / 3) + kappa * d(i, J) * d(k, L) +
                     4 * p.afs * G(i, J) * G(k, L);
          if (i == 0 && J == 0 && k == 0 && L == 0) c += fibre_side * 4 * p.af;
          if (i == 1 && J == 1 && k == 1 && L == 1) c += sheet_side * 4 * p.as;
          A(index9(i, J), index9(k, L)) = c;
        }
  return A;
}

TEST(HolzapfelOgden, SmallStrainLimitIsTheLinearizedLaw) {
  for (const auto& v : variants()) {
    if (v.p.isotropic != IsotropicInvariant::isochoric) continue;  // not stress free
    const HolzapfelOgden law(v.p);
    // At E = 0 exactly (I4 = 1) the tangent takes the tension side (header comment).
    const Mat9 A0 = law.tangent(Vec9::Zero());
    const Mat9 expected = linearized_tangent(v.p, 1, 1);
    EXPECT_LE((A0 - expected).norm(), 1e-12 * expected.norm()) << v.label << "\n" << A0 - expected;
    // One-sided difference quotients along Z₁₁ and Z₂₂: the tension side adds the
    // fibre (sheet) modulus 4a_f (4a_s), the compression side does not.
    const double eps = 1e-7;
    for (int i = 0; i < 2; ++i) {
      const int col = index9(i, i);
      for (const double side : {+1.0, -1.0}) {
        Vec9 Z = Vec9::Zero();
        Z(col) = side * eps;
        const Vec9 slope = (law.stress(Z) - law.stress(Vec9::Zero())) / (side * eps);
        const double t = side > 0 ? 1.0 : 0.0;
        const Vec9 expected_col = linearized_tangent(v.p, i == 0 ? t : 0, i == 1 ? t : 0).col(col);
        EXPECT_LE((slope - expected_col).norm(), 1e-5 * expected_col.norm())
            << v.label << " axis " << i << " side " << side << "\n"
            << slope.transpose() << "\n"
            << expected_col.transpose();
      }
    }
  }
}

TEST(HolzapfelOgden, EnergyIsFrameIndifferentAndFibreStiffest) {
  const HolzapfelOgden law(HolzapfelOgdenParameters{});
  const Mat3 R = Eigen::AngleAxisd(1.1, Vec3(0.3, -1, 2).normalized()).toRotationMatrix();
  for (const auto& d : deformations()) {
    const Vec9 Z_rotated = as_vec9(R * (Mat3::Identity() + as_mat3(d.Z)) - Mat3::Identity());
    EXPECT_NEAR(law.energy(Z_rotated), law.energy(d.Z), 1e-12 * law.energy(d.Z)) << d.label;
    const Mat3 Pi_expected = R * as_mat3(law.stress(d.Z));
    EXPECT_LE((as_mat3(law.stress(Z_rotated)) - Pi_expected).norm(), 1e-12 * Pi_expected.norm());
  }
  // Orthotropy: the same stretch costs more along f than along s, more along s than n.
  const double Wf = law.energy(uniaxial(0, 1.1)), Ws = law.energy(uniaxial(1, 1.1)),
               Wn = law.energy(uniaxial(2, 1.1));
  EXPECT_GT(Wf, 2 * Ws);
  EXPECT_GT(Ws, 2 * Wn);
}

TEST(HolzapfelOgden, OverflowAndInversionAreNumericalErrors) {
  const HolzapfelOgden law(HolzapfelOgdenParameters{});
  Vec9 Pi;
  Mat9 A;
  const Vec9 huge = uniaxial(0, 10.0);  // b_f (I4f − 1)² ≈ 1.6e5: e^… overflows
  EXPECT_THROW(law.energy(huge), NumericalError);
  EXPECT_THROW(law.stress_and_tangent(huge, Pi, A), NumericalError);
  Vec9 reflected = Vec9::Zero();
  reflected(index9(0, 0)) = -2.0;
  EXPECT_THROW(law.stress_and_tangent(reflected, Pi, A), NumericalError);
}

TEST(HolzapfelOgden, ConstructorRejectsNonPhysicalParameters) {
  auto rejects = [](auto change, const std::string& text) {
    HolzapfelOgdenParameters p;
    change(p);
    try {
      HolzapfelOgden law(p);
      ADD_FAILURE() << "accepted: " << text;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
    }
  };
  rejects([](auto& p) { p.a = 0.0; }, "parameter a = 0, expected > 0");
  rejects([](auto& p) { p.af = -1.0; }, "parameter af = -1, expected >= 0");
  rejects([](auto& p) { p.bfs = 0.0; }, "parameter bfs = 0, expected > 0");
  rejects([](auto& p) { p.kappa = 0.0; }, "parameter kappa = 0, expected > 0");
  rejects([](auto& p) { p.isotropic = IsotropicInvariant::full; },
          "isotropic = full needs volumetric = none");
  HolzapfelOgdenParameters none;
  none.volumetric = Volumetric::none;
  none.kappa = 0.0;  // unused without the penalty
  EXPECT_NO_THROW(HolzapfelOgden{none});
  EXPECT_DOUBLE_EQ(HolzapfelOgden{none}.stiffness_scale(), 2 * 59.0 + 4 * 18472.0);
}

TEST(GuccioneVolumetric, NoneDiffersFromTheDefaultExactlyByThePenalty) {
  const GuccioneParameters dflt;
  GuccioneParameters none;
  none.volumetric = Volumetric::none;
  const Guccione with(dflt), without(none);
  EXPECT_DOUBLE_EQ(with.stiffness_scale() - without.stiffness_scale(), dflt.kappa);
  // Π_vol = U'(J) ∂J/∂F = κ(J − 1) J F⁻ᵀ, written on F (not on S as the law does).
  auto Pi_vol = [&](const Vec9& Z) {
    const Mat3 F = Mat3::Identity() + as_mat3(Z);
    const double J = F.determinant();
    return as_vec9(dflt.kappa * (J - 1) * J * F.inverse().transpose());
  };
  for (const auto& d : deformations()) {
    const Mat3 F = Mat3::Identity() + as_mat3(d.Z);
    const double J = F.determinant();
    EXPECT_NEAR(with.energy(d.Z) - without.energy(d.Z), 0.5 * dflt.kappa * (J - 1) * (J - 1),
                1e-12 * with.energy(d.Z))
        << d.label;
    const Vec9 dPi = with.stress(d.Z) - without.stress(d.Z);
    EXPECT_LE((dPi - Pi_vol(d.Z)).norm(), 1e-12 * with.stress(d.Z).norm()) << d.label;
    // 𝔸_vol by central differences of the closed-form Π_vol.
    Mat9 A_vol;
    for (int b = 0; b < 9; ++b) {
      Vec9 Zp = d.Z, Zm = d.Z;
      Zp(b) += 1e-6;
      Zm(b) -= 1e-6;
      A_vol.col(b) = (Pi_vol(Zp) - Pi_vol(Zm)) / 2e-6;
    }
    const Mat9 dA = with.tangent(d.Z) - without.tangent(d.Z);
    EXPECT_LE((dA - A_vol).norm(), 1e-6 * A_vol.norm()) << d.label << "\n" << dA - A_vol;
    // and without the penalty the law is FD-consistent on its own.
    EXPECT_LE((without.tangent(d.Z) - fd_tangent(without, d.Z, 1e-6)).norm(),
              1e-6 * without.tangent(d.Z).norm())
        << d.label;
  }
  // No penalty: a pure volume change of the fibre frame costs only C/2 (e^Q − 1).
  const Vec9 dilation = as_vec9(0.02 * Mat3::Identity());
  const double E = 0.5 * (1.02 * 1.02 - 1);
  const double Q = (dflt.bf + 2 * dflt.bt) * E * E;
  EXPECT_NEAR(without.energy(dilation), 0.5 * dflt.C * std::expm1(Q), 1e-12 * dflt.C);
}

/// make_material on `spec` at "/material"; the InputError's message or "".
std::string factory_error(const json& spec) {
  try {
    SpecNode node(spec, "/material", material_schema());
    make_material(node);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(HolzapfelOgdenFactory, DefaultsAreHolzapfelOgden2009Table1InPascal) {
  const json spec = {{"model", "holzapfel_ogden"}};  // SpecNode holds a pointer: a named json
  SpecNode node(spec, "/material", material_schema());
  const auto m = std::dynamic_pointer_cast<const HolzapfelOgden>(make_material(node));
  ASSERT_TRUE(m);
  const HolzapfelOgdenParameters& p = m->parameters();
  EXPECT_EQ(p.a, 59.0);
  EXPECT_EQ(p.b, 8.023);
  EXPECT_EQ(p.af, 18472.0);
  EXPECT_EQ(p.bf, 16.026);
  EXPECT_EQ(p.as, 2481.0);
  EXPECT_EQ(p.bs, 11.12);
  EXPECT_EQ(p.afs, 216.0);
  EXPECT_EQ(p.bfs, 11.436);
  EXPECT_EQ(p.kappa, 1.0e5);
  EXPECT_EQ(p.isotropic, IsotropicInvariant::isochoric);
  EXPECT_EQ(p.volumetric, Volumetric::penalty);
}

TEST(HolzapfelOgdenFactory, ReadsEveryKey) {
  const json spec = {{"model", "holzapfel_ogden"}, {"a", 100}, {"b", 5}, {"af", 0}, {"bf", 10},
                     {"as", 0},  {"bs", 3},   {"afs", 0},  {"bfs", 2},  {"isotropic", "full"},
                     {"volumetric", "none"}};
  SpecNode node(spec, "/material", material_schema());
  const auto m = std::dynamic_pointer_cast<const HolzapfelOgden>(make_material(node));
  ASSERT_TRUE(m);
  EXPECT_EQ(m->parameters().a, 100.0);
  EXPECT_EQ(m->parameters().af, 0.0);
  EXPECT_EQ(m->parameters().bfs, 2.0);
  EXPECT_EQ(m->parameters().isotropic, IsotropicInvariant::full);
  EXPECT_EQ(m->parameters().volumetric, Volumetric::none);
  const json guccione = {{"model", "guccione"}, {"volumetric", "none"}};
  SpecNode g(guccione, "/material", material_schema());
  const auto gm = std::dynamic_pointer_cast<const Guccione>(make_material(g));
  ASSERT_TRUE(gm);
  EXPECT_EQ(gm->parameters().volumetric, Volumetric::none);
}

TEST(HolzapfelOgdenFactory, BadValuesNameTheKey) {
  std::string msg = factory_error({{"model", "holzapfel_ogden"}, {"af", -1.0}});
  EXPECT_NE(msg.find("/material/af"), std::string::npos) << msg;
  EXPECT_NE(msg.find("-1"), std::string::npos) << msg;
  msg = factory_error({{"model", "holzapfel_ogden"}, {"b", 0}});
  EXPECT_NE(msg.find("/material/b"), std::string::npos) << msg;
  msg = factory_error({{"model", "holzapfel_ogden"}, {"isotropic", "deviatoric"}});
  EXPECT_NE(msg.find("/material/isotropic"), std::string::npos) << msg;
  EXPECT_NE(msg.find("isochoric"), std::string::npos) << msg;
  // A penalty given where there is none would be silently ignored: refused.
  for (const char* model : {"guccione", "holzapfel_ogden"}) {
    msg = factory_error({{"model", model}, {"volumetric", "none"}, {"kappa", 1e5}});
    EXPECT_NE(msg.find("/material/kappa"), std::string::npos) << msg;
    EXPECT_NE(msg.find("volumetric = \"none\""), std::string::npos) << msg;
  }
  // The full I1 has a reference stress a I: only with a mixed formulation's pressure.
  msg = factory_error({{"model", "holzapfel_ogden"}, {"isotropic", "full"}});
  EXPECT_NE(msg.find("/material/isotropic: got \"full\""), std::string::npos) << msg;
  EXPECT_NE(msg.find("volumetric = \"none\""), std::string::npos) << msg;
  msg = factory_error({{"model", "guccione"}, {"volumetric", "mixed"}});
  EXPECT_NE(msg.find("/material/volumetric"), std::string::npos) << msg;
}

}  // namespace
}  // namespace fe2
