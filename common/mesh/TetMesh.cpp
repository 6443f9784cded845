#include "common/mesh/TetMesh.h"

#include "common/error.h"

#include <algorithm>
#include <cmath>

namespace fe2 {

namespace {

// Local node numbers of the four faces of a tet, face i opposite node i.
constexpr std::array<std::array<int, 3>, 4> kTetFaces = {{{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}}};

using FaceKey = std::array<int, 3>;

FaceKey sorted_key(const std::array<int, 3>& tri) {
  FaceKey k = tri;
  std::sort(k.begin(), k.end());
  return k;
}

// The tets that own one face: at most two in a conforming mesh.
struct FaceOwners {
  std::array<int, 2> tet{-1, -1};       ///< in the order found (ascending element index)
  std::array<int, 2> opposite{-1, -1};  ///< each tet's node opposite the face
  int count = 0;
};

std::map<FaceKey, FaceOwners> build_face_map(const TetMesh& m) {
  std::map<FaceKey, FaceOwners> faces;
  for (int e = 0; e < m.num_tets(); ++e) {
    const auto& t = m.tets[e];
    for (int f = 0; f < 4; ++f) {
      const auto& lf = kTetFaces[f];
      FaceOwners& o = faces[sorted_key({t[lf[0]], t[lf[1]], t[lf[2]]})];
      if (o.count < 2) {
        o.tet[o.count] = e;
        o.opposite[o.count] = t[f];
      }
      ++o.count;
    }
  }
  return faces;
}

void check_node_index(const TetMesh& m, int node, const std::string& source,
                      const std::string& where) {
  if (node < 0 || node >= m.num_nodes())
    throw InputError(fmt::format("mesh '{}': {} refers to node {}, expected 0 <= node < {}",
                                 source, where, node, m.num_nodes()));
}

void check_nodes_finite(const TetMesh& m, const std::string& source) {
  for (int i = 0; i < m.num_nodes(); ++i)
    if (!m.nodes[i].allFinite())
      throw InputError(fmt::format("mesh '{}': node {} has coordinates ({}, {}, {}), expected finite numbers",
                                   source, i, m.nodes[i].x(), m.nodes[i].y(), m.nodes[i].z()));
}

void check_tets(const TetMesh& m, const std::string& source) {
  for (int e = 0; e < m.num_tets(); ++e) {
    const auto& t = m.tets[e];
    for (int a = 0; a < 4; ++a) check_node_index(m, t[a], source, fmt::format("element {}", e));
    const double v = tet_signed_volume(m, e);
    if (!(v > 0.0))
      throw InputError(fmt::format(
          "mesh '{}': element {} (nodes {} {} {} {}) is inverted: signed volume {:.6g}, expected > 0",
          source, e, t[0], t[1], t[2], t[3], v));
  }
}

void check_regions(TetMesh& m, const std::string& source) {
  // Generators may leave regions unset: everything is then region 1, as for files.
  if (m.region.empty()) m.region.assign(m.tets.size(), 1);
  if (m.region.size() != m.tets.size())
    throw InputError(fmt::format("mesh '{}': {} region tags for {} elements, expected one per element",
                                 source, m.region.size(), m.tets.size()));
}

// The owner a named triangle is oriented outward from: the only one of a boundary
// face; of an interior face the one of the lower region tag, the first found if equal.
int side_of(const TetMesh& m, const FaceOwners& o) {
  return o.count == 2 && m.region[o.tet[1]] < m.region[o.tet[0]] ? 1 : 0;
}

void check_edges(const TetMesh& m, const std::string& source) {
  if (m.order() == 1) return;
  for (const auto& [edge, node] : m.edge_nodes)
    check_node_index(m, node, source, fmt::format("the node of edge ({}, {})", edge.first, edge.second));
  for (int e = 0; e < m.num_tets(); ++e)
    for (const auto& [a, b] : kTetEdges) {
      const auto key = std::minmax(m.tets[e][a], m.tets[e][b]);
      if (!m.edge_nodes.count(key))
        throw InputError(fmt::format("mesh '{}': quadratic element {} has no node on its edge ({}, {}), "
                                     "expected 10-node tetrahedra throughout",
                                     source, e, key.first, key.second));
    }
}

}  // namespace

double tet_signed_volume(const TetMesh& m, int e) {
  const auto& t = m.tets[e];
  const Vec3& x0 = m.nodes[t[0]];
  return (m.nodes[t[1]] - x0).dot((m.nodes[t[2]] - x0).cross(m.nodes[t[3]] - x0)) / 6.0;
}

int TetMesh::edge_node(int a, int b) const {
  const auto it = edge_nodes.find(std::minmax(a, b));
  if (it == edge_nodes.end())
    throw InputError(fmt::format("mesh: no node on edge ({}, {}), expected a quadratic mesh with "
                                 "a node on every tet edge",
                                 a, b));
  return it->second;
}

std::vector<int> TetMesh::element_nodes(int e) const {
  std::vector<int> n(tets[e].begin(), tets[e].end());
  if (order() == 2)
    for (const auto& [a, b] : kTetEdges) n.push_back(edge_node(tets[e][a], tets[e][b]));
  return n;
}

std::vector<int> TetMesh::face_nodes(const std::array<int, 3>& tri) const {
  std::vector<int> n(tri.begin(), tri.end());
  if (order() == 2)
    for (int a = 0; a < 3; ++a) n.push_back(edge_node(tri[a], tri[(a + 1) % 3]));
  return n;
}

std::vector<int> TetMesh::surface_nodes(const std::vector<std::array<int, 3>>& tris) const {
  std::vector<int> ids;
  ids.reserve(6 * tris.size());
  for (const auto& t : tris) {
    const auto n = face_nodes(t);
    ids.insert(ids.end(), n.begin(), n.end());
  }
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  return ids;
}

std::vector<int> TetMesh::vertices() const {
  std::vector<char> used(nodes.size(), 0);
  for (const auto& t : tets)
    for (int n : t) used[n] = 1;
  std::vector<int> v;
  for (int i = 0; i < num_nodes(); ++i)
    if (used[i]) v.push_back(i);
  return v;
}

void make_quadratic(TetMesh& m) {
  if (m.order() == 2) return;
  for (const auto& t : m.tets)
    for (const auto& [a, b] : kTetEdges) {
      const auto key = std::minmax(t[a], t[b]);
      if (m.edge_nodes.count(key)) continue;
      m.edge_nodes[key] = m.num_nodes();
      m.nodes.push_back(0.5 * (m.nodes[key.first] + m.nodes[key.second]));
    }
  // Node sets derived from faces must hold the new edge nodes too (Dirichlet sets).
  for (const auto* surfaces : {&m.faces, &m.interfaces})
    for (const auto& [name, tris] : *surfaces) m.node_sets[name] = m.surface_nodes(tris);
}

void validate_mesh(TetMesh& m, const std::string& source) {
  if (m.nodes.empty() || m.tets.empty())
    throw InputError(fmt::format("mesh '{}': {} nodes and {} tetrahedra, expected a non-empty mesh",
                                 source, m.nodes.size(), m.tets.size()));
  check_nodes_finite(m, source);
  check_tets(m, source);
  check_edges(m, source);
  check_regions(m, source);
  for (const auto* surfaces : {&m.faces, &m.interfaces})
    for (const auto& [name, tris] : *surfaces)
      for (std::size_t i = 0; i < tris.size(); ++i)
        for (int n : tris[i]) check_node_index(m, n, source, fmt::format("face '{}' triangle {}", name, i));
  for (auto& [name, ids] : m.node_sets)
    for (int n : ids) check_node_index(m, n, source, fmt::format("node set '{}'", name));
  // An explicitly given node set wins over the one derived from a surface of the same name.
  for (const auto* surfaces : {&m.faces, &m.interfaces})
    for (const auto& [name, tris] : *surfaces)
      if (!m.node_sets.count(name)) m.node_sets[name] = m.surface_nodes(tris);
}

void orient_named_surfaces(TetMesh& m, const std::string& source) {
  if (m.faces.empty()) return;
  for (int e = 0; e < m.num_tets(); ++e)
    for (int n : m.tets[e]) check_node_index(m, n, source, fmt::format("element {}", e));
  check_regions(m, source);
  const auto face_map = build_face_map(m);
  for (auto named = m.faces.begin(); named != m.faces.end();) {
    auto& [name, tris] = *named;
    std::array<int, 2> first_of{-1, -1};  // first boundary, first interior triangle
    for (std::size_t i = 0; i < tris.size(); ++i) {
      auto& tri = tris[i];
      const auto it = face_map.find(sorted_key(tri));
      if (it == face_map.end())
        throw InputError(fmt::format("mesh '{}': face '{}' triangle {} (nodes {} {} {}) is not a face of any "
                                     "tetrahedron, expected a boundary face of the volume mesh or an "
                                     "interior face between two of its tetrahedra",
                                     source, name, i, tri[0], tri[1], tri[2]));
      const FaceOwners& o = it->second;
      if (o.count > 2)
        throw InputError(fmt::format("mesh '{}': face '{}' triangle {} (nodes {} {} {}) is shared by {} "
                                     "tetrahedra, expected 1 (a boundary face) or 2 (an interior face)",
                                     source, name, i, tri[0], tri[1], tri[2], o.count));
      int& first = first_of[o.count - 1];
      if (first < 0) first = static_cast<int>(i);
      // Outward means the right-hand normal points away from the tet's fourth node.
      const Vec3& x0 = m.nodes[tri[0]];
      const Vec3 normal = (m.nodes[tri[1]] - x0).cross(m.nodes[tri[2]] - x0);
      if (normal.dot(m.nodes[o.opposite[side_of(m, o)]] - x0) > 0.0) std::swap(tri[1], tri[2]);
    }
    if (first_of[0] >= 0 && first_of[1] >= 0)
      throw InputError(fmt::format("mesh '{}': face '{}' has boundary triangle {} and interior triangle {}, "
                                   "expected a surface wholly on the boundary or wholly inside (an interface)",
                                   source, name, first_of[0], first_of[1]));
    if (first_of[1] < 0) {
      ++named;
      continue;
    }
    m.interfaces[name] = std::move(tris);
    named = m.faces.erase(named);
  }
}

std::vector<int> face_elements(const TetMesh& m, const std::vector<std::array<int, 3>>& tris) {
  const auto face_map = build_face_map(m);
  std::vector<int> tet(tris.size(), -1);
  for (std::size_t i = 0; i < tris.size(); ++i) {
    const auto it = face_map.find(sorted_key(tris[i]));
    if (it == face_map.end())
      throw InputError(fmt::format("triangle {} (nodes {} {} {}) is not a face of any tetrahedron of the mesh", i,
                                   tris[i][0], tris[i][1], tris[i][2]));
    const FaceOwners& o = it->second;
    int side = 0;
    if (o.count == 2) {  // the tet the triangle's normal points away from
      const Vec3& x0 = m.nodes[tris[i][0]];
      const Vec3 normal = (m.nodes[tris[i][1]] - x0).cross(m.nodes[tris[i][2]] - x0);
      side = normal.dot(m.nodes[o.opposite[0]] - x0) < 0.0 ? 0 : 1;
    }
    tet[i] = o.tet[side];
  }
  return tet;
}

std::optional<std::vector<std::array<int, 3>>> oriented_from(const TetMesh& m, std::vector<std::array<int, 3>> tris,
                                                             const std::function<bool(int tet)>& side) {
  const auto face_map = build_face_map(m);
  for (auto& tri : tris) {
    const auto it = face_map.find(sorted_key(tri));
    if (it == face_map.end()) return std::nullopt;
    const FaceOwners& o = it->second;
    const int on_side = (o.count > 0 && side(o.tet[0])) + (o.count > 1 && side(o.tet[1]));
    if (on_side != 1) return std::nullopt;
    const int k = side(o.tet[0]) ? 0 : 1;
    const Vec3& x0 = m.nodes[tri[0]];
    const Vec3 normal = (m.nodes[tri[1]] - x0).cross(m.nodes[tri[2]] - x0);
    if (normal.dot(m.nodes[o.opposite[k]] - x0) > 0.0) std::swap(tri[1], tri[2]);
  }
  return tris;
}

}  // namespace fe2
