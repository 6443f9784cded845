#pragma once
// A run of the macro problem and its Newton driver (paper Fig. 5), by roles:
//   MacroProblem   (macro/MacroProblem.h) fields, constraints, terms, state, solve
//   PointCoupling  (PointCoupling.h)      frames, activation, jobs, Z̄, the points' answers
//   Simulation     the Newton iteration in named phases, the time stepper, observables
// One iteration:
//   predict          each field's rates of the trial x (macro/TimeIntegration.h); the
//                    prescribed increment Δx_D
//   evaluate points  (a) Z̄_k = B̄_k ū at every integration point, rotated into the
//                    point's frame (Z̄_μ = R Z̄), with Ż̄, t, Δt; (b–e) the points answer
//                    (𝔸_hom, P̃, P̄)                               [PointEvaluator]
//   assemble         (g) every macro term of the scene into S̄ and the residual
//                    [MacroTerm, macro/macro_scene.h]
//   converge         (i) the true residual (with P̄) of every field, each by its own
//                    norm and tolerance [macro/field_residuals.h], and every unit's ‖r‖
//   solve            (h) S̄ Δx = −R̃ on the coordinators (MUMPS)
//   update           (j) x += Δx (newton.line_search: the next iteration's evaluation is
//                    the trial; one the line search rejects is retracted to x + αΔx,
//                    macro/LineSearch.h)
// Each phase is timed (IterationTiming, the traces). A step that fails (divergence,
// NaN, inverted element, iteration cap) is rolled back and retried shorter by the load
// stepper (LoadStepper.h: fixed halvings up to newton.max_cutbacks, or time.adaptive);
// then the run stops, saying where and why (failure_diagnosis.h names the cause it can).
#include "coordinator/LoadStepper.h"
#include "coordinator/PointCoupling.h"
#include "coordinator/PointEvaluator.h"
#include "coordinator/macro/MacroProblem.h"
#include "common/circulation/Circulation.h"
#include "coordinator/RunSpec.h"
#include "coordinator/farm/Trace.h"
#include "coordinator/macro/macro_scene.h"
#include "proto/Transport.h"

#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace fe2 {

class CavityPressureTerm;

struct FieldResidualHistory {
  std::string field;
  std::vector<double> values;       ///< its residual norm per iteration
  std::vector<double> corrections;  ///< max |Δx| over its free DOFs per correction taken
};

struct StepRecord {
  int step = 0;
  double time = 0.0;
  int iterations = 0;                 ///< Newton iterations of the accepted (sub)steps
  int cutbacks = 0;
  int retries = 0;                    ///< solves again with a valve's state changed (MacroTerm::accept)
  int line_search_backtracks = 0;     ///< trials newton.line_search rejected
  /// Per macro field (table order): its residual norm per iteration (last substep).
  std::vector<FieldResidualHistory> residuals;
  std::vector<double> micro_residuals;///< max_k ‖r_k‖ / r_ref,k per iteration (last substep)
  /// The residual history of `field` (empty if the scene has no such field).
  const std::vector<double>& residual(const std::string& field) const;
  /// The Newton corrections of `field` (MacroProblem::correction_norms; empty if none).
  const std::vector<double>& correction(const std::string& field) const;
  int gmres_iterations = 0;
  int refreshes = 0;
  int factor_evictions = 0;           ///< farm.factor_memory_budget: factors dropped ...
  int factor_rebuilds = 0;            ///< ... and rebuilt on a later job
  double factor_rebuild_cpu_seconds = 0.0;  ///< CPU of those rebuilds (in micro_cpu_seconds)
  int forced_refreshes = 0;           ///< iterations whose units all refactored because Newton stalled
  int collective_refreshes = 0;       ///< refresh "collective": iterations × models whose units all refactored
  double wall_seconds = 0.0;
  double micro_cpu_seconds = 0.0;
  std::vector<double> cavity_volumes;   ///< per spec.cavities, at the end of the step
  std::vector<double> load_pressures;   ///< per spec.pressure, at the end of the step
  std::vector<Vec3> probes;             ///< per spec.probes, deformed position at the end of the step
  std::vector<double> cavity_pressures; ///< coupled: p_c per circulation cavity, Pa
  CavityFlows circulation;              ///< coupled: flows, valves, phases (on the assembling coordinator)
  /// The terms' observables at the end of the step (MacroTerm::observe), in term order.
  std::vector<std::pair<std::string, double>> observables;
};

struct RunResult {
  bool converged = false;
  int steps = 0;                      ///< steps completed
  int newton_iterations = 0;
  std::vector<StepRecord> history;
  std::string error;                  ///< why the run stopped early, if it did
  bool periodic = false;              ///< stopped at a periodic beat (time.periodic_tolerance)
  bool stopped = false;               ///< stopped early on request (a signal), after a whole step
  double edv_change = 0.0;            ///< time.beats: EDV change over the last whole beat
};

class Simulation {
 public:
  /// One process owning every element. `points` is lent.
  Simulation(const RunSpec& spec, PointEvaluator& points, const MacroExtension& extension = {});
  /// A coordinator of a farm owning the elements of `partition` (its part is the group
  /// rank) and their integration points; `coordinators` is lent.
  /// @note Collective on the coordinator group (MUMPS).
  Simulation(const RunSpec& spec, PointEvaluator& points, const proto::Group& coordinators,
             MacroPartition partition, const MacroExtension& extension = {});

  /// Called after every accepted step (for output); may be empty.
  using StepHook = std::function<void(const StepRecord&)>;
  /// Called after every Newton iteration with its phase times (traces); may be empty.
  using IterationHook = std::function<void(const IterationTiming&)>;
  /// `done`: the steps a restarted run has behind it (restore_state first); run()
  /// continues after them. @note Collective.
  RunResult run(const StepHook& on_step = {}, const IterationHook& on_iteration = {},
                RunResult done = {});
  /// run() returns after the step in progress (or the one on_step reports), with
  /// `stopped` set: a batch system's signal, once a checkpoint is written.
  void request_stop() { stop_requested_ = true; }
  /// A stop request polled before every Newton iteration (and so between cut-backs and
  /// line-search trials): when it answers true inside a step, the step is rolled back to
  /// the committed state and run() returns with `stopped` at once. Must answer alike on
  /// every coordinator (reduce over them). @note Collective (it is called collectively).
  void set_stop_poll(std::function<bool()> poll) { stop_poll_ = std::move(poll); }

  /// Checkpoints: the committed macro state (t, ū and its rates, p, each term's
  /// history), the same on every coordinator. Also drops the kept macro factor, so
  /// that this run and one restarted from here start the next step alike (bit for bit).
  void save_state(ByteWriter& w);
  /// Restarts: what save_state wrote. Before run(). @note Not collective.
  void restore_state(ByteReader& r);
  /// After restore_state with fresh points (--fresh-units): they settle at the restored
  /// Z̄ before their first Newton update (PointCoupling::settle_points).
  void settle_fresh_points() { coupling_.settle_points(); }

  /// Adds a macro term (tests: manufactured body forces). Before the first run().
  void add_term(std::unique_ptr<MacroTerm> term);
  /// Replaces the Dirichlet values: value(dof, t) for every prescribed DOF (tests:
  /// manufactured solutions). Before the first run().
  void set_dirichlet_values(std::function<double(int dof, double t)> value) {
    problem_.set_prescribed_values(std::move(value));
  }

  const RunSpec& spec() const { return spec_; }
  const MacroSystem& system() const { return problem_.system(); }
  /// The fill-reducing ordering MUMPS chose for S̄ ("" before the first solve).
  const std::string& macro_ordering() const { return problem_.solver().ordering(); }
  /// The last assembled macro tangent (MacroProblem::tangent).
  Eigen::SparseMatrix<double> macro_tangent() const { return problem_.tangent(); }
  /// Factorizations and kept-factor solves of the macro system so far.
  const MacroSolver::Stats& macro_solver_stats() const { return problem_.solver().stats(); }
  const MacroPoints& points() const { return coupling_.points(); }
  /// Every DOF, field by field (system().fields()).
  const Eigen::VectorXd& state() const { return problem_.x(); }
  /// The block of the field named `name`.
  Eigen::VectorXd field_values(const std::string& name) const { return problem_.field_values(name); }
  /// ū at every mesh node, 3a + i (zero at nodes off the wall).
  Eigen::VectorXd displacement() const {
    return displacement_field_.at_every_node(state(), spec_.mesh.num_nodes());
  }
  /// Pressure at every mesh node (vertices: the unknown; edge nodes: the mean of their
  /// ends, which is the P1 field there); empty without a pressure field.
  std::vector<double> nodal_pressure() const;
  /// A scalar field on the vertices (P1: "pressure", "fluid_pressure") at every mesh
  /// node: the unknown at its vertices, the mean of an edge's ends at its edge nodes (the
  /// P1 field there), zero off the field; empty without such a field.
  std::vector<double> vertex_field_at_nodes(const std::string& name) const;
  /// The rates ẋ of the fields with a time scheme (zero elsewhere), field by field.
  const Eigen::VectorXd& rates() const { return problem_.v(); }
  /// Per element, the constant of an enriched P1+P0 pressure (0 for the first element
  /// and without enrichment): the total pressure is the nodal field plus this.
  std::vector<double> element_pressure() const;
  /// Per point, the last P̄ in the global frame, gathered on coordinator 0.
  /// @note Collective.
  PointFields gather_point_fields() const { return coupling_.gather_fields(); }
  const Mat3& frame(int point) const { return coupling_.frame(point); }
  /// Z̄ at point k of the current ū.
  Vec9 displacement_gradient(int point) const;
  /// Deformed volume of each cavity of the spec (in its order) at the current ū.
  std::vector<double> cavity_volumes() const;
  /// Deformed position of a reference point inside the mesh.
  Vec3 deformed_position(const Vec3& X) const;
  /// output.units: the chosen units' micro fields at the end of the last output step
  /// (on the first coordinator; Simulation::run takes them before the step's commit).
  const std::vector<proto::UnitFields>& unit_fields() const { return unit_fields_; }
  /// Whether step `step` (from 0) writes output: every output.every-th and the last.
  bool is_output_step(int step) const;
  /// The circulation coupling, or null (no "circulation" in the spec).
  const CavityPressureTerm* cavity_term() const { return cavity_term_; }

  /// One Newton solve from the committed state to time t_new; true if converged.
  bool newton(int step, double t_new, double dt, StepRecord& rec);

 private:
  /// One Newton iteration's residuals: each field's norm (table order), the units' max.
  struct Residual {
    std::vector<double> fields;
    double micro = 0.0;          ///< max_k ‖r_k‖ / r_ref,k
  };
  /// A kept-factor Newton that stops contracting: the next iteration refactors every unit.
  struct StallGuard {
    double previous = std::numeric_limits<double>::infinity();
    /// Whether iteration `it` calls for it (`refreshed`: this one already refactored all).
    bool stalled(int it, double measure, bool converged, bool refreshed);
  };
  enum class Outcome {
    converged,  ///< the iterate is the step's answer
    solved,     ///< a new correction is ready for update
    rejected,   ///< the line search rejects this trial: retract to a shorter one
  };
  /// One iteration (predict, evaluate points, assemble, converge, solve); `search` (null
  /// without a line search) judges the iterate before a new correction is solved for.
  /// @note Collective.
  Outcome iterate(int step, int it, double t_new, double dt, const Eigen::VectorXd* lift, StepRecord& rec,
                  StallGuard& stall, IterationTiming& timing, LineSearch* search);
  /// Residual norms of the assembled iteration, the same on every coordinator. @note Collective.
  Residual converge(double t_new);
  /// "displacement 1.2e-3, pressure 4.0e-9, micro 2.1e-10": for logs and errors.
  std::string describe(const Residual& r) const;
  /// Sums the units' work counters of the iteration into `rec`. @note Collective.
  void account_work(StepRecord& rec) const;
  /// max over the residuals of each one's ratio to its tolerance: converged iff ≤ 1.
  double convergence_measure(const Residual& r) const;
  /// Steps from the committed state to t_target in the sub-steps of the LoadStepper
  /// (fixed: halving on failure, newton.max_cutbacks; or time.adaptive); returns "" or why
  /// it gave up (the state then rolled back). @note Collective.
  std::string advance(int step, double t_target, StepRecord& rec);
  /// Why a failing mixed run's elements may be the cause: failure_diagnosis.h's
  /// volume_diagnosis of the committed state ("" if nothing stands out).
  std::string volume_diagnosis() const;
  /// The step's observables: cavity volumes, probes, cavity pressures and flows, loads, the
  /// terms' observables. @note Collective.
  void observe(StepRecord& rec) const;
  /// time.beats: records the last beat's EDV change; true when below the tolerance.
  bool beat_is_periodic(RunResult& result) const;
  void commit(double t_new, double dt);
  void rollback();

  const RunSpec& spec_;
  proto::Group self_;                  ///< MPI_COMM_SELF for the one-process form
  const proto::Group& group_;
  MacroPartition partition_;
  MacroProblem problem_;
  const Field& displacement_field_;
  PointCoupling coupling_;
  LoadStepper stepper_;                ///< the sub-steps of each step (time.adaptive)
  CavityPressureTerm* cavity_term_ = nullptr;  ///< when a circulation is coupled
  IterationHook on_iteration_;
  std::vector<proto::UnitFields> unit_fields_;
  bool stop_requested_ = false;
  std::function<bool()> stop_poll_;
  /// Thrown by newton() when stop_poll_ says so; advance() rolls back and run() returns.
  struct StopRequested {};
  bool stopped_in_step_ = false;
};

}  // namespace fe2
