// `fe2heart spec-schema [--unit]`: the spec schema as JSON Schema 2020-12, from the same
// declarations the readers read every key by (common/spec/spec_schemas.cpp).
#include "common/spec/json_schema.h"
#include "common/spec/spec_schemas.h"
#include "tools/commands.h"

namespace fe2::cli {

int spec_schema(bool unit) {
  const json doc =
      unit ? to_json_schema(unit_spec_schema(), "urn:fe2heart:unit-spec",
                            "fe2heart unit spec (fe2heart unit)")
           : to_json_schema(run_spec_schema(), "urn:fe2heart:run-spec",
                            "fe2heart run spec (fe2heart run, validate)");
  fmt::print("{}\n", doc.dump(2));
  return 0;
}

}  // namespace fe2::cli
