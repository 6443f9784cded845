#pragma once
// The two spec schemas: a run spec (`fe2heart run`, `validate`) and a unit spec
// (`fe2heart unit`). Declared once, in spec_schemas.cpp; the readers (RunSpec.cpp,
// MicroModel.cpp, material_factory.cpp, tools/unit_spec.cpp) are checked against them
// key by key (SchemaNode.h).
#include "common/spec/SchemaNode.h"

namespace fe2 {

const SchemaNode& run_spec_schema();
const SchemaNode& unit_spec_schema();

}  // namespace fe2
