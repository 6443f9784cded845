#pragma once
// Per-element activation times from a file (activation kind "file"), with the
// conventions of fibre files (FileFrame.h):
//  - CSV: lines "tag,time" keyed by element tag; blank lines, lines starting with '#'
//    and a first line that is not numbers (a header) are skipped;
//  - Gmsh: a 1-component $ElementData view of a MSH 4.1 file (default "activation"),
//    keyed by the element tags of the mesh file.
// For a mesh that is not a Gmsh file (a generator) tag = index + 1. Exactly one time
// per tetrahedron, none missing, each finite and >= 0 (s); anything else is an
// InputError naming the file, the line and tag, and the value.
#include "common/mesh/TetMesh.h"

#include <string>
#include <vector>

namespace fe2 {

struct ActivationFileOptions {
  std::string file;                ///< the activation file
  bool csv = false;                ///< CSV, else a Gmsh view
  std::string view = "activation"; ///< Gmsh view name
  std::string mesh_file;           ///< Gmsh mesh the tags refer to ("" : tag = index + 1)
};

/// The time of every tet of `mesh`, read and checked.
std::vector<double> read_activation_file(const TetMesh& mesh, const ActivationFileOptions& opt);

}  // namespace fe2
