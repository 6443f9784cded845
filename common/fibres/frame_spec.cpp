#include "common/fibres/frame_spec.h"

#include <cmath>
#include <filesystem>

namespace fe2 {

namespace {

Vec3 unit_vec3(SpecNode& s, const std::string& key, const Vec3& def, const std::string& help) {
  const auto v = s.numbers(key, 3, std::vector<double>{def[0], def[1], def[2]}, help);
  const Vec3 x(v[0], v[1], v[2]);
  if (!(x.norm() > 0)) s.fail(key, "a non-zero vector");
  return x.normalized();
}

void read_analytic(SpecNode& f, bool rotating, AnalyticFrame& fr) {
  fr.fibre = unit_vec3(f, "fibre", Vec3::UnitX(), "fibre direction f (unit axis 1)");
  const Vec3 s = unit_vec3(f, "sheet", Vec3::UnitY(), "sheet direction s (unit axis 2)");
  fr.sheet = (s - s.dot(fr.fibre) * fr.fibre);
  if (!(fr.sheet.norm() > 1e-8)) f.fail("sheet", "a direction not parallel to 'fibre'");
  fr.sheet.normalize();
  if (!rotating) return;
  fr.rotating = true;
  fr.axis = unit_vec3(f, "axis", Vec3::UnitZ(), "rotation axis of the fibres");
  fr.coordinate = unit_vec3(f, "coordinate", Vec3::UnitY(), "direction along which the angle varies (transmural)");
  const auto from = f.numbers("from", 2, std::nullopt, "[coordinate, angle in degrees]");
  const auto to = f.numbers("to", 2, std::nullopt, "[coordinate, angle in degrees]");
  if (!(to[0] != from[0])) f.fail("to", "a coordinate different from 'from'");
  fr.c0 = from[0];
  fr.c1 = to[0];
  fr.angle0 = from[1] * M_PI / 180.0;
  fr.angle1 = to[1] * M_PI / 180.0;
}

void read_rule(SpecNode& f, const TetMesh& mesh, RuleFrameOptions& r) {
  const Range angle = Range::closed(-180, 180);
  r.alpha_endo = f.number("alpha_endo", 60.0, angle, "helix angle on the endocardium (degrees)");
  r.alpha_epi = f.number("alpha_epi", -60.0, angle, "helix angle on the epicardium (degrees)");
  r.beta_endo = f.number("beta_endo", 0.0, angle, "sheet angle on the endocardium (degrees)");
  r.beta_epi = f.number("beta_epi", 0.0, angle, "sheet angle on the epicardium (degrees)");
  r.endo = f.string("endo", "endo", "named surface of the (LV) endocardium: φ = 0");
  r.epi = f.string("epi", "epi", "named surface of the epicardium: φ = 1");
  r.base = f.string("base", "base", "named surface of the base: ψ = 1");
  r.apex = f.string("apex", "", "named node set of the apex: ψ = 0 (\"\": the epi node farthest from the base)");
  r.rv_endo = f.string("rv_endo", "", "named surface of the RV endocardium (biventricular); \"\": LV only");
  std::vector<std::string> names;
  for (const auto& [n, nodes] : mesh.node_sets) names.push_back(n);
  for (const auto& [key, name] : {std::pair<const char*, const std::string&>{"endo", r.endo},
                                  {"epi", r.epi}, {"base", r.base}, {"apex", r.apex}, {"rv_endo", r.rv_endo}}) {
    if ((std::string(key) == "rv_endo" || std::string(key) == "apex") && name.empty()) continue;
    const auto it = mesh.node_sets.find(name);
    if (it != mesh.node_sets.end() && !it->second.empty()) continue;
    const std::string guess = closest_match(name, names);
    f.fail(key, fmt::format("a named surface or node set of the mesh ({}){}",
                            names.empty() ? "none" : fmt::format("{}", fmt::join(names, ", ")),
                            guess.empty() ? "" : "; did you mean \"" + guess + "\"?"));
  }
}

}  // namespace

FrameFieldSpec read_frame_field_spec(SpecNode& f, const TetMesh& mesh, const std::string& base_dir,
                                     const std::string& gmsh_mesh_file) {
  FrameFieldSpec spec;
  const std::string kind =
      f.choice("kind", "constant", {"constant", "rotating", "file", "rule"}, "fibre frame rule");
  if (kind == "constant" || kind == "rotating") {
    spec.kind = kind == "constant" ? FrameFieldSpec::Kind::constant : FrameFieldSpec::Kind::rotating;
    read_analytic(f, kind == "rotating", spec.analytic);
  } else if (kind == "file") {
    spec.kind = FrameFieldSpec::Kind::file;
    FileFrameOptions& o = spec.file;
    std::filesystem::path p = f.string("file", std::nullopt, "fibre file: Gmsh MSH 4.1 views or CSV");
    if (p.is_relative()) p = std::filesystem::path(base_dir) / p;
    o.file = p.string();
    o.csv = f.choice("format", "gmsh", {"gmsh", "csv"},
                     "gmsh: $ElementData/$NodeData views; csv: lines tag,fx,fy,fz,sx,sy,sz") == "csv";
    o.per_node = f.choice("per", "element", {"element", "node"},
                          "one fibre and sheet per element, or per node (interpolated)") == "node";
    o.fibre_view = f.string("fibre_view", "fibre", "name of the Gmsh view of fibre vectors");
    o.sheet_view = f.string("sheet_view", "sheet", "name of the Gmsh view of sheet vectors");
    o.mesh_file = gmsh_mesh_file;
    spec.loaded = std::make_shared<FileFrame>(mesh, o);
  } else {
    spec.kind = FrameFieldSpec::Kind::rule;
    read_rule(f, mesh, spec.rule);
  }
  return spec;
}

std::shared_ptr<const FrameField> make_frame_field(const FrameFieldSpec& spec, const TetMesh& mesh) {
  switch (spec.kind) {
    case FrameFieldSpec::Kind::constant:
    case FrameFieldSpec::Kind::rotating:
      return std::make_shared<AnalyticFrame>(spec.analytic);
    case FrameFieldSpec::Kind::file:
      return spec.loaded ? spec.loaded : std::make_shared<FileFrame>(mesh, spec.file);
    case FrameFieldSpec::Kind::rule:
      return std::make_shared<RuleFrame>(mesh, spec.rule);
  }
  return nullptr;
}

}  // namespace fe2
