#pragma once
// A frame field given in a file (frame kind "file"): a fibre and a sheet vector per
// element or per node.
//  - Gmsh: two 3-component views of a MSH 4.1 file ($ElementData or $NodeData, named
//    e.g. "fibre" and "sheet"), keyed by the element or node tags of the mesh file;
//  - CSV: lines "tag,fx,fy,fz,sx,sy,sz" keyed by element (or node) tag; blank lines,
//    lines starting with '#' and a first line that is not numbers (a header) are skipped.
// For a mesh that is not a Gmsh file (the box generator) tag = index + 1.
// Every vector is checked on reading: |f|, |s| within 1e-3 of 1, |f·s| <= 1e-3, exactly
// one entry per element/node, none missing; anything else is an InputError naming the
// file, the tag and the value. The vectors are stored as read (bit for bit).
// Evaluation: per element, the element's vectors; per node, f and s interpolated with
// the element's shape functions (P1, or P2 on a quadratic mesh, from λ), nodal signs
// first aligned with the element's first node (f and −f are the same fibre), then
// re-orthonormalized: f normalized, s Gram–Schmidt against f.
#include "common/fibres/FrameField.h"
#include "common/mesh/TetMesh.h"

#include <string>
#include <vector>

namespace fe2 {

struct FileFrameOptions {
  std::string file;              ///< the fibre file
  bool csv = false;              ///< CSV, else Gmsh MSH 4.1 views
  bool per_node = false;         ///< per node, else per element
  std::string fibre_view = "fibre", sheet_view = "sheet";  ///< Gmsh view names
  std::string mesh_file;         ///< Gmsh mesh the tags refer to ("" : tag = index + 1)
};

inline constexpr double kFrameFileTolerance = 1e-3;

class FileFrame : public FrameField {
 public:
  /// Reads and checks the file for `mesh` (which must outlive nothing: the element
  /// nodes are copied).
  FileFrame(const TetMesh& mesh, const FileFrameOptions& opt);

  Mat3 at(int e, const Bary& lambda, const Vec3& X) const override;

  bool per_node() const { return per_node_; }
  /// The vectors as read, per element or per node (mesh numbering).
  const std::vector<Vec3>& fibres() const { return f_; }
  const std::vector<Vec3>& sheets() const { return s_; }

 private:
  bool per_node_;
  std::vector<std::vector<int>> element_nodes_;  ///< per node only: TetMesh::element_nodes
  std::vector<Vec3> f_, s_;
  std::string file_;
};

}  // namespace fe2
