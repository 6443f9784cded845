#include "common/materials/material_factory.h"

#include "common/materials/Guccione.h"
#include "common/materials/HolzapfelOgden.h"
#include "common/materials/Myocardium.h"
#include "common/cellmodels/cell_model_factory.h"
#include "common/cellmodels/cell_model_keys.h"
#include "common/materials/NeoHookean.h"
#include "common/materials/StVenantKirchhoff.h"

#include <functional>
#include <tuple>

namespace fe2 {
namespace {

/// E and ν of an isotropic law, both required: there is no sensible default tissue.
template <class Law>
MaterialPtr make_isotropic(SpecNode& node) {
  // −1 < ν < ½ is where the small-strain tensor is positive definite.
  const Range poisson{-1.0, 0.5, true, true};
  const double E = node.number("E", std::nullopt, Range::positive(), "Young's modulus (Pa)");
  const double nu = node.number("nu", std::nullopt, poisson, "Poisson's ratio");
  return std::make_shared<const Law>(E, nu);
}

/// "volumetric" and "kappa" of a law in the material frame (volumetric.h). A kappa
/// given with "none" is refused: it would be silently ignored.
std::pair<Volumetric, double> read_volumetric(SpecNode& node, double default_kappa) {
  const std::vector<std::string> names(kVolumetricNames.begin(), kVolumetricNames.end());
  const Volumetric v = volumetric_from_name(node.choice(
      "volumetric", names[0], names,
      "volumetric energy: penalty U = kappa/2 (J-1)^2, or none (a mixed formulation's "
      "pressure enforces J = 1)"));
  if (v == Volumetric::none && node.has("kappa"))
    node.fail("kappa", "no kappa with volumetric = \"none\" (there is no penalty term)");
  const double kappa = node.number("kappa", default_kappa, Range::positive(),
                                   "volumetric penalty kappa (Pa), U = kappa/2 (J-1)^2");
  return {v, kappa};
}

MaterialPtr make_guccione(SpecNode& node) {
  const GuccioneParameters d;  // defaults: Guccione et al. 1991, see Guccione.h
  GuccioneParameters p;
  p.C = node.number("C", d.C, Range::positive(), "stiffness scale C (Pa)");
  p.bf = node.number("bf", d.bf, Range::positive(), "fibre exponent b_f");
  p.bt = node.number("bt", d.bt, Range::positive(), "transverse exponent b_t");
  p.bfs = node.number("bfs", d.bfs, Range::positive(), "fibre-shear exponent b_fs");
  std::tie(p.volumetric, p.kappa) = read_volumetric(node, d.kappa);
  return std::make_shared<const Guccione>(p);
}

MaterialPtr make_holzapfel_ogden(SpecNode& node) {
  const HolzapfelOgdenParameters d;  // defaults: Holzapfel & Ogden 2009, Table 1
  HolzapfelOgdenParameters p;
  const Range positive = Range::positive(), non_negative = Range::non_negative();
  p.a = node.number("a", d.a, positive, "isotropic modulus a (Pa)");
  p.b = node.number("b", d.b, positive, "isotropic exponent b");
  p.af = node.number("af", d.af, non_negative, "fibre modulus a_f (Pa), acts in fibre tension only");
  p.bf = node.number("bf", d.bf, positive, "fibre exponent b_f");
  p.as = node.number("as", d.as, non_negative, "sheet modulus a_s (Pa), acts in sheet tension only");
  p.bs = node.number("bs", d.bs, positive, "sheet exponent b_s");
  p.afs = node.number("afs", d.afs, non_negative, "fibre-sheet coupling modulus a_fs (Pa)");
  p.bfs = node.number("bfs", d.bfs, positive, "fibre-sheet coupling exponent b_fs");
  const std::vector<std::string> iso(kIsotropicInvariantNames.begin(),
                                     kIsotropicInvariantNames.end());
  p.isotropic = node.choice("isotropic", iso[0], iso,
                            "invariant of the isotropic term: isochoric J^(-2/3) I1 (stress-free "
                            "reference) or full I1 (reference stress a I, for a mixed "
                            "formulation)") == "full"
                    ? IsotropicInvariant::full
                    : IsotropicInvariant::isochoric;
  std::tie(p.volumetric, p.kappa) = read_volumetric(node, d.kappa);
  if (p.isotropic == IsotropicInvariant::full && p.volumetric == Volumetric::penalty)
    node.fail("isotropic", "\"isochoric\", or volumetric = \"none\" with \"full\" (the full I1 "
                           "has the reference stress a I, which only a mixed formulation's "
                           "pressure takes up)");
  return std::make_shared<const HolzapfelOgden>(p);
}

struct Model {
  const char* name;
  std::function<MaterialPtr(SpecNode&)> build;
};

const std::vector<Model>& models() {
  static const std::vector<Model> table = {
      {NeoHookean::kName, make_isotropic<NeoHookean>},
      {StVenantKirchhoff::kName, make_isotropic<StVenantKirchhoff>},
      {Guccione::kName, make_guccione},
      {HolzapfelOgden::kName, make_holzapfel_ogden},
  };
  return table;
}

}  // namespace

std::vector<std::string> material_models() {
  std::vector<std::string> names;
  for (const auto& m : models()) names.emplace_back(m.name);
  return names;
}

MaterialPtr make_material(SpecNode& node) {
  const std::string model =
      node.choice("model", std::nullopt, material_models(), "constitutive law");
  MaterialPtr material;
  for (const auto& m : models())
    if (model == m.name) material = m.build(node);
  MyocardiumOptions myocardium;
  if (node.has("active")) {
    SpecNode active = node.child("active", false, cell_keys::kModelHelp);
    ActiveStressSpec a = read_active_stress(active);
    myocardium.cell = std::move(a.cell);
    myocardium.transverse_fraction = a.transverse_fraction;
  }
  myocardium.viscosity = node.number("viscosity", 0.0, Range::non_negative(), kViscosityHelp);
  node.finish();
  // Nothing asked, nothing wrapped: a passive heart keeps the bare law (and its
  // symmetric tangent, Cholesky path).
  if (!myocardium.cell && myocardium.viscosity == 0.0) return material;
  return std::make_shared<const Myocardium>(material, std::move(myocardium));
}

}  // namespace fe2
