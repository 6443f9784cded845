#include "common/materials/material_factory.h"

#include "common/materials/Guccione.h"
#include "common/materials/NeoHookean.h"
#include "common/materials/StVenantKirchhoff.h"

#include <functional>

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

MaterialPtr make_guccione(SpecNode& node) {
  const GuccioneParameters d;  // defaults: Guccione et al. 1991, see Guccione.h
  GuccioneParameters p;
  p.C = node.number("C", d.C, Range::positive(), "stiffness scale C (Pa)");
  p.bf = node.number("bf", d.bf, Range::positive(), "fibre exponent b_f");
  p.bt = node.number("bt", d.bt, Range::positive(), "transverse exponent b_t");
  p.bfs = node.number("bfs", d.bfs, Range::positive(), "fibre-shear exponent b_fs");
  p.kappa = node.number("kappa", d.kappa, Range::positive(),
                        "volumetric penalty kappa (Pa), U = kappa/2 (J-1)^2");
  return std::make_shared<const Guccione>(p);
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
  node.finish();
  return material;
}

}  // namespace fe2
