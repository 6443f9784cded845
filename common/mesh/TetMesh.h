#pragma once
// The macro mesh: 4-node tetrahedra with named node sets and named boundary faces.
#include "common/tensor9.h"

#include <array>
#include <map>
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
  /// Named node sets (every named face also gives a node set of the same name).
  std::map<std::string, std::vector<int>> node_sets;

  int num_nodes() const { return static_cast<int>(nodes.size()); }
  int num_tets() const { return static_cast<int>(tets.size()); }
};

/// Signed volume of tet e: (x1-x0)·((x2-x0)×(x3-x0))/6.
double tet_signed_volume(const TetMesh& m, int e);

/// Checks every tet has positive volume (throws fe2::InputError naming the element,
/// its nodes and the volume, and `source` (file name or generator) otherwise), that
/// node indices are in range, and adds a node set for each named face that has none.
void validate_mesh(TetMesh& m, const std::string& source);

/// Orients every named face triangle outward from the tet it bounds; throws
/// InputError if a face triangle is not a boundary face of any tet.
void orient_faces_outward(TetMesh& m, const std::string& source);

}  // namespace fe2
