#pragma once
// Reads a run spec's "fluid" section (common/fluid/fluid_schema.cpp) into the FluidSetup
// the macro scene builds the fluid from (macro/fluid_scene.h). After the mesh, the wall
// regions and the time are read.
#include "common/spec/SpecNode.h"
#include "coordinator/macro/FluidSetup.h"

#include <memory>

namespace fe2 {

struct RunSpec;

/// Null when the spec has no "fluid". Throws InputError naming the key on a region that
/// is also wall, a set the mesh lacks, or an element that does not match the mesh order.
std::shared_ptr<const FluidSetup> read_fluid(SpecNode node, const RunSpec& spec);

}  // namespace fe2
