#pragma once
// A structured tetrahedral mesh of an axis-aligned box, for tests and simple scenes.
#include "common/mesh/TetMesh.h"

#include <array>

namespace fe2 {

/// Meshes the box [lo, hi] with divisions[0] x divisions[1] x divisions[2] hexahedral
/// cells, each split into 6 positively oriented tets around its main diagonal
/// (Kuhn/Freudenthal split: the same diagonal direction in every cell keeps the mesh
/// conforming). Named faces "xmin", "xmax", "ymin", "ymax", "zmin", "zmax" (outward
/// triangles, each also a node set). Node (i,j,k) of the grid has index
/// i + (nx+1)*(j + (ny+1)*k).
///
/// Regions: with region_slabs_axis in {0,1,2} the cells are grouped into region_slabs
/// slabs along that axis, tagged 1..region_slabs; slab boundaries fall on cell planes
/// (equal slabs when divisions[axis] is a multiple of region_slabs). With -1 every
/// tet is region 1. `order` 2 adds a node at the midpoint of every edge (10-node tets,
/// numbered after the grid nodes). Throws InputError for divisions < 1, hi <= lo, bad
/// slab arguments or an order other than 1 or 2.
TetMesh make_box_mesh(const Vec3& lo, const Vec3& hi, std::array<int, 3> divisions,
                      int region_slabs_axis = -1, int region_slabs = 1, int order = 1);

}  // namespace fe2
