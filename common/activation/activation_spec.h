#pragma once
// The run spec's "activation" object: when each material point's calcium transient
// starts (ActivationField.h). Kinds:
//   uniform: time                                         (one time everywhere)
//   eikonal: sources [{surface | point, time}], velocity  (eikonal.h)
//   file:    file, format (gmsh | csv), view              (activation_file.h)
// The keys, defaults and ranges are the same as activation_schema() declares.
#include "common/activation/ActivationField.h"
#include "common/fibres/FrameField.h"
#include "common/mesh/TetMesh.h"
#include "common/spec/SpecNode.h"

#include <memory>
#include <string>

namespace fe2 {

/// Default conduction velocities (mm/s, for meshes in mm): the orthotropic velocities
/// measured in pig left-ventricular myocardium by Caldwell et al. 2009 ("Three distinct
/// directions of intramural activation reveal nonuniform side-to-side electrical
/// coupling of ventricular myocytes", Circ. Arrhythm. Electrophysiol. 2:433–440):
/// 0.67 m/s along the fibres, 0.30 m/s along the sheets, 0.17 m/s across them.
inline constexpr double kDefaultVelocityFibre = 670.0;
inline constexpr double kDefaultVelocitySheet = 300.0;
inline constexpr double kDefaultVelocityNormal = 170.0;

/// Reads an "activation" object (and finish()es it and its sources) and builds the
/// field: "eikonal" solves now, "file" reads and checks the file now (so `validate`
/// reports both). `frames` (lent; may be null when the velocity is isotropic) gives the
/// fibre frame of each element at its centroid; `base_dir` is where relative file
/// names resolve; `gmsh_mesh_file` the Gmsh file the mesh came from, whose element tags
/// a file refers to ("" for a generated mesh: tag = index + 1). Bad input is an
/// InputError naming the key or file, the value and what was expected.
std::shared_ptr<const ActivationField> read_activation(SpecNode& node, const TetMesh& mesh, const FrameField* frames,
                                                       const std::string& base_dir,
                                                       const std::string& gmsh_mesh_file);

}  // namespace fe2
