#include "common/fibres/frame_spec.h"

#include <cmath>
#include <filesystem>

namespace fe2 {

namespace {

Vec3 unit_vec3(SpecNode& s, const std::string& key) {
  const auto v = s.numbers(key);
  const Vec3 x(v[0], v[1], v[2]);
  if (!(x.norm() > 0)) s.fail(key, "a non-zero vector");
  return x.normalized();
}

void read_analytic(SpecNode& f, bool rotating, AnalyticFrame& fr) {
  fr.fibre = unit_vec3(f, "fibre");
  const Vec3 s = unit_vec3(f, "sheet");
  fr.sheet = (s - s.dot(fr.fibre) * fr.fibre);
  if (!(fr.sheet.norm() > 1e-8)) f.fail("sheet", "a direction not parallel to 'fibre'");
  fr.sheet.normalize();
  if (!rotating) return;
  fr.rotating = true;
  fr.axis = unit_vec3(f, "axis");
  fr.coordinate = unit_vec3(f, "coordinate");
  const auto from = f.numbers("from");
  const auto to = f.numbers("to");
  if (!(to[0] != from[0])) f.fail("to", "a coordinate different from 'from'");
  fr.c0 = from[0];
  fr.c1 = to[0];
  fr.angle0 = from[1] * M_PI / 180.0;
  fr.angle1 = to[1] * M_PI / 180.0;
}

void read_rule(SpecNode& f, const TetMesh& mesh, RuleFrameOptions& r) {
  r.alpha_endo = f.number("alpha_endo");
  r.alpha_epi = f.number("alpha_epi");
  r.beta_endo = f.number("beta_endo");
  r.beta_epi = f.number("beta_epi");
  r.endo = f.string("endo");
  r.epi = f.string("epi");
  r.base = f.string("base");
  r.apex = f.string("apex");
  r.rv_endo = f.string("rv_endo");
  std::vector<std::string> names;
  for (const auto& [n, nodes] : mesh.node_sets) names.push_back(n);
  for (const auto& [key, name] : {std::pair<const char*, const std::string&>{"endo", r.endo},
                                  {"epi", r.epi}, {"base", r.base}, {"apex", r.apex}, {"rv_endo", r.rv_endo}}) {
    if ((std::string(key) == "rv_endo" || std::string(key) == "apex") && name.empty()) continue;
    const auto it = mesh.node_sets.find(name);
    if (it != mesh.node_sets.end() && !it->second.empty()) continue;
    f.fail(key, known_names("a named surface or node set of the mesh", name, names));
  }
}

}  // namespace

FrameFieldSpec read_frame_field_spec(SpecNode& f, const TetMesh& mesh, const std::string& base_dir,
                                     const std::string& gmsh_mesh_file, int quadrature_degree) {
  FrameFieldSpec spec;
  const std::string kind = f.choice("kind");
  if (kind == "constant" || kind == "rotating") {
    spec.kind = kind == "constant" ? FrameFieldSpec::Kind::constant : FrameFieldSpec::Kind::rotating;
    read_analytic(f, kind == "rotating", spec.analytic);
  } else if (kind == "file") {
    spec.kind = FrameFieldSpec::Kind::file;
    FileFrameOptions& o = spec.file;
    std::filesystem::path p = f.string("file");
    if (p.is_relative()) p = std::filesystem::path(base_dir) / p;
    o.file = p.string();
    o.csv = f.choice("format") == "csv";
    const std::string per = f.choice("per");
    o.per = per == "node" ? FramePer::node : per == "point" ? FramePer::point : FramePer::element;
    if (o.per == FramePer::point && !o.csv)
      f.fail("format", "\"csv\" for frames per point (lines tag,point,fx,fy,fz,sx,sy,sz; Gmsh views hold one "
                       "vector per element or node)");
    o.quadrature_degree = quadrature_degree;
    o.fibre_view = f.string("fibre_view");
    o.sheet_view = f.string("sheet_view");
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
