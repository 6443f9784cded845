#pragma once
// The spec of a standalone circulation run (`fe2heart circulation SPEC --out DIR`):
//   {"title": "...",
//    "circulation": {<circulation>},
//    "ventricles": {"lv": {E_min, E_max, V0, V_init, onset, contraction, relaxation}, "rv": {...}},
//    "time": {"beats": 5, "steps_per_beat": 400}   or   {"t_end": 2.4, "steps": 1200}}
// One elastance ventricle per cavity of the circulation stands in for the wall.
#include "common/circulation/Circulation.h"
#include "common/circulation/ElastanceVentricle.h"
#include "common/spec/SchemaNode.h"

#include <string>
#include <vector>

namespace fe2 {

struct CirculationRunSpec {
  std::string title;
  CirculationPtr circulation;
  std::vector<ElastanceVentricle> ventricles;  ///< per cavity of the circulation
  int beats = 0;        ///< 0: the run is t_end long instead
  double t_end = 0.0;   ///< s
  int steps = 0;        ///< total
  double dt() const { return t_end / steps; }
};

/// True for a standalone circulation spec (it has "ventricles", or a "circulation"
/// without a "mesh").
bool is_circulation_run_spec(const json& j);

/// Reads and checks a standalone spec by circulation_run_schema(); `doc` as in SpecNode.
CirculationRunSpec read_circulation_run_spec(const json& j, const std::string& file,
                                             SpecDoc* doc = nullptr);

/// The root schema of standalone circulation specs.
const SchemaNode& circulation_run_schema();

}  // namespace fe2
