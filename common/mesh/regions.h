#pragma once
// Regions of a macro mesh (TetMesh::region tags) and the interfaces between them: a
// wall region next to a cavity region shares the nodes of their common faces, where a
// field of one is tied to a field of the other (coordinator/macro/Constraints.h). An
// interface is found from the regions on its two sides, or named (TetMesh::interfaces).
#include "common/mesh/TetMesh.h"

#include <string>
#include <vector>

namespace fe2 {

/// Nodes (every node of the mesh's order) of elements whose region is in `a` and of
/// elements whose region is in `b`, ascending. Empty if the regions do not touch.
std::vector<int> interface_nodes(const TetMesh& mesh, const std::vector<int>& a, const std::vector<int>& b);

/// Nodes (every node of the mesh's order) of the named interface's faces, ascending.
/// InputError naming the interface and those the mesh has if it has none of that name.
std::vector<int> interface_nodes(const TetMesh& mesh, const std::string& name);

}  // namespace fe2
