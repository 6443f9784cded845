#pragma once
// The schema of the run spec's "activation" object (activation_spec.h reads exactly
// these keys); the lead's spec_schemas.cpp puts it under the top-level "activation".
#include "common/spec/SchemaNode.h"

namespace fe2 {

Schema activation_schema();
/// The object form of "velocity" (a custom key: a number or this object), with the
/// defaults of an absent velocity.
const SchemaNode& velocity_object_schema();

}  // namespace fe2
