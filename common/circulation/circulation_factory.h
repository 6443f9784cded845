#pragma once
// Builds a Circulation from its spec object (the "circulation" key), e.g.
//   {"kind": "windkessel", "cavities": {"lv": {"preload": {"pressure": 1333},
//        "outflow_valve": {"R_open": 1e-3}, "windkessel": {"Rp": 0.13, "C": 1.1e4}}}}
//   {"kind": "closed_loop", "cavities": {"lv": {}, "rv": {}}, "systemic": {"R_ar": 0.1}}
// Every key is declared on the SpecNode (the same tables as circulation_schema(), from
// circulation_keys.h) and each node is finished, so unknown keys and bad values are
// InputErrors naming the key. Defaults: circulation_keys.h (human, with sources).
#include "common/circulation/Circulation.h"
#include "common/circulation/TimeVaryingElastance.h"
#include "common/spec/SpecNode.h"

namespace fe2 {

/// Reads "kind", "period" and that kind's keys from `node`, then node.finish().
std::shared_ptr<const Circulation> make_circulation(SpecNode& node);

/// Reads the keys of one time-varying elastance (circulation_keys::elastance_keys())
/// (defaults from the node's schema), checks E_max >= E_min and that onset and T_C + T_R fit in
/// `period` (the caller finishes the node).
ElastanceParameters read_elastance(SpecNode& node, double period);

}  // namespace fe2
