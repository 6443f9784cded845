// The spec reader on arbitrary text, as `fe2heart validate` and `run` read a spec:
// the JSON parse (duplicate keys, nesting depth, overflowing numbers), then the parts
// of the reader that live in common/: a standalone circulation spec in full
// (read_circulation_run_spec), a run spec's circulation, its cell models
// (models/<name>/material/active), its farm.factor_memory_budget, and the SpecNode
// accessors on the usual sections. Every refusal must be an InputError naming the key.
// (The rest of read_run_spec, in coordinator/, builds meshes and unit plans and needs
// the solver libraries; the fuzz build links only common/ and proto/.)
#include "common/cellmodels/cell_model_factory.h"
#include "common/cellmodels/cell_model_schema.h"
#include "common/circulation/circulation_factory.h"
#include "common/circulation/circulation_run_spec.h"
#include "common/circulation/circulation_schema.h"
#include "common/spec/SpecNode.h"
#include "common/spec/memory_size.h"
#include "common/spec/spec_schemas.h"
#include "tests/fuzz/fuzz_support.h"

#include <cmath>

using namespace fe2;

namespace {

// A run spec's sections as coordinator/RunSpec.cpp reads them, through every kind of
// SpecNode accessor (keys of the run spec schema).
void read_run_sections(const json& j) {
  SpecNode root(j, "", run_spec_schema());
  root.string("title");
  SpecNode time = root.child("time");
  fuzz::require(time.number("t_end") > 0, "t_end in range");
  const int steps = time.integer("steps");
  fuzz::require(steps >= 1 && steps <= 10000000, "steps in range");
  time.finish();
  SpecNode mesh = root.child("mesh");
  if (mesh.choice("kind") == "box") {
    fuzz::require(mesh.numbers("lo").size() == 3, "3 numbers");
    mesh.numbers("divisions");
  }
  for (SpecNode& d : root.children("dirichlet")) {
    d.string("set");
    d.numbers("components");
    d.finish();
  }
  SpecNode probes = root.child("probes");
  for (const auto& p : probes.raw().items()) probes.numbers(p.key());
}

void read_common_parts(const json& j) {
  if (!j.is_object()) return;
  if (j.contains("farm") && j["farm"].is_object() && j["farm"].contains("factor_memory_budget") &&
      j["farm"]["factor_memory_budget"].is_string()) {
    fuzz::expect_only<InputError>([&] {
      const double b = parse_memory_size(j["farm"]["factor_memory_budget"].get<std::string>(),
                                         "/farm/factor_memory_budget");
      fuzz::require(std::isfinite(b) && b > 0, "a memory size is finite and positive");
    });
  }
  if (j.contains("circulation") && j["circulation"].is_object()) {
    fuzz::expect_only<InputError>([&] {
      SpecNode c(j["circulation"], "/circulation", *circulation_schema());
      const auto circ = make_circulation(c);
      fuzz::require(circ && std::isfinite(circ->period()) && circ->period() > 0, "a finite period");
    });
  }
  if (j.contains("models") && j["models"].is_object())
    for (const auto& item : j["models"].items()) {
      const json& m = item.value();
      const std::string name = item.key();
      if (m.is_object() && m.contains("material") && m["material"].is_object() &&
          m["material"].contains("active") && m["material"]["active"].is_object())
        fuzz::expect_only<InputError>([&] {
          SpecNode a(m["material"]["active"], "/models/" + name + "/material/active", *cell_model_schema());
          fuzz::require(read_active_stress(a).cell != nullptr, "a cell model");
        });
    }
  fuzz::expect_only<InputError>([&] { read_run_sections(j); });
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view text = fuzz::text_of(data, size);
  if (size <= 64)  // the same text as a size ("8G"), as --memory-limit reads it
    fuzz::expect_only<InputError>([&] {
      const double b = parse_memory_size(std::string(text), "--memory-limit");
      fuzz::require(std::isfinite(b) && b > 0, "a memory size is finite and positive");
    });
  json j;
  try {
    j = parse_json_text(text, "fuzz.json");
  } catch (const InputError&) {
    return 0;
  }
  if (is_circulation_run_spec(j))
    fuzz::expect_only<InputError>([&] {
      const CirculationRunSpec s = read_circulation_run_spec(j, "fuzz.json");
      fuzz::require(s.steps > 0 && std::isfinite(s.dt()) && s.dt() > 0, "a positive time step");
    });
  read_common_parts(j);
  return 0;
}
