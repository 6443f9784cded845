#pragma once
// Builds a CellModel from its spec object (the "active" key of a material), e.g.
//   {"model": "land2017", "parameter_set": "intact", "calcium": {"peak": 1.2}}
//   {"model": "bestel_clement_sorine", "sigma_0": 1.2e5, "calcium": {"period": 0.8}}
//   {"model": "constant", "Ta": 5e4}
//   {"model": "table", "table": [[0, 0], [0.1, 6e4], [0.4, 0]]}
// Every key is declared on the SpecNode (the same keys as cell_model_schema()) and the
// node is finished, so unknown keys and bad values are InputErrors naming the key.
#include "common/cellmodels/CellModel.h"
#include "common/spec/SpecNode.h"

#include <string>
#include <vector>

namespace fe2 {

/// Reads "model" and that model's keys from `node`, then node.finish().
CellModelPtr make_cell_model(SpecNode& node);

/// A material's "active" object: its cell model and the transverse fraction n_t of the
/// active stress (S_a = T_a [(1 − n_t) f₀⊗f₀ + n_t I], common/materials/active_stress.h).
struct ActiveStressSpec {
  CellModelPtr cell;
  double transverse_fraction = 0.0;
};

/// Reads "transverse_fraction", then the cell model (make_cell_model; finishes the node).
ActiveStressSpec read_active_stress(SpecNode& node);

/// The model names make_cell_model accepts.
std::vector<std::string> cell_model_names();

}  // namespace fe2
