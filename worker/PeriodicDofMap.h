#pragma once
// Periodic degrees of freedom of a micro unit: w is periodic on the box Y, so nodes
// that are images of each other across opposite faces share their unknowns, and one
// node is pinned to remove the rigid translation (DESIGN §1).
//
// Images are found geometrically (any hex mesh whose opposite faces match works, a
// Gmsh cell as well as the built-in grids); a node on a face with no image on the
// opposite face makes the mesh non-periodic, which is an InputError naming the node.
#include "common/mesh/HexMesh.h"

#include <string>
#include <vector>

namespace fe2 {

class PeriodicDofMap {
 public:
  /// `source` names the mesh in error messages.
  PeriodicDofMap(const HexMesh& mesh, const std::string& source);

  /// Global equation number of component i of node `node`, or -1 if pinned.
  int dof(int node, int i) const { return dof_[3 * node + i]; }
  /// The periodic representative ("master") of a node.
  int master(int node) const { return master_[node]; }
  int num_dofs() const { return num_dofs_; }
  int num_masters() const { return num_masters_; }
  int pinned_node() const { return pinned_; }

 private:
  std::vector<int> master_;
  std::vector<int> dof_;
  int num_dofs_ = 0;
  int num_masters_ = 0;
  int pinned_ = 0;
};

}  // namespace fe2
