#pragma once
// The macro mesh: tetrahedra with named node sets, named boundary faces and named
// interfaces (interior faces, e.g. between two regions).
// Linear (4-node) or quadratic (10-node): a quadratic mesh keeps the four vertices of
// each tet in `tets` (geometry, partitions and point location work on them) and adds
// one node per edge in `edge_nodes`, which may lie off the straight edge (curved,
// isoparametric geometry, e.g. an ellipsoidal wall).
#include "common/tensor9.h"

#include <array>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace fe2 {

struct TetMesh {
  std::vector<Vec3> nodes;                    ///< reference coordinates X̄
  std::vector<std::array<int, 4>> tets;       ///< node indices, positive orientation
  std::vector<int> region;                    ///< per tet: physical volume tag (1 if none)
  std::map<int, std::string> region_names;    ///< tag -> name, where the file names it
  /// Named boundary surfaces as triangles, each oriented with its normal pointing
  /// out of the solid (right-hand rule on the node order).
  std::map<std::string, std::vector<std::array<int, 3>>> faces;
  /// Named interior surfaces as triangles, each shared by two tets and oriented with its
  /// normal pointing from the tet of the lower region tag into the other (same region:
  /// from the tet of the lower element index).
  std::map<std::string, std::vector<std::array<int, 3>>> interfaces;
  /// Named node sets (every named face and interface also gives a node set of the same name).
  std::map<std::string, std::vector<int>> node_sets;
  /// Quadratic meshes only: the node on each edge, keyed by its end vertices (smaller first).
  std::map<std::pair<int, int>, int> edge_nodes;

  int num_nodes() const { return static_cast<int>(nodes.size()); }
  int num_tets() const { return static_cast<int>(tets.size()); }
  /// 1 (4-node tets) or 2 (10-node tets).
  int order() const { return edge_nodes.empty() ? 1 : 2; }
  /// The node on edge (a, b); throws fe2::InputError if the mesh has none there.
  int edge_node(int a, int b) const;
  /// The element's nodes in VTK order: linear 4 vertices; quadratic the 4 vertices,
  /// then edges 01, 12, 02, 03, 13, 23 (VTK_QUADRATIC_TETRA).
  std::vector<int> element_nodes(int e) const;
  /// A face triangle's nodes: its 3 vertices, then (quadratic) edges 01, 12, 20
  /// (VTK_QUADRATIC_TRIANGLE, the order of Gmsh's 6-node triangle).
  std::vector<int> face_nodes(const std::array<int, 3>& tri) const;
  /// The distinct face_nodes() of the triangles, ascending.
  std::vector<int> surface_nodes(const std::vector<std::array<int, 3>>& tris) const;
  /// The distinct vertices of the tets, ascending (all nodes when linear).
  std::vector<int> vertices() const;
};

/// Local vertex pairs of the six edges of a tet, in VTK_QUADRATIC_TETRA order.
inline constexpr std::array<std::array<int, 2>, 6> kTetEdges = {{{0, 1}, {1, 2}, {0, 2}, {0, 3}, {1, 3}, {2, 3}}};

/// Makes a linear mesh quadratic with straight edges: a new node at the midpoint of
/// every edge, numbered after the vertices; face node sets gain their edge nodes.
void make_quadratic(TetMesh& m);

/// For each triangle of `tris` (a boundary face or an interface of `m`), the tet it
/// bounds: of an interior triangle the tet its normal points away from (for a named
/// interface, the one of the lower region tag). Throws InputError naming the triangle if
/// it is no face of a tet.
std::vector<int> face_elements(const TetMesh& m, const std::vector<std::array<int, 3>>& tris);

/// `tris` oriented outward from the tet of each that `side` accepts, if every triangle
/// is a face of exactly one such tet (e.g. an interface seen from the wall); else none.
std::optional<std::vector<std::array<int, 3>>> oriented_from(const TetMesh& m, std::vector<std::array<int, 3>> tris,
                                                             const std::function<bool(int tet)>& side);

/// Signed volume of tet e: (x1-x0)·((x2-x0)×(x3-x0))/6.
double tet_signed_volume(const TetMesh& m, int e);

/// Checks every tet has positive volume (throws fe2::InputError naming the element,
/// its nodes and the volume, and `source` (file name or generator) otherwise), that
/// node indices are in range, and adds a node set for each named face and interface
/// that has none.
void validate_mesh(TetMesh& m, const std::string& source);

/// Orients every named face triangle outward from the tet it bounds, and moves each
/// named surface of interior faces from `faces` to `interfaces`, oriented as they are.
/// Throws InputError naming the surface and triangle if a triangle is no face of any
/// tet, or if a surface has both boundary and interior triangles.
void orient_named_surfaces(TetMesh& m, const std::string& source);

}  // namespace fe2
