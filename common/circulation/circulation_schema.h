#pragma once
// The schema of a circulation spec object (circulation_factory.h): a <circulation>
// definition with "kind" as discriminator, declared optional (the run spec reads it with
// node.child("circulation"); the standalone spec makes it required).
#include "common/spec/SchemaNode.h"

namespace fe2 {

Schema circulation_schema();

}  // namespace fe2
