#pragma once
// Readers for ASCII Gmsh MSH 4.1 files (https://gmsh.info/doc/texinfo/gmsh.html#MSH-file-format).
// Binary files, other versions and partitioned meshes are rejected with an InputError
// that names the file, the line and what was expected. Sections other than
// $MeshFormat, $PhysicalNames, $Entities, $Nodes, $Elements, $NodeData and
// $ElementData are skipped.
#include "common/mesh/HexMesh.h"
#include "common/mesh/TetMesh.h"

#include <string>
#include <vector>

namespace fe2 {

/// The macro mesh of a Gmsh file:
///  - 4-node tetrahedra (type 4) or 10-node tetrahedra (type 11, a quadratic mesh whose
///    edge nodes go to TetMesh::edge_nodes; not both); region = first physical tag of
///    their volume entity (1 if it has none); region_names = names of physical volumes;
///  - 3-node triangles (type 2; type 9, 6-node, in a quadratic mesh) on surface entities
///    with a named physical group become faces[name] (boundary faces, oriented outward)
///    or interfaces[name] (interior faces, oriented from the lower region tag), see
///    orient_named_surfaces; their node sets include the edge nodes;
///  - points (type 15) on named physical points and the nodes of 2-node lines (type 1)
///    on named physical curves (3-node lines, type 8, in a quadratic mesh) become node_sets[name].
/// Nodes are those of the tets, renumbered 0.. in file order. Elements of other types
/// are ignored. Throws InputError if there are no tets or a tet is inverted.
TetMesh read_gmsh_tets(const std::string& file);

/// A micro-unit mesh of a Gmsh file: 8-node hexahedra (type 5), region = 0-based
/// index of the hex's (first) physical volume tag among all physical volume tags of hex
/// entities sorted ascending; region_names = the physical names (the tag as text where
/// a group has no name), which the unit spec's materials refer to; lo/hi = bounding
/// box of the hex nodes. Throws InputError if there are no hexes, one is inverted, or
/// a hex entity belongs to no physical volume.
HexMesh read_gmsh_hexes(const std::string& file);

/// File tags of the tets and nodes of a Gmsh mesh, in the numbering read_gmsh_tets
/// gives them: elements[e] is the tag of TetMesh tet e, nodes[i] that of node i.
struct GmshTags {
  std::vector<long long> elements, nodes;
};
GmshTags read_gmsh_tags(const std::string& file);

enum class GmshDataOn { elements, nodes };

/// A 3-component view of a Gmsh file: the $ElementData or $NodeData section whose
/// first string tag is `name` (e.g. "fibre"), entries keyed by element or node tag in
/// file order (map them with read_gmsh_tags of the mesh). The file need not hold a mesh.
/// Throws InputError naming the file if no such view exists (listing those that do),
/// if it appears twice (several time steps) or has other than 3 components.
struct GmshVectorView {
  std::vector<long long> tags;
  std::vector<Vec3> values;
  std::vector<int> lines;  ///< file line of each entry, for messages
};
GmshVectorView read_gmsh_vector_view(const std::string& file, GmshDataOn on, const std::string& name);

/// A 1-component view (e.g. "activation"), found and checked as read_gmsh_vector_view.
struct GmshScalarView {
  std::vector<long long> tags;
  std::vector<double> values;
  std::vector<int> lines;  ///< file line of each entry, for messages
};
GmshScalarView read_gmsh_scalar_view(const std::string& file, GmshDataOn on, const std::string& name);

}  // namespace fe2
