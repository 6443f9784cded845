// `fe2heart spec-doc`: the reference of spec keys, printed from the spec schemas
// (spec_kinds()) that every read takes its key from, so it lists every key of every
// branch whether or not a shipped config uses it.
#include "common/spec/spec_reference.h"
#include "tools/commands.h"

namespace fe2::cli {

int spec_doc() {
  fmt::print("Every spec key: path, type, default (or required), the branch it belongs to, help.\n"
             "<name>, <region>: free names; <i>: array index. JSON Schema: fe2heart spec-schema.\n\n");
  std::vector<std::pair<std::string, const SchemaNode*>> specs;
  for (const SpecKind& k : spec_kinds()) specs.emplace_back(std::string(k.heading) + ":", k.schema);
  fmt::print("{}", spec_reference(specs));
  return 0;
}

}  // namespace fe2::cli
