#pragma once
// A spec schema (SchemaNode.h) as a JSON Schema 2020-12 document, for editors and
// validators: `fe2heart spec-schema` prints it. Objects are closed
// (additionalProperties false); an object with a discriminator is a oneOf with one
// closed branch per value; shared definitions (material, unit) go to $defs.
#include "common/spec/SchemaNode.h"

#include <string>

namespace fe2 {

/// `id` is the document's $id, `title` its title.
json to_json_schema(const SchemaNode& root, const std::string& id, const std::string& title);

}  // namespace fe2
