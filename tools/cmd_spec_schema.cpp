// `fe2heart spec-schema [--unit | --circulation | --study]`: a spec schema as JSON Schema
// 2020-12, from the same declarations the readers read every key by
// (common/spec/spec_schemas.cpp, circulation_run_spec.cpp, tools/study_spec.cpp).
#include "common/circulation/circulation_run_spec.h"
#include "common/spec/json_schema.h"
#include "common/spec/spec_schemas.h"
#include "tools/commands.h"
#include "tools/study_spec.h"

namespace fe2::cli {

const std::vector<SpecKind>& spec_kinds() {
  static const std::vector<SpecKind> kinds = {
      {"run", "run specs (fe2heart run / validate)", &run_spec_schema(), "urn:fe2heart:run-spec",
       "fe2heart run spec (fe2heart run, validate)"},
      {"unit", "unit specs (fe2heart unit)", &unit_spec_schema(), "urn:fe2heart:unit-spec",
       "fe2heart unit spec (fe2heart unit)"},
      {"circulation", "circulation specs (fe2heart circulation)", &circulation_run_schema(),
       "urn:fe2heart:circulation-spec", "fe2heart circulation spec (fe2heart circulation)"},
      {"study", "study files (fe2heart study)", &study_spec_schema(), "urn:fe2heart:study-spec",
       "fe2heart study file (fe2heart study)"},
  };
  return kinds;
}

int spec_schema(const std::string& kind) {
  for (const SpecKind& k : spec_kinds())
    if (kind == k.name) {
      fmt::print("{}\n", to_json_schema(*k.schema, k.id, k.title).dump(2));
      return 0;
    }
  throw Error(fmt::format("internal error: no spec kind '{}'", kind));
}

}  // namespace fe2::cli
