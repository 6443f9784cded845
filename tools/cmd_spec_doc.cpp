// `fe2heart spec-doc`: the reference of spec keys, printed from the spec schema
// (common/spec/spec_schemas.cpp) that every read takes its key from, so it lists
// every key of every branch whether or not a shipped config uses it.
#include "common/circulation/circulation_run_spec.h"
#include "common/spec/spec_reference.h"
#include "common/spec/spec_schemas.h"
#include "tools/commands.h"

namespace fe2::cli {

int spec_doc() {
  fmt::print("Every spec key: path, type, default (or required), the branch it belongs to, help.\n"
             "<name>, <region>: free names; <i>: array index. JSON Schema: fe2heart spec-schema.\n\n");
  fmt::print("{}", spec_reference({{"run specs (fe2heart run / validate):", &run_spec_schema()},
                                   {"unit specs (fe2heart unit):", &unit_spec_schema()},
                                   {"circulation specs (fe2heart circulation):", &circulation_run_schema()}}));
  return 0;
}

}  // namespace fe2::cli
