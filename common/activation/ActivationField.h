#pragma once
// The activation time t_act (s) of every material point: when its calcium transient
// starts. One of
//  - uniform: the same time everywhere ("uniform");
//  - per vertex: P1 interpolation of vertex times at the point's barycentric
//    coordinates ("eikonal", eikonal.h);
//  - per element: one time for each element's points ("file", activation_file.h).
#include "common/fibres/FrameField.h"
#include "common/mesh/TetMesh.h"

#include <array>
#include <vector>

namespace fe2 {

class ActivationField {
 public:
  enum class Kind { uniform, per_vertex, per_element };

  static ActivationField uniform(double time);
  /// `node_times` per node of `mesh` (solve_eikonal's result); the field interpolates
  /// the 4 vertex times of each tet.
  static ActivationField per_vertex(const TetMesh& mesh, std::vector<double> node_times);
  /// One time per tet of the mesh.
  static ActivationField per_element(std::vector<double> element_times);

  Kind kind() const { return kind_; }

  /// t_act at the point of element e with barycentric coordinates λ (TetMesh::tets
  /// order); throws fe2::Error for an element outside the field's mesh.
  double at(int e, const Bary& lambda) const;

  /// Per node of `mesh`, for VTU point data: uniform the time, per vertex the times
  /// (edge nodes: the mean of their edge's vertices), per element the mean of the
  /// elements holding the node (for viewing only: the points use the element time).
  std::vector<double> node_times(const TetMesh& mesh) const;
  /// Per element at its centroid, for VTU cell data.
  std::vector<double> element_times(const TetMesh& mesh) const;

 private:
  Kind kind_ = Kind::uniform;
  double time_ = 0.0;                      ///< uniform
  std::vector<double> values_;             ///< per node, or per element
  std::vector<std::array<int, 4>> tets_;   ///< per vertex: each tet's vertices
};

}  // namespace fe2
