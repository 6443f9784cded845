#pragma once
// The two spec schemas: a run spec (`fe2heart run`, `validate`) and a unit spec
// (`fe2heart unit`). Declared once, in spec_schemas.cpp; the readers (RunSpec.cpp,
// MicroModel.cpp, material_factory.cpp, worker/unit_spec.cpp) read every key by them
// (SpecNode.h).
#include "common/spec/SchemaNode.h"

namespace fe2 {

const SchemaNode& run_spec_schema();
const SchemaNode& unit_spec_schema();
/// The <material> and <unit> definitions, for reading one alone (tests, tools).
const SchemaNode& material_schema();
const SchemaNode& micro_unit_schema();
/// "ramp" of a load or boundary value: linear (value·t/t_end) or constant.
Schema ramp_schema();

}  // namespace fe2
