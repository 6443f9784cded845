#include "common/activation/activation_spec.h"

#include "common/activation/activation_file.h"
#include "common/activation/activation_schema.h"
#include "common/activation/eikonal.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>

namespace fe2 {

namespace {

struct Velocity {
  double fibre = 0, sheet = 0, normal = 0;
  bool isotropic() const { return fibre == sheet && sheet == normal; }
};

Velocity read_velocity(SpecNode& node) {
  const json* j = node.declared_value("velocity");
  Velocity v;
  if (j && j->is_number()) {
    const double x = j->get<double>();
    if (!(std::isfinite(x) && x > 0)) node.fail("velocity", "a number > 0 (isotropic conduction velocity)");
    v.fibre = v.sheet = v.normal = x;
    return v;
  }
  if (j && !j->is_object())
    node.fail("velocity", "a number > 0 (isotropic) or an object {\"fibre\": .., \"sheet\": .., \"normal\": ..}");
  // Absent: the object form's defaults.
  static const json none = json::object();
  SpecNode o(j ? *j : none, node.key_path("velocity"), velocity_object_schema());
  v.fibre = o.number("fibre");
  v.sheet = o.number("sheet");
  v.normal = o.number("normal");
  o.finish();
  return v;
}

std::vector<std::string> face_names(const TetMesh& mesh) {
  std::vector<std::string> out;
  for (const auto& [name, tris] : mesh.faces)
    if (!tris.empty()) out.push_back(name);
  return out;
}

/// The vertex nearest to p (lowest index on a tie); refuses a point outside the mesh's
/// bounding box grown by a tenth of its diagonal (a unit slip, e.g. m for mm).
int nearest_vertex(SpecNode& s, const TetMesh& mesh, const Vec3& p) {
  const std::vector<int> vertices = mesh.vertices();
  Vec3 lo = mesh.nodes[vertices[0]], hi = lo;
  for (int v : vertices) lo = lo.cwiseMin(mesh.nodes[v]), hi = hi.cwiseMax(mesh.nodes[v]);
  const double pad = 0.1 * (hi - lo).norm();
  if (!((p.array() >= lo.array() - pad).all() && (p.array() <= hi.array() + pad).all()))
    s.fail("point", fmt::format("a point near the mesh (its bounding box is [{}, {}] x [{}, {}] x [{}, {}])", lo[0],
                                hi[0], lo[1], hi[1], lo[2], hi[2]));
  int best = vertices[0];
  double best_d = std::numeric_limits<double>::infinity();
  for (int v : vertices) {
    const double d = (mesh.nodes[v] - p).squaredNorm();
    if (d < best_d) best_d = d, best = v;
  }
  return best;
}

std::vector<EikonalSource> read_sources(SpecNode& node, const TetMesh& mesh) {
  std::vector<SpecNode> items = node.children("sources");
  if (items.empty()) node.fail("sources", "at least one source {\"surface\": name, \"time\": t}");
  std::vector<EikonalSource> out;
  for (SpecNode& s : items) {
    const bool surface = s.has("surface"), point = s.has("point");
    if (surface == point)
      s.fail(surface ? "point" : "surface",
             "exactly one of 'surface' (a named surface of the mesh) or 'point' ([x, y, z])");
    const double time = s.number("time");
    if (surface) {
      const std::string name = s.string("surface");
      const auto it = mesh.faces.find(name);
      if (it == mesh.faces.end() || it->second.empty()) {
        s.fail("surface", known_names("a named surface of the mesh", name, face_names(mesh)));
      }
      std::vector<int> vs;
      for (const auto& tri : it->second) vs.insert(vs.end(), tri.begin(), tri.end());
      std::sort(vs.begin(), vs.end());
      vs.erase(std::unique(vs.begin(), vs.end()), vs.end());
      for (int v : vs) out.push_back({v, time});
    } else {
      const auto p = s.numbers("point");
      out.push_back({nearest_vertex(s, mesh, Vec3(p[0], p[1], p[2])), time});
    }
    s.finish();
  }
  return out;
}

}  // namespace

std::shared_ptr<const ActivationField> read_activation(SpecNode& node, const TetMesh& mesh, const FrameField* frames,
                                                       const std::string& base_dir,
                                                       const std::string& gmsh_mesh_file) {
  const std::string kind = node.choice("kind");
  std::shared_ptr<const ActivationField> field;
  if (kind == "uniform") {
    const double t = node.number("time");
    field = std::make_shared<ActivationField>(ActivationField::uniform(t));
  } else if (kind == "eikonal") {
    const std::vector<EikonalSource> sources = read_sources(node, mesh);
    const Velocity v = read_velocity(node);
    if (!v.isotropic() && !frames)
      node.fail("velocity", "one number (isotropic): different fibre, sheet and normal velocities need a fibre frame");
    std::vector<Mat3> metric(mesh.tets.size());
    for (int e = 0; e < mesh.num_tets(); ++e) {
      Mat3 Q = Mat3::Identity();
      if (!v.isotropic()) {
        Vec3 X = Vec3::Zero();
        for (int n : mesh.tets[e]) X += 0.25 * mesh.nodes[n];
        Q = frames->at(e, kCentroid, X);
      }
      metric[e] = conduction_metric(Q, v.fibre, v.sheet, v.normal);
    }
    field = std::make_shared<ActivationField>(
        ActivationField::per_vertex(mesh, solve_eikonal(mesh, metric, sources)));
  } else {
    ActivationFileOptions o;
    std::filesystem::path p = node.string("file");
    if (p.is_relative()) p = std::filesystem::path(base_dir) / p;
    o.file = p.string();
    o.csv = node.choice("format") == "csv";
    o.view = node.string("view");
    o.mesh_file = gmsh_mesh_file;
    field = std::make_shared<ActivationField>(ActivationField::per_element(read_activation_file(mesh, o)));
  }
  node.finish();
  return field;
}

}  // namespace fe2
