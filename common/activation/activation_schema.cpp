// The "activation" object's keys, as common/activation/activation_spec.cpp reads them.
#include "common/activation/activation_schema.h"

#include "common/activation/activation_spec.h"

namespace fe2 {

const SchemaNode& velocity_object_schema() {
  using namespace schema;
  static const Schema s = object(
      false, "conduction velocity per direction (mesh length units per second)",
      {{"fibre", number(kDefaultVelocityFibre, Range::positive(), "velocity along the fibres")},
       {"sheet", number(kDefaultVelocitySheet, Range::positive(), "velocity along the sheets")},
       {"normal", number(kDefaultVelocityNormal, Range::positive(), "velocity along the sheet normals")}});
  return *s;
}

namespace {

Schema make_activation_schema() {
  using namespace schema;
  using std::nullopt;
  const json positive = {{"type", "number"}, {"exclusiveMinimum", 0}};
  const json velocity = {
      {"oneOf",
       {positive,
        {{"type", "object"},
         {"properties", {{"fibre", positive}, {"sheet", positive}, {"normal", positive}}},
         {"additionalProperties", false}}}}};
  const Schema source = exactly_one_of(
      {"surface", "point"},
      object(true, "a source",
             {{"surface", optional(string(nullopt, "named surface of the mesh whose vertices start"))},
              {"point", optional(numbers(3, nullopt, "a point [x, y, z]: its nearest mesh vertex starts"))},
              {"time", number(0.0, Range::non_negative(), "activation time of the source (s)")}}));
  return object(
      false, "activation time of every material point (when its calcium transient starts)",
      {{"kind", choice("uniform", {"uniform", "eikonal", "file"},
                       "how activation times are given: one time, an eikonal front, or a file")}},
      "kind",
      {{"uniform", {{"time", number(0.0, Range::non_negative(), "activation time of every point (s)")}}},
       {"eikonal",
        {{"sources", array(true, "where the front starts: named surfaces or points, each with a time", source, 1)},
         {"velocity", custom("number > 0 or object {fibre, sheet, normal}",
                             "conduction velocity (mesh length units per second): one number (isotropic) or "
                             "{fibre, sheet, normal}; default {670, 300, 170} mm/s (Caldwell et al. 2009)",
                             velocity)}}},
       {"file",
        {{"file", string(nullopt, "activation file: a Gmsh MSH 4.1 view or CSV")},
         {"format", choice("gmsh", {"gmsh", "csv"}, "gmsh: an $ElementData view; csv: lines tag,time")},
         {"view", string("activation", "name of the Gmsh $ElementData view of activation times (s)")}}}});
}

}  // namespace

Schema activation_schema() {
  static const Schema s = make_activation_schema();
  return s;
}

}  // namespace fe2
