// `fe2heart spec-doc`: the reference of spec keys, built from the same declarations
// that read and validate specs (so it cannot drift from the code). Keys are
// collected by reading example specs; by default the shipped configs.
#include "coordinator/RunSpec.h"
#include "tools/commands.h"
#include "tools/unit_spec.h"

#include <filesystem>
#include <map>
#include <regex>

namespace fe2::cli {

int spec_doc(const std::vector<std::string>& given) {
  std::vector<std::string> specs = given;
  if (specs.empty())
    for (const auto& e : std::filesystem::directory_iterator(FE2_CONFIG_DIR))
      if (e.path().extension() == ".json") specs.push_back(e.path().string());
  std::sort(specs.begin(), specs.end());
  SpecDoc run_doc, unit_doc;
  for (const auto& f : specs) {
    const json j = read_json_file(f);
    if (j.is_object() && j.contains("unit") && !j.contains("mesh"))
      read_unit_spec(j, f, &unit_doc);
    else
      read_run_spec(j, f, &run_doc);
  }
  // Free names (model names, region names) become <name> so the reference is general.
  auto print = [](const SpecDoc& d, const char* title) {
    if (d.entries.empty()) return;
    std::map<std::string, std::string> general;
    const std::regex model("^/models/[^/]+"), probe("^/probes/[^/]+$"), index("/[0-9]+(/|$)");
    for (const auto& [path, text] : d.entries) {
      std::string p = std::regex_replace(path, model, "/models/<name>");
      p = std::regex_replace(p, probe, "/probes/<name>");
      p = std::regex_replace(p, index, "/<i>$1");
      general.emplace(p, text);
    }
    fmt::print("{}\n", title);
    for (const auto& [path, text] : general) fmt::print("  {:<44} {}\n", path, text);
    fmt::print("\n");
  };
  fmt::print("Keys declared by {} spec(s): {}\n\n", specs.size(), fmt::join(specs, ", "));
  print(run_doc, "run specs (fe2heart run / validate):");
  print(unit_doc, "unit specs (fe2heart unit):");
  return 0;
}

}  // namespace fe2::cli
