#pragma once
// The schema of a cell-model spec object (cell_model_factory.h), for the run spec's
// material "active" key: a <cell_model> definition with "model" as discriminator. It is
// declared optional.
#include "common/spec/SchemaNode.h"

namespace fe2 {

Schema cell_model_schema();

}  // namespace fe2
