#pragma once
// The macro problem a spec's scene asks for, built from data: its fields (FieldTable.h),
// its constraints (Constraints.h) and its terms (MacroTerm.h). An effect that is off adds
// no field and builds no term. The driver (Simulation) names no field: it numbers,
// integrates in time, assembles and measures whatever this file declares.
//
// The displacement and the pressure live on the wall (RunSpec::wall_regions).
//
//   field            when                       term(s)
//   displacement     always                     PointStressTerm; InertiaTerm (newmark);
//                                               FollowerPressureTerm (/pressure)
//   pressure         formulation.kind = mixed   IncompressibilityTerm
//   cavity_pressure  a circulation is coupled   CavityPressureTerm
//   fluid_*, mesh_displacement   "fluid"       fluid_scene.h (Navier–Stokes, boundaries, mesh motion)
#include "coordinator/RunSpec.h"
#include "coordinator/macro/MacroPartition.h"
#include "coordinator/macro/MacroSystem.h"
#include "coordinator/macro/MacroTerm.h"
#include "coordinator/macro/PointStressTerm.h"

#include <functional>
#include <memory>

namespace fe2 {

/// Fields and constraints beyond the spec's scene (fields of physics the spec does not
/// name yet, a test-only field), added through the table alone; their terms join with
/// Simulation::add_term and find the fields by name.
struct MacroExtension {
  std::vector<FieldDecl> fields;
  /// Adds constraints on the numbered fields (prescribed values, ties).
  std::function<void(const FieldTable&, MacroConstraints&)> constrain;
  /// Sets the initial state at t_start of its fields (values x and rates v; the rest
  /// stays zero); may be empty.
  std::function<void(const FieldTable&, Eigen::VectorXd& x, Eigen::VectorXd& v)> initial;
};

/// The spec's fields beyond the wall's (its fluid) joined with `extension`: theirs first.
MacroExtension scene_extension(const RunSpec& spec, const MacroExtension& extension);

/// The scene's fields, in block order: ū, then p, then p_c, then the fluid's, then the
/// extension's.
FieldTable scene_fields(const RunSpec& spec, const MacroExtension& extension = {});

/// The macro system: the scene's fields numbered on the mesh; the spec's Dirichlet
/// conditions on ū (a later condition on the same DOF replaces an earlier one), then the
/// extension's constraints.
MacroSystem make_macro_system(const RunSpec& spec, const MacroExtension& extension = {});

/// The scene's terms over this coordinator's `partition` of the mesh (the wall terms
/// over its wall elements, the surface loads over its elements' faces, the cavity rows
/// where it owns the global unknowns); `responses` (the owned points' answers) is lent
/// to the point-stress term.
std::vector<std::unique_ptr<MacroTerm>> scene_terms(const RunSpec& spec, const MacroPoints& points,
                                                    const MacroPartition& partition,
                                                    const std::vector<PointResponse>& responses);

}  // namespace fe2
