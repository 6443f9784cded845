#pragma once
// Builds a Material from its spec object, e.g.
//   {"model": "neo_hookean", "E": 10000, "nu": 0.3}
//   {"model": "guccione", "C": 880, "bf": 18.5, "bt": 3.58, "bfs": 1.63, "kappa": 1e5}
//   {"model": "holzapfel_ogden", "isotropic": "full", "volumetric": "none"}
//   {"model": "holzapfel_ogden", "active": {"model": "land2017"}, "viscosity": 100}
// Every key is read by the <material> schema (common/spec/spec_schemas.cpp: defaults,
// ranges, help) and the node is finished, so unknown keys and
// out-of-range values are InputErrors naming the key.
#include "common/materials/Material.h"
#include "common/spec/SpecNode.h"

#include <string>
#include <vector>

namespace fe2 {

inline const char* const kViscosityHelp =
    "Kelvin-Voigt viscosity eta (Pa s) of the myocardium: S_v = eta dE/dt";

/// Reads "model" and that model's parameters from `node`, then node.finish(). With
/// "active" (a cell model, common/cellmodels/) or "viscosity" > 0 the law is wrapped in
/// a Myocardium (passive + active stress + Kelvin–Voigt); without, it is the bare law.
MaterialPtr make_material(SpecNode& node);

/// The model names make_material accepts, in the order it documents them.
std::vector<std::string> material_models();

}  // namespace fe2
