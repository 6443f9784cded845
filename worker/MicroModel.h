#pragma once
// Everything about a micro unit that does not change while it runs and is the same
// for every unit built from one spec: the periodic hex mesh, its materials, the
// periodic DOF map, element geometry, the fixed sparsity pattern of K with each
// element's scatter positions, and the solver options. Shared read-only
// (std::shared_ptr<const MicroModel>) by all units of that spec on a rank.
#include "common/materials/Material.h"
#include "common/mesh/HexMesh.h"
#include "common/spec/SpecNode.h"
#include "worker/PeriodicDofMap.h"
#include "worker/SparseFactor.h"
#include "worker/hex8.h"
#include "worker/micro_cell.h"
#include "worker/micro_memory.h"

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace fe2 {

/// How a unit keeps its factor of K and its characteristic modes χ (paper Fig. 6).
struct MicroSolverOptions {
  enum class Factorization { cholesky, lu, automatic };
  enum class Refresh { every_iteration, fixed, adaptive, collective };
  Factorization factorization = Factorization::automatic;
  Refresh refresh = Refresh::collective;  ///< docs/solvers.md, "How often to refactor"
  int N_t = 10;              ///< fixed policy: refresh at iteration 1 of every N_t-th step
  bool step4 = true;         ///< Eq. (11): δw = δw₁ − χ ΔZ̄
  double gmres_rtol = 1e-10; ///< Step 1: ‖K δw₁ + r‖ <= gmres_rtol ‖r‖ (the tightest it asks)
  /// Step 1's tolerance over a Newton solve: constant (gmres_rtol), or `residual`, the
  /// inexact-Newton forcing η = ‖r‖/r_ref within [gmres_rtol, gmres_forcing_max].
  enum class Forcing { constant, residual };
  Forcing gmres_forcing = Forcing::residual;
  double gmres_forcing_max = 1e-4;  ///< if below gmres_rtol, Step 1 uses gmres_rtol
  /// The unit's Newton tolerance (the run's newton.micro_rtol): the forcing never asks
  /// Step 1 for a residual below half of it, 0.5·newton_rtol·r_ref.
  double newton_rtol = 1e-8;
  int gmres_restart = 50;
  int gmres_max_iterations = 500;
  /// What a flop of a solve or a product with K costs in flops of a factorization (which
  /// runs BLAS-3, several times faster per flop): weighs a stale Step 1's iterations
  /// against a refresh in the rental policies' budget within a job (RefreshPolicy).
  double solve_flop_cost = 4.0;
  /// The factor in single precision, used only as the GMRES preconditioner: the answer
  /// stays double, the factor costs half the memory. The LLᵀ kind uses the supernodal
  /// float LLᵀ (worker/FloatCholeskyFactor.h) unless single_factor_mumps; LU is MUMPS.
  bool single_precision = false;
  bool single_factor_mumps = false;
  /// precision "half": the supernodal float LLᵀ kept in IEEE binary16 between solves (a
  /// quarter of the double factor's bytes); factored in float, LU stays MUMPS single.
  bool half_storage = false;
  double blr_tolerance = 0.0;  ///< single precision only: block low-rank threshold, 0 = off

  /// Step 1's relative tolerance η at a unit residual ‖r‖/r_ref = `relative_residual`.
  double step1_rtol(double relative_residual) const;

  /// Reads /.../solver; every key optional.
  static MicroSolverOptions from_spec(SpecNode node);
};

class MicroModel;

/// A unit model read from its spec but not yet built: its cell (a built-in layout or a
/// mesh read from file), materials and options, and what building it will cost. Reading
/// a plan allocates at most the mesh of a mesh file, so a spec can be checked and its
/// memory refused before the pattern, geometry or any factor exists.
struct MicroModelPlan {
  std::string path;          ///< the unit's spec path, e.g. /models/myocardium/unit
  std::string size_key;      ///< the key that sets its size: <path>/resolution or /mesh_file
  std::string source;        ///< labels errors: the mesh file, or the spec path
  std::optional<CellLayout> layout;  ///< built-in cell
  std::optional<HexMesh> file_mesh;  ///< cell read from a mesh file
  std::vector<std::string> region_names;
  std::vector<MaterialPtr> materials;  ///< one per region name
  MicroSolverOptions options;
  MicroMemoryEstimate memory;

  /// What can be checked without the heavy parts, in O(mesh): the cell meshes with
  /// every region present, is periodic, and every region has a material. Returns the
  /// unit's number of DOF.
  int check() const;
  /// Whether a unit of this plan may factor with MUMPS (single precision with LU, which
  /// the automatic policy falls back to on an unsymmetric or indefinite K, or with
  /// single_factor "mumps"): MUMPS calls MPI, so such units run on a rank's main thread.
  bool may_run_mumps() const;
  std::shared_ptr<const MicroModel> build() const;
};

class MicroModel {
 public:
  /// Reads a unit spec object (see `fe2heart spec-doc`) without building the model;
  /// `base_dir` resolves relative mesh files.
  static MicroModelPlan plan(SpecNode node, const std::string& base_dir);
  /// plan(node, base_dir).build()
  static std::shared_ptr<const MicroModel> from_spec(SpecNode node, const std::string& base_dir);
  /// Builds from a ready mesh and one material per region.
  MicroModel(HexMesh mesh, std::vector<MaterialPtr> materials, MicroSolverOptions options,
             const std::string& source);

  const HexMesh& mesh() const { return mesh_; }
  const PeriodicDofMap& dofs() const { return dofs_; }
  const MicroSolverOptions& options() const { return options_; }
  const Material& material_of(int e) const { return *materials_[mesh_.region[e]]; }
  /// Elements of equal shape share one geometry (bit for bit: a voxel cell has a few
  /// hundred distinct ones among thousands of elements), so an assembly reads it from
  /// cache instead of streaming 1.6 KB per element.
  const HexGeometry& geometry(int e) const { return geometry_[geometry_of_[e]]; }
  /// How many distinct element geometries the mesh has.
  int num_distinct_geometries() const { return static_cast<int>(geometry_.size()); }
  int num_dofs() const { return dofs_.num_dofs(); }
  int num_elements() const { return mesh_.num_hexes(); }
  double inv_volume() const { return 1.0 / mesh_.volume(); }
  /// Equation of element unknown 8i + a, or -1 for the pinned node.
  const std::array<int, 24>& element_equations(int e) const { return eq_[e]; }
  /// Where element e's matrix goes in K's value array: entry (8i+a, 8k+b) at
  /// block[8a+b] + i + k·stride[b], block −1 when node a or b is pinned. A node's three
  /// rows are adjacent in every column and its three columns hold the same rows, so
  /// 72 ints per element locate all 576 entries (and stream 8× less per assembly).
  struct ElementScatter {
    std::array<int, 64> block;  ///< position of (row of node a's x, column of node b's x)
    std::array<int, 8> stride;  ///< column length of node b's columns
  };
  const ElementScatter& scatter(int e) const { return scatter_[e]; }
  /// The zero-valued K with the fixed pattern, to copy into each unit.
  const SparseMatrix& pattern() const { return pattern_; }
  /// A fresh copy of pattern() whose values lie on large pages (worker/large_pages.h):
  /// an assembly adds into them at scattered places. What units assemble into.
  SparseMatrix zero_matrix() const;
  /// True when every material's tangent has major symmetry, so H = Gᵀ and K is symmetric.
  bool symmetric() const { return symmetric_; }
  /// ‖ρ‖ with ρ_a = ⟨|∇N_a|⟩ over periodic nodes: r_ref = max(‖P̄‖, σ_floor) · node_scale.
  double node_scale() const { return node_scale_; }
  /// Stress floor for r_ref: 1e-6 × the stiffest material's scale.
  double stress_floor() const { return stress_floor_; }
  /// Which factorization a fresh unit starts with.
  FactorKind initial_factor_kind() const;
  /// An empty factor of that kind in the precision the options ask for.
  std::unique_ptr<SparseFactor> make_factor(FactorKind kind) const;
  /// Content hash of mesh, materials layout and options (checks deserialized state).
  uint64_t fingerprint() const { return fingerprint_; }
  /// Whether element e's law reads its point context (Material::uses_context).
  bool uses_context(int e) const { return uses_context_[mesh_.region[e]] != 0; }
  /// Doubles of point history in one unit: Σ_e 8 · (history_size of e's law); 0 when no
  /// law keeps history (then units allocate none).
  size_t history_size() const { return history_offset_.empty() ? 0 : history_offset_.back(); }
  /// Every Gauss point's history as its law starts it (Material::initial_history).
  void initial_history(std::span<double> history) const;
  /// Where element e's history (8 Gauss points, point q at q · history_size of its law)
  /// starts in a unit's history array.
  size_t history_offset(int e) const { return history_offset_.empty() ? 0 : history_offset_[e]; }

 private:
  HexMesh mesh_;
  std::vector<MaterialPtr> materials_;
  MicroSolverOptions options_;
  PeriodicDofMap dofs_;
  std::vector<HexGeometry> geometry_;  ///< distinct geometries
  std::vector<int> geometry_of_;       ///< element → its geometry in geometry_
  std::vector<std::array<int, 24>> eq_;
  std::vector<ElementScatter> scatter_;
  SparseMatrix pattern_;
  bool symmetric_ = true;
  double node_scale_ = 1.0;
  double stress_floor_ = 0.0;
  uint64_t fingerprint_ = 0;
  std::vector<uint8_t> uses_context_;   ///< per region
  std::vector<size_t> history_offset_;  ///< num_elements + 1 prefix sums; empty without history
};

using MicroModelPtr = std::shared_ptr<const MicroModel>;

}  // namespace fe2
