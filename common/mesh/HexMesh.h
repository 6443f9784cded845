#pragma once
// A micro-unit mesh: 8-node hexahedra with one material region per element. Node
// order as VTK and Gmsh: 0:(-,-,-) 1:(+,-,-) 2:(+,+,-) 3:(-,+,-) (the bottom face,
// counter-clockwise seen from +z), then 4..7 the same on the top face.
#include "common/tensor9.h"

#include <array>
#include <string>
#include <vector>

namespace fe2 {

struct HexMesh {
  std::vector<Vec3> nodes;
  std::vector<std::array<int, 8>> hexes;
  std::vector<int> region;   ///< per hex: material region index (0-based)
  std::vector<std::string> region_names;  ///< per region index, where the mesh names them
  Vec3 lo = Vec3::Zero();    ///< bounding box of the periodic cell Y
  Vec3 hi = Vec3::Zero();

  int num_nodes() const { return static_cast<int>(nodes.size()); }
  int num_hexes() const { return static_cast<int>(hexes.size()); }
  double volume() const { return (hi - lo).prod(); }
};

}  // namespace fe2
