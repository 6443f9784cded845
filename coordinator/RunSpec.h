#pragma once
// A run spec (`fe2heart run SPEC.json`), read and checked in one place: every key is
// declared once in the spec schema (common/spec/spec_schemas.cpp), which gives this
// reader every default, range and help text and `fe2heart spec-doc` and `spec-schema` print.
//
// A scene names its effects; an effect that is off allocates and assembles nothing:
//   point models (FE² units or the macro law, per region), Dirichlet conditions,
//   follower pressure, inertia (Newmark), probes.
#include "common/activation/ActivationField.h"
#include "common/circulation/Circulation.h"
#include "common/fibres/frame_spec.h"
#include "common/materials/Material.h"
#include "common/mesh/TetMesh.h"
#include "common/spec/SpecNode.h"
#include "coordinator/farm/FarmOptions.h"
#include "coordinator/LoadStepper.h"
#include "coordinator/macro/FluidSetup.h"
#include "coordinator/macro/LineSearch.h"
#include "coordinator/macro/MacroSolverOptions.h"
#include "worker/MicroModel.h"
#include "worker/point_models.h"

#include <limits>
#include <map>
#include <string>
#include <vector>

namespace fe2 {

/// Load scaling in time: value(t) = value · λ(t).
enum class Ramp { linear, constant };
double ramp_factor(Ramp ramp, double t, double t_end);

struct DirichletSpec {
  std::string set;
  std::array<bool, 3> fixed{true, true, true};
  Vec3 value = Vec3::Zero();
  Ramp ramp = Ramp::linear;
};

struct PressureSpec {
  std::string surface;
  double value = 0.0;  ///< Pa, acting against the outward normal of the solid
  Ramp ramp = Ramp::linear;
};

/// Fibre frame rule: constant, or (f0, s0) rotated about `axis` by an angle varying
/// linearly with X·coordinate between two planes (a transmural helix rule). `field`
/// holds every kind (also "file" and "rule"): make_frame_field(field, mesh) builds the
/// FrameField (common/fibres/), which replaces at() once the macro side calls it.
struct FrameSpec {
  FrameFieldSpec field;
  std::shared_ptr<const FrameField> built;  ///< the field, once built (else make_frame_field)
  Vec3 fibre = Vec3::UnitX();
  Vec3 sheet = Vec3::UnitY();
  bool rotating = false;
  Vec3 axis = Vec3::UnitZ();
  Vec3 coordinate = Vec3::UnitY();
  double c0 = 0, c1 = 1, angle0 = 0, angle1 = 0;  ///< angles in radians
  /// Orthonormal Q = [f s n] at X.
  Mat3 at(const Vec3& X) const;
};

/// The macro discretization. Displacement order = the mesh's (P1 or P2); `mixed` adds a
/// P1 pressure p (positive in compression) on the vertices: Taylor–Hood P2/P1 on
/// quadratic meshes, stabilized equal-order P1/P1 on linear ones.
struct FormulationSpec {
  bool mixed = false;
  /// Perturbed Lagrangian J̄ − 1 = −p/κ; +∞: Lagrange multiplier (J̄ = 1).
  double bulk_modulus = std::numeric_limits<double>::infinity();
  double stabilization_modulus = 0.0;  ///< μ_s of P1/P1 (0: none)
  /// Pressure P1+P0 (enriched Taylor–Hood): a constant per element besides the P1
  /// field, so each element's volume is held, not only P1-weighted means.
  bool element_pressure = false;
  int quadrature_degree = -1;          ///< −1: 2(order − 1)
};

/// Built by read_run_spec only: a member read from the spec has no default here (the
/// spec schema holds it), so a zero is never an answer.
struct RunSpec {
  std::string file;        ///< where it was read from ("" when built in code)
  std::string base_dir;    ///< relative files resolve here
  std::string title;
  json raw;                ///< the whole spec (for the output folder and hashes)

  TetMesh mesh;
  std::string mesh_source;
  /// Region tags of the solid wall (mesh.wall_regions; empty: every region). Only its
  /// elements carry the displacement, the pressure and the point models (FE² units);
  /// other regions are left to the fields that live there.
  std::vector<int> wall_regions;  ///< ascending
  FrameSpec frame;
  /// When each point's cells are excited ("activation"); null: all at t = 0.
  std::shared_ptr<const ActivationField> activation;
  std::vector<PointModelSpec> models;
  std::map<int, int> model_of_region;  ///< region tag -> model index
  int default_model = 0;

  FormulationSpec formulation;
  int points_per_element = 1;          ///< of the quadrature rule (point models per element)

  std::vector<DirichletSpec> dirichlet;
  std::vector<PressureSpec> pressure;

  double t_end = 0;
  int steps = 0;
  bool dynamic = false;    ///< Newmark-β with a mass matrix
  double beta = 0, gamma = 0, density = 0;
  int beats = 0;                  ///< time.beats (0: t_end and steps); t_end = beats · period
  int steps_per_beat = 0;
  double periodic_tolerance = 0;  ///< stop once the EDV changes less than this over a beat
  /// time.inflation_steps: the first steps (of `steps`) inflate the wall to end-diastole
  /// in [t_start, 0]; the beat is (0, t_end].
  int inflation_steps = 0;
  double t_start = 0;             ///< −inflation_steps · the beat's step (0 without inflation)
  /// The nominal step (t_end − t_start) / steps.
  double dt() const { return (t_end - t_start) / steps; }
  /// Where step `step` (from 0) ends.
  double step_end_time(int step) const {
    if (step + 1 == steps) return t_end;
    if (step + 1 == inflation_steps) return 0.0;  // exactly: the beat starts there
    return t_start + (step + 1) * dt();
  }
  /// Whether a step ending at `t` inflates the wall (time.inflation_steps).
  bool inflating(double t) const { return inflation_steps > 0 && t <= 0.0; }

  int newton_max_iterations = 0;
  double newton_rtol = 0;         ///< macro residual, relative to max(‖f_int‖, ‖f_ext‖)
  /// newton.field_rtol: macro field name -> its tolerance (others: newton_rtol).
  std::map<std::string, double> field_rtol;
  double rtol_of(const std::string& field) const;
  double micro_rtol = 0;          ///< each unit: ‖r‖ <= micro_rtol · r_ref
  int max_cutbacks = 0;
  LoadStepOptions load_steps;     ///< time.adaptive and its bounds; max_cutbacks (coordinator/LoadStepper.h)
  LineSearchOptions line_search;  ///< newton.line_search (coordinator/macro/LineSearch.h)
  MacroSolverOptions macro_solver;  ///< newton.macro_solver: when the macro factor is refreshed

  FarmOptions farm;
  uint64_t hash = 0;              ///< of the spec's canonical text (ranks compare it)

  std::vector<std::pair<std::string, Vec3>> probes;
  /// Legal but likely unintended settings, for the log (`run`, `validate`).
  std::vector<std::string> warnings;
  std::vector<std::pair<std::string, std::string>> cavities;  ///< (name, bounding face)
  /// The 0D circulation ("circulation"; null: none) and, per circulation cavity, its
  /// index in `cavities`: those cavities' pressures are unknowns of the macro system.
  std::shared_ptr<const Circulation> circulation;
  std::vector<int> coupled_cavities;
  /// Blood on the fluid regions ("fluid"; null: none), macro/fluid_scene.h.
  std::shared_ptr<const FluidSetup> fluid;
  int output_every = 0;
  int checkpoint_every = 0;       ///< output.checkpoint_every (0: only on a signal)
  bool checkpoint_factors = false;  ///< output.checkpoint_factors: units' numeric factors in the checkpoint
  bool write_vtu = false;
  /// output.units: points (FE² units) whose micro fields are written at output steps.
  std::vector<int> output_units;

  bool is_wall_region(int tag) const;
  bool is_wall(int e) const;
  /// The wall's elements (is_wall), ascending.
  std::vector<int> wall_elements() const;
  /// The wall's elements among `elements` (ascending), in their order.
  std::vector<int> wall_elements_among(const std::vector<int>& elements) const;
  int model_index_of_tet(int e) const;
  /// Whether some point model has contracting cells (active stress).
  bool contracts() const;
  /// Model index of every integration point, in point order (wall element after wall
  /// element, points_per_element each; MacroPoints).
  std::vector<int> model_of_points() const;
  int num_points() const { return points_per_element * static_cast<int>(wall_elements().size()); }
};

/// Reads and checks a spec; every problem is an InputError naming the key.
/// Every key is read by run_spec_schema(); `doc`, if given, records those read.
/// `build_units` false: FE² models are only planned (PointModelSpec::plan, with their
/// memory estimate), so they can be refused before allocation; build_unit_models builds them.
/// `key` of `node`: a non-empty array of region tags or names of the spec's mesh, each
/// once (ascending tags); an InputError naming the entry and the regions there are otherwise.
std::vector<int> read_region_list(SpecNode& node, const std::string& key, const RunSpec& spec);

RunSpec read_run_spec(const json& j, const std::string& file, SpecDoc* doc = nullptr,
                      bool build_units = true);
RunSpec read_run_spec_file(const std::string& file, bool build_units = true);
void build_unit_models(RunSpec& spec);

}  // namespace fe2
