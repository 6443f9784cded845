#include "common/activation/activation_spec.h"

#include "common/activation/activation_file.h"
#include "common/activation/eikonal.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>

namespace fe2 {

namespace {

const char* const kVelocityType = "number > 0 or object {fibre, sheet, normal}";

struct Velocity {
  double fibre = kDefaultVelocityFibre, sheet = kDefaultVelocitySheet, normal = kDefaultVelocityNormal;
  bool isotropic() const { return fibre == sheet && sheet == normal; }
};

Velocity read_velocity(SpecNode& node) {
  Velocity v;
  const json* j = node.declared_value(
      "velocity", kVelocityType,
      "conduction velocity (mesh length units per second): one number (isotropic) or "
      "{fibre, sheet, normal}; default {670, 300, 170} mm/s (Caldwell et al. 2009)");
  if (!j) return v;
  if (j->is_number()) {
    const double x = j->get<double>();
    if (!(std::isfinite(x) && x > 0)) node.fail("velocity", "a number > 0 (isotropic conduction velocity)");
    v.fibre = v.sheet = v.normal = x;
    return v;
  }
  if (!j->is_object())
    node.fail("velocity", "a number > 0 (isotropic) or an object {\"fibre\": .., \"sheet\": .., \"normal\": ..}");
  SpecNode o(*j, node.key_path("velocity"));
  v.fibre = o.number("fibre", kDefaultVelocityFibre, Range::positive(), "velocity along the fibres");
  v.sheet = o.number("sheet", kDefaultVelocitySheet, Range::positive(), "velocity along the sheets");
  v.normal = o.number("normal", kDefaultVelocityNormal, Range::positive(), "velocity along the sheet normals");
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
  std::vector<SpecNode> items =
      node.children("sources", true, "where the front starts: named surfaces or points, each with a time");
  if (items.empty()) node.fail("sources", "at least one source {\"surface\": name, \"time\": t}");
  std::vector<EikonalSource> out;
  for (SpecNode& s : items) {
    const bool surface = s.has("surface"), point = s.has("point");
    if (surface == point)
      s.fail(surface ? "point" : "surface",
             "exactly one of 'surface' (a named surface of the mesh) or 'point' ([x, y, z])");
    const double time = s.number("time", 0.0, Range::non_negative(), "activation time of the source (s)");
    if (surface) {
      const std::string name = s.string("surface", std::nullopt, "named surface of the mesh whose vertices start");
      const auto it = mesh.faces.find(name);
      if (it == mesh.faces.end() || it->second.empty()) {
        const std::vector<std::string> names = face_names(mesh);
        const std::string guess = closest_match(name, names);
        s.fail("surface", fmt::format("a named surface of the mesh ({}){}",
                                      names.empty() ? "none" : fmt::format("{}", fmt::join(names, ", ")),
                                      guess.empty() ? "" : "; did you mean \"" + guess + "\"?"));
      }
      std::vector<int> vs;
      for (const auto& tri : it->second) vs.insert(vs.end(), tri.begin(), tri.end());
      std::sort(vs.begin(), vs.end());
      vs.erase(std::unique(vs.begin(), vs.end()), vs.end());
      for (int v : vs) out.push_back({v, time});
    } else {
      const auto p = s.numbers("point", 3, std::nullopt, "a point [x, y, z]: its nearest mesh vertex starts");
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
  const std::string kind = node.choice("kind", "uniform", {"uniform", "eikonal", "file"},
                                       "how activation times are given: one time, an eikonal front, or a file");
  std::shared_ptr<const ActivationField> field;
  if (kind == "uniform") {
    const double t = node.number("time", 0.0, Range::non_negative(), "activation time of every point (s)");
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
    std::filesystem::path p = node.string("file", std::nullopt, "activation file: a Gmsh MSH 4.1 view or CSV");
    if (p.is_relative()) p = std::filesystem::path(base_dir) / p;
    o.file = p.string();
    o.csv = node.choice("format", "gmsh", {"gmsh", "csv"},
                        "gmsh: an $ElementData view; csv: lines tag,time") == "csv";
    o.view = node.string("view", "activation", "name of the Gmsh $ElementData view of activation times (s)");
    o.mesh_file = gmsh_mesh_file;
    field = std::make_shared<ActivationField>(ActivationField::per_element(read_activation_file(mesh, o)));
  }
  node.finish();
  return field;
}

}  // namespace fe2
