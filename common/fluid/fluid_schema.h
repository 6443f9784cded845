#pragma once
// The schema of a run spec's "fluid" section (coordinator/fluid_spec.h reads it):
// blood on the mesh's fluid regions, its boundary conditions and its mesh motion.
#include "common/spec/SchemaNode.h"

namespace fe2 {

Schema fluid_schema();

}  // namespace fe2
