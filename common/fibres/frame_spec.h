#pragma once
// The run spec's "frame" object, every kind: what the reader reads (one place for
// coordinator/RunSpec.cpp's read_frame) and how the field is built from it.
//   constant: fibre, sheet
//   rotating: fibre, sheet, axis, coordinate, from, to      (AnalyticFrame.h)
//   file:     file, format (gmsh | csv), per (element | node | point), fibre_view, sheet_view
//   rule:     alpha_endo, alpha_epi, beta_endo, beta_epi (degrees), endo, epi, base,
//             apex ("": found), rv_endo (set: biventricular)  (RuleFrame.h)
#include "common/fibres/AnalyticFrame.h"
#include "common/fibres/FileFrame.h"
#include "common/fibres/RuleFrame.h"
#include "common/spec/SpecNode.h"

#include <memory>
#include <string>

namespace fe2 {

struct FrameFieldSpec {
  enum class Kind { constant, rotating, file, rule };
  Kind kind = Kind::constant;
  AnalyticFrame analytic;   ///< constant, rotating
  FileFrameOptions file;    ///< file
  RuleFrameOptions rule;    ///< rule
  /// file: the field, read and checked with the spec (so `validate` reports bad files).
  std::shared_ptr<const FrameField> loaded;
};

/// Reads the keys of a "frame" object (not finish(): the caller does). Checks what needs
/// the mesh: a "file" field is read and checked in full; a "rule" field's surfaces must
/// be named sets of the mesh (its Laplace problems are solved by make_frame_field).
/// `base_dir`: where relative file names resolve; `gmsh_mesh_file`: the Gmsh file the
/// mesh came from, whose tags a fibre file refers to ("" for a generated mesh: tag =
/// index + 1); `quadrature_degree`: the macro points' tet rule, by which a file per
/// point numbers its points (formulation.quadrature_degree; −1: 2(order − 1)).
FrameFieldSpec read_frame_field_spec(SpecNode& f, const TetMesh& mesh, const std::string& base_dir,
                                     const std::string& gmsh_mesh_file, int quadrature_degree = -1);

/// The frame field of `spec` on `mesh` (rule: solves its Laplace problems now).
std::shared_ptr<const FrameField> make_frame_field(const FrameFieldSpec& spec, const TetMesh& mesh);

}  // namespace fe2
