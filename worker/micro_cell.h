#pragma once
// Built-in periodic cells for micro units, meshed with 8-node hexahedra on a box
// [0,L1]x[0,L2]x[0,L3] at any resolution. Axis 1 is the cells' long axis (fibre).
//  - homogeneous: one region (0).
//  - laminate:    two phases alternating along one axis; region 0 where the element
//                 centroid lies below `fraction` of the cell, region 1 above.
//  - two_cells:   paper Fig. 4: two cardiac cells (region 1) end to end along axis 1,
//                 each of length (L1/2 − gap·L1) and cross-section `cross_section`
//                 of L2 and L3, embedded in extracellular matrix (region 0).
// Elements are classified by their centroid, so a region thinner than an element
// disappears; the generator refuses a resolution that loses a region.
#include "common/mesh/HexMesh.h"

#include <array>
#include <string>

namespace fe2 {

struct CellLayout {
  std::string kind = "two_cells";    ///< homogeneous | laminate | two_cells
  Vec3 size = Vec3(1.0, 0.25, 0.25);
  std::array<int, 3> resolution = {8, 4, 4};
  double fraction = 0.5;             ///< laminate: volume fraction of region 0
  int axis = 0;                      ///< laminate: layer normal axis
  double gap = 0.1;                  ///< two_cells: ECM gap per cell as a fraction of L1
  double cross_section = 0.75;       ///< two_cells: cell width as a fraction of L2, L3
};

/// Number of material regions of a layout.
int num_regions(const CellLayout& layout);

/// Meshes the cell; throws InputError if the resolution loses a region.
HexMesh make_cell_mesh(const CellLayout& layout);

/// How a resolution represents a layout with two regions: the volume fraction of region
/// 1 (the cells; the laminate's upper phase) that its elements give and the one the
/// layout describes, and per axis the smallest resolution (up to 1000) that puts every
/// interface of the layout on element faces, 0 where none does. Classifying elements by
/// centroid moves an interface by up to half an element, so a unit refined from an
/// unresolved resolution may change its microstructure, not only its discretization.
struct CellResolution {
  double realised = 1.0, nominal = 1.0;
  std::array<int, 3> exact = {1, 1, 1};
};
CellResolution cell_resolution(const CellLayout& layout);

}  // namespace fe2
