#pragma once
// A frame field given in a file (frame kind "file"): a fibre and a sheet vector per
// element, per node or per integration point.
//  - Gmsh (per element or node): two 3-component views of a MSH 4.1 file ($ElementData
//    or $NodeData, named e.g. "fibre" and "sheet"), keyed by the element or node tags of
//    the mesh file;
//  - CSV: lines "tag,fx,fy,fz,sx,sy,sz" keyed by element (or node) tag, or per point
//    "tag,point,fx,fy,fz,sx,sy,sz" keyed by element tag and the point's index (0-based)
//    in the element's quadrature rule; blank lines, lines starting with '#' and a first
//    line that is not numbers (a header) are skipped. Per point is CSV only: a Gmsh
//    view holds one vector per element or node, and 6·npoints-component views are not
//    read.
// For a mesh that is not a Gmsh file (the box generator) tag = index + 1.
// Every vector is checked on reading: |f|, |s| within 1e-3 of 1, |f·s| <= 1e-3, exactly
// one entry per element/node/point, none missing, a point index that the rule has;
// anything else is an InputError naming the file, the tag (and point) and the value.
// The vectors are stored as read (bit for bit).
// Evaluation (each read frame is [f s n] with f normalized, s Gram–Schmidt against f):
//  - per element: the element's frame;
//  - per node: the nodal frames interpolated as rotations (frame_mean,
//    frame_interpolation.h: the weighted mean on SO(3) modulo the frame's symmetries,
//    bislerp's generalization), weighted by the element's shape functions (P1, or P2 on a
//    quadratic mesh, from λ). Not as vectors: a helix turning by tens of degrees per
//    element keeps its angle (interpolated as an angle), and f and −f are one fibre;
//  - per point: at a point of the rule (λ within 1e-12 of the rule's), that point's frame
//    exactly; elsewhere (the centroid, for the VTU output and the activation front) the
//    element's mean frame, the points' frames averaged with the rule's weights.
// Points are numbered as coordinator/MacroPoints numbers them: the tet rule of degree
// `quadrature_degree` (formulation.quadrature_degree; −1: 2(order − 1)).
#include "common/fibres/FrameField.h"
#include "common/fem/quadrature.h"
#include "common/mesh/TetMesh.h"

#include <Eigen/Geometry>

#include <string>
#include <vector>

namespace fe2 {

enum class FramePer { element, node, point };

struct FileFrameOptions {
  std::string file;              ///< the fibre file
  bool csv = false;              ///< CSV, else Gmsh MSH 4.1 views
  FramePer per = FramePer::element;
  int quadrature_degree = -1;    ///< per point: the rule the points are numbered by (−1: 2(order − 1))
  std::string fibre_view = "fibre", sheet_view = "sheet";  ///< Gmsh view names
  std::string mesh_file;         ///< Gmsh mesh the tags refer to ("" : tag = index + 1)
};

inline constexpr double kFrameFileTolerance = 1e-3;
/// Per point: how close λ must be to a rule point's to be that point.
inline constexpr double kFramePointMatch = 1e-12;

class FileFrame : public FrameField {
 public:
  /// Reads and checks the file for `mesh` (which must outlive nothing: the element
  /// nodes are copied).
  FileFrame(const TetMesh& mesh, const FileFrameOptions& opt);

  Mat3 at(int e, const Bary& lambda, const Vec3& X) const override;

  FramePer per() const { return per_; }
  bool per_node() const { return per_ == FramePer::node; }
  /// Per point: the points per element (the rule's size).
  int points_per_element() const { return static_cast<int>(rule_.size()); }
  /// The vectors as read, per element, per node (mesh numbering) or per point
  /// (e·points_per_element() + k).
  const std::vector<Vec3>& fibres() const { return f_; }
  const std::vector<Vec3>& sheets() const { return s_; }

 private:
  /// The read frame i ([f s n] from f_[i], s_[i]).
  Mat3 frame(std::size_t i) const;

  FramePer per_;
  std::vector<std::vector<int>> element_nodes_;  ///< per node only: TetMesh::element_nodes
  std::vector<TetQuadraturePoint> rule_;         ///< per point only
  std::vector<Vec3> f_, s_;
  std::vector<Eigen::Quaterniond> q_;            ///< per node or point: frame(i) as a quaternion
  std::string file_;
};

}  // namespace fe2
