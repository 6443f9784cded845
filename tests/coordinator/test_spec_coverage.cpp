// Every key of the spec schema is read by the reader, and the reader reads no key the
// schema lacks (SpecNode reads every key by the schema; a key it lacks throws). Together:
// the schema that spec-doc and spec-schema print is exactly what the reader accepts.
// The specs read: every shipped config, the exemplars in tests/data/schema/ (written to
// cover every branch) and the positive controls of the CLI tests.
#include "common/circulation/circulation_run_spec.h"
#include "common/spec/SchemaNode.h"
#include "common/spec/spec_schemas.h"
#include "coordinator/RunSpec.h"
#include "tools/unit_spec.h"

#include <gtest/gtest.h>

#include <filesystem>

namespace fe2 {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> specs_to_read() {
  const fs::path src = FE2_SOURCE_DIR;
  std::vector<std::string> files;
  for (const fs::path& dir : {src / "configs", src / "tests/data/schema"})
    for (const auto& e : fs::directory_iterator(dir))
      if (e.path().extension() == ".json" && e.path().filename().string().rfind("reject_", 0) != 0)
        files.push_back(e.path().string());
  for (const char* f : {"tests/data/bad/valid_tets.json", "tests/data/bad/periodic_unit.json",
                        "tests/mpi/farm_scene.json"})
    files.push_back((src / f).string());
  std::sort(files.begin(), files.end());
  return files;
}

bool is_unit_spec(const json& j) { return j.contains("unit") && !j.contains("mesh"); }

/// Paths of schema nodes under `n` that no read visited.
void unvisited(const SchemaNode& n, const std::string& path, const SpecDoc& doc,
               std::vector<std::string>& out, std::set<const SchemaNode*>& seen) {
  if (!seen.insert(&n).second) return;  // shared definitions are walked once
  auto key = [&](const std::string& p, const SchemaNode& k) {
    if (!doc.visited.count(&k)) out.push_back(p);
    unvisited(k, p, doc, out, seen);
  };
  for (const auto& [name, k] : n.keys) key(path + "/" + name, *k);
  for (const auto& b : n.branches)
    for (const auto& [name, k] : b.keys)
      key(path + "/" + name + " (" + n.discriminator + " = " + b.value + ")", *k);
  if (n.element) key(path + "/*", *n.element);
}

TEST(SpecSchemaCoverage, EveryKeyOfBothSchemasIsReadByTheReaders) {
  SpecDoc doc;
  int run = 0, unit = 0, circulation = 0;
  for (const auto& f : specs_to_read()) {
    SCOPED_TRACE(f);
    const json j = read_json_file(f);
    // Study files (configs/study-*.json) vary a run spec; tools/study_spec reads them and
    // validates every variant through read_run_spec (the cli.study tests).
    if (j.contains("base") && (j.contains("variants") || j.contains("one_at_a_time"))) continue;
    // Throws (failing the test) if the reader reads a key the schema does not declare.
    if (is_circulation_run_spec(j)) {
      read_circulation_run_spec(j, f, &doc);
      ++circulation;
    } else if (is_unit_spec(j)) {
      cli::read_unit_spec(j, f, &doc);
      ++unit;
    } else {
      read_run_spec(j, f, &doc);
      ++run;
    }
  }
  EXPECT_GE(run, 5);
  EXPECT_GE(unit, 3);
  EXPECT_GE(circulation, 4);
  std::vector<std::string> missing;
  std::set<const SchemaNode*> seen;
  unvisited(run_spec_schema(), "", doc, missing, seen);
  unvisited(unit_spec_schema(), "(unit spec)", doc, missing, seen);
  unvisited(circulation_run_schema(), "(circulation spec)", doc, missing, seen);
  EXPECT_TRUE(missing.empty())
      << "schema keys the readers never declared while reading every spec (a branch no spec "
         "selects: add it to an exemplar in tests/data/schema/; or a key the reader does not "
         "accept: remove it from common/spec/spec_schemas.cpp): "
                               << fmt::format("{}", fmt::join(missing, ", "));
}

}  // namespace
}  // namespace fe2
