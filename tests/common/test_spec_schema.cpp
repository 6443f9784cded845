// The spec schema (common/spec/spec_schemas.cpp) is the one declaration of every spec
// key: SpecNode refuses a read the schema does not declare, spec-doc prints every
// branch, and the JSON Schema has the types, ranges and branches of the reader.
#include "common/spec/SpecNode.h"
#include "common/spec/json_schema.h"
#include "common/spec/spec_reference.h"
#include "common/spec/spec_schemas.h"

#include <gtest/gtest.h>

#include <regex>

namespace fe2 {
namespace {

/// The message of the fe2::Error (not InputError: the fault is the code's) that `f` throws.
template <class F>
std::string internal_error(F f) {
  try {
    f();
  } catch (const InputError& e) {
    return std::string("InputError: ") + e.what();
  } catch (const Error& e) {
    EXPECT_EQ(e.exit_code(), 1);
    return e.what();
  }
  return "nothing thrown";
}

TEST(SpecSchema, ReadsTakeDefaultsAndRangesFromTheSchema) {
  const json j = {{"farm", {{"batch", 2}}}, {"time", {{"t_end", 2.0}}}};
  SpecNode root(j, "", run_spec_schema());
  SpecNode farm = root.child("farm");
  EXPECT_EQ(farm.integer("batch"), 2);
  EXPECT_EQ(farm.choice("policy"), "cost_based");  // the schema's default
  SpecNode time = root.child("time");
  EXPECT_EQ(time.number("t_end"), 2.0);
  EXPECT_EQ(time.integer("steps"), 1);
  EXPECT_EQ(time.number("beta"), 0.25);
}

TEST(SpecSchema, ErrorsUseTheSchemasRangeAndHelp) {
  const json j = {{"newton", {{"max_iterations", 0}, {"macro_solver", {{"refresh", "adaptve"}}}}}};
  SpecNode root(j, "", run_spec_schema());
  SpecNode n = root.child("newton");
  const SchemaNode& help = *run_spec_schema().find("newton", j)->find("max_iterations", j["newton"]);
  try {
    n.integer("max_iterations");
    ADD_FAILURE() << "0 iterations accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              "/newton/max_iterations: got 0, expected an integer in [1, 1000] (" + help.help + ")");
  }
  SpecNode m = n.child("macro_solver");
  try {
    m.choice("refresh");
    ADD_FAILURE() << "a misspelt choice accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("expected one of \"every_iteration\", \"adaptive\" (every_iteration: "),
              std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("; did you mean \"adaptive\"?"), std::string::npos) << e.what();
  }
}

TEST(SpecSchema, AReadOfAnotherTypeIsAnInternalError) {
  const json j = {{"farm", json::object()}};
  SpecNode root(j, "", run_spec_schema());
  SpecNode farm = root.child("farm");
  const std::string type = internal_error([&] { farm.number("batch"); });
  EXPECT_NE(type.find("internal error: the spec reader reads /farm/batch with number(), the spec "
                      "schema (common/spec/spec_schemas.cpp) declares it integer in [1, 1000000]"),
            std::string::npos)
      << type;
  const std::string object = internal_error([&] { farm.child("policy"); });
  EXPECT_NE(object.find("reads /farm/policy with child()"), std::string::npos) << object;
}

TEST(SpecSchema, AKeyTheSchemaLacksIsAnInternalError) {
  const json j = {{"newton", json::object()}};
  SpecNode root(j, "", run_spec_schema());
  SpecNode n = root.child("newton");
  const std::string msg = internal_error([&] { n.number("atol"); });
  EXPECT_NE(msg.find("internal error: the spec reader reads /newton/atol (number), which the spec "
                     "schema (common/spec/spec_schemas.cpp) has no key for here"),
            std::string::npos)
      << msg;
}

TEST(SpecSchema, TheDiscriminatorPicksTheBranch) {
  const json gmsh = {{"mesh", {{"kind", "gmsh"}, {"file", "heart.msh"}}}};
  SpecNode root(gmsh, "", run_spec_schema());
  SpecNode m = root.child("mesh");
  m.choice("kind");
  EXPECT_EQ(m.string("file"), "heart.msh");
  // Without "kind" the mesh is a box (the default branch), which has no file.
  const json box = {{"mesh", {{"hi", {1, 1, 1}}}}};
  SpecNode root2(box, "", run_spec_schema());
  SpecNode m2 = root2.child("mesh");
  EXPECT_EQ(m2.choice("kind"), "box");
  const std::string msg = internal_error([&] { m2.string("file"); });
  EXPECT_NE(msg.find("reads /mesh/file (string), which the spec schema"), std::string::npos) << msg;
  EXPECT_EQ(m2.numbers("hi"), (std::vector<double>{1, 1, 1}));
  EXPECT_EQ(m2.numbers("lo"), (std::vector<double>{0, 0, 0}));  // the schema's default
}

TEST(SpecNames, KnownNamesListThemAndSuggestTheNearest) {
  EXPECT_EQ(known_names("a node set of the mesh", "tpo", {"bottom", "top"}),
            "a node set of the mesh (bottom, top); did you mean \"top\"?");
  EXPECT_EQ(known_names("a node set of the mesh", "left", {"bottom", "top"}), "a node set of the mesh (bottom, top)");
  EXPECT_EQ(known_names("a cavity", "lv", {}), "a cavity (none)");
  EXPECT_EQ(did_you_mean("3", {"1", "2"}), "");  // a region tag has no spelling
  EXPECT_EQ(unknown_key("rtoll", "/newton", {"rtol", "max_iterations"}),
            "unknown key 'rtoll' in /newton; did you mean 'rtol'?; known keys: rtol, max_iterations");
}

TEST(SpecSchema, ReadsRecordTheSchemaNodesTheyVisit) {
  const json j = {{"output", {{"every", 3}}}};
  SpecDoc doc;
  SpecNode root(j, "", run_spec_schema(), &doc);
  SpecNode out = root.child("output");
  out.integer("every");
  const SchemaNode* output = run_spec_schema().find("output", j);
  ASSERT_NE(output, nullptr);
  EXPECT_EQ(doc.visited.size(), 2u);
  EXPECT_TRUE(doc.visited.count(output));
  EXPECT_TRUE(doc.visited.count(output->find("every", j["output"])));
}

/// The spec-doc line of `path`, or "" if there is none.
std::string line_of(const std::string& doc, const std::string& path) {
  std::istringstream in(doc);
  for (std::string line; std::getline(in, line);)
    if (line.rfind("  " + path + " ", 0) == 0) return line;
  return "";
}

std::string collapse(std::string s) {  // runs of spaces to one (the path column is padded)
  return std::regex_replace(s, std::regex(" +"), " ");
}

TEST(SpecSchema, SpecDocListsEveryBranchWithIntegersAsIntegers) {
  const std::string doc = spec_reference(
      {{"run specs:", &run_spec_schema()}, {"unit specs:", &unit_spec_schema()}});
  auto expect = [&](const std::string& path, const std::string& text) {
    EXPECT_EQ(collapse(line_of(doc, path)), " " + path + " " + text) << doc;
  };
  expect("/mesh/file", "string (required), when kind = \"gmsh\": Gmsh 4.1 ASCII mesh file");
  expect("/mesh/divisions",
         "array of 3 integers in [1, 1000] (required), when kind = \"box\": cells per axis (6 "
         "tets per cell)");
  expect("/time/steps", "integer in [1, 10000000] (default 1): number of steps");
  expect("/models/<name>/material",
         "object <material> (required), when kind = \"macro_law\": constitutive law");
  expect("/models/<name>/unit", "object <unit> (required), when kind = \"fe2\": the micro unit");
  expect("/unit", "object <unit> (required): the micro unit");
  expect("<unit>/mesh_file",
         "string (required), when cell = \"mesh_file\": Gmsh 4.1 hex mesh of the cell");
  expect("<unit>/resolution",
         "array of 3 integers in [1, 1000] (default [8, 4, 4]), when cell = \"two_cells\": "
         "hexahedra per axis");
  expect("<material>/bfs",
         "number > 0 (default 1.63), when model = \"guccione\": fibre-shear exponent b_fs");
  expect("<material>/E", "number > 0 (required), when model = \"neo_hookean\": Young's modulus (Pa)");
  expect("<material>/af",
         "number >= 0 (default 18472), when model = \"holzapfel_ogden\": fibre modulus a_f (Pa), "
         "acts in fibre tension only");
  EXPECT_NE(line_of(doc, "/farm/stall_timeout").find("number > 0 (default 600)"), std::string::npos);
  expect("/probes/<name>", "array of 3 numbers (required): reference position");
  // Each shared definition is printed once, saying where it is used.
  EXPECT_NE(doc.find("<material>: constitutive law (at /models/<name>/material, "
                     "<unit>/materials/ecm"),
            std::string::npos)
      << doc;
  EXPECT_NE(doc.find("<unit>: the micro unit (at /models/<name>/unit, /unit)"), std::string::npos);
}

TEST(SpecSchema, JsonSchemaHasTypesRangesAndOneBranchPerKind) {
  const json s = to_json_schema(run_spec_schema(), "urn:test", "run");
  EXPECT_EQ(s["$schema"], "https://json-schema.org/draft/2020-12/schema");
  EXPECT_EQ(s["additionalProperties"], false);
  EXPECT_EQ(s["required"], json({"mesh", "models", "dirichlet"}));
  const json& mesh = s["properties"]["mesh"];
  ASSERT_EQ(mesh["oneOf"].size(), 3u);  // box, gmsh, lv
  const json& box = mesh["oneOf"][0];
  EXPECT_EQ(box["properties"]["kind"]["const"], "box");
  EXPECT_EQ(box["required"], json({"hi", "divisions"}));  // kind may be omitted: box is the default
  EXPECT_EQ(box["additionalProperties"], false);
  EXPECT_EQ(box["properties"]["divisions"],
            json({{"type", "array"},
                  {"items", {{"type", "integer"}, {"minimum", 1.0}, {"maximum", 1000.0}}},
                  {"minItems", 3},
                  {"maxItems", 3},
                  {"description", "cells per axis (6 tets per cell)"}}));
  const json& gmsh = mesh["oneOf"][1];
  EXPECT_EQ(gmsh["required"], json({"kind", "file"}));
  EXPECT_FALSE(gmsh["properties"].contains("divisions"));
  const json& batch = s["properties"]["farm"]["properties"]["batch"];
  EXPECT_EQ(batch["type"], "integer");
  EXPECT_EQ(batch["default"], 4);
  const json& beta = s["properties"]["time"]["properties"]["beta"];
  EXPECT_EQ(beta["exclusiveMinimum"], 0.0);
  EXPECT_EQ(beta["maximum"], 0.5);
  // Shared definitions: the material has one branch per model, guccione with its keys.
  const json& material = s["$defs"]["material"];
  ASSERT_EQ(material["oneOf"].size(), 4u);
  EXPECT_EQ(material["oneOf"][2]["properties"]["kappa"]["default"], 1e5);
  EXPECT_EQ(material["oneOf"][3]["properties"]["isotropic"]["default"], "isochoric");
  EXPECT_EQ(material["oneOf"][3]["properties"]["af"]["minimum"], 0.0);
  EXPECT_EQ(material["oneOf"][3]["properties"]["volumetric"]["enum"], json({"penalty", "none"}));
  EXPECT_EQ(s["$defs"]["unit"]["oneOf"].size(), 4u);
  const json unit = to_json_schema(unit_spec_schema(), "urn:test", "unit");
  EXPECT_EQ(unit["oneOf"], json({{{"required", {"Zbar"}}}, {{"required", {"Zbar_path"}}}}));
}

}  // namespace
}  // namespace fe2
