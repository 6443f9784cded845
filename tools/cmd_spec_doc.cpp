// `fe2heart spec-doc`: the reference of spec keys, printed from the spec schemas
// (spec_kinds()) that every read takes its key from, so it lists every key of every
// branch whether or not a shipped config uses it.
#include "common/spec/spec_reference.h"
#include "tools/commands.h"

#include <cctype>

namespace fe2::cli {

int spec_doc(bool markdown) {
  if (markdown)
    fmt::print("# Spec reference\n\n"
               "Every key of every fe2heart spec file: its path, type, default (or required), the "
               "branch of its object it belongs to (When) and help. `<name>`, `<region>`: free "
               "names; `<i>`: array index. JSON Schema: `fe2heart spec-schema`.\n\n"
               "Generated from the spec schemas by `fe2heart spec-doc --markdown > "
               "docs/spec-reference.md` (the test cli.spec_reference_md fails when it is out of date); "
               "do not edit by hand.\n\n");
  else
    fmt::print("Every spec key: path, type, default (or required), the branch it belongs to, help.\n"
               "<name>, <region>: free names; <i>: array index. JSON Schema: fe2heart spec-schema.\n\n");
  std::vector<std::pair<std::string, const SchemaNode*>> specs;
  for (const SpecKind& k : spec_kinds())
    specs.emplace_back(markdown ? std::string(1, static_cast<char>(std::toupper(k.heading[0]))) + (k.heading + 1)
                                : std::string(k.heading) + ":",
                       k.schema);
  fmt::print("{}", spec_reference(specs, markdown));
  return 0;
}

}  // namespace fe2::cli
