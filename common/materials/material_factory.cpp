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
  const double E = node.number("E");
  const double nu = node.number("nu");
  return std::make_shared<const Law>(E, nu);
}

/// "volumetric" and "kappa" of a law in the material frame (volumetric.h). A kappa
/// given with "none" is refused: it would be silently ignored.
std::pair<Volumetric, double> read_volumetric(SpecNode& node) {
  const Volumetric v = volumetric_from_name(node.choice("volumetric"));
  if (v == Volumetric::none && node.has("kappa"))
    node.fail("kappa", "no kappa with volumetric = \"none\" (there is no penalty term)");
  const double kappa = node.number("kappa");
  return {v, kappa};
}

MaterialPtr make_guccione(SpecNode& node) {
  GuccioneParameters p;
  p.C = node.number("C");
  p.bf = node.number("bf");
  p.bt = node.number("bt");
  p.bfs = node.number("bfs");
  std::tie(p.volumetric, p.kappa) = read_volumetric(node);
  return std::make_shared<const Guccione>(p);
}

MaterialPtr make_holzapfel_ogden(SpecNode& node) {
  HolzapfelOgdenParameters p;
  p.a = node.number("a");
  p.b = node.number("b");
  p.af = node.number("af");
  p.bf = node.number("bf");
  p.as = node.number("as");
  p.bs = node.number("bs");
  p.afs = node.number("afs");
  p.bfs = node.number("bfs");
  p.isotropic = node.choice("isotropic") == "full"
                    ? IsotropicInvariant::full
                    : IsotropicInvariant::isochoric;
  std::tie(p.volumetric, p.kappa) = read_volumetric(node);
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
  const std::string model = node.choice("model");
  MaterialPtr material;
  for (const auto& m : models())
    if (model == m.name) material = m.build(node);
  MyocardiumOptions myocardium;
  if (node.has("active")) {
    SpecNode active = node.child("active");
    ActiveStressSpec a = read_active_stress(active);
    myocardium.cell = std::move(a.cell);
    myocardium.transverse_fraction = a.transverse_fraction;
  }
  myocardium.viscosity = node.number("viscosity");
  node.finish();
  // Nothing asked, nothing wrapped: a passive heart keeps the bare law (and its
  // symmetric tangent, Cholesky path).
  if (!myocardium.cell && myocardium.viscosity == 0.0) return material;
  return std::make_shared<const Myocardium>(material, std::move(myocardium));
}

}  // namespace fe2
