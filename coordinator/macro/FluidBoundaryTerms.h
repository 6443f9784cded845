#pragma once
// The fluid's boundary and level terms (fluid_scene.h), each on the partition's share:
//   OpenBoundaryTerm     pressure faces: f_ext,a = −P(t) ∫N_a n da; traction faces:
//                        f_ext,a = t(t) ∫N_a da (on the current face); and backflow
//                        stabilization where β > 0 (common/fluid/fluid_boundary.h)
//   FluxConstraintTerm   flux faces k: the multiplier λ_k acts as the traction −λ_k n,
//                          R_v,a += λ_k ∫N_a n da,   R_λk = Σ_a (v_a − v̂_a)·∫N_a n da − Q_k(t)
//                        (a symmetric saddle block; λ_k is the face's pressure). A two-way
//                        valve ring's Q_k is its valve's flow at the cavity pressures p_c,
//                        with −∂Q_k/∂p_c in its row; while the wall is inflated the inflow
//                        ring holds p_c instead: R_λk = A_k (λ_k − p_c)
//   PressureLevelTerm    ∫ p dV = 0 by a multiplier μ: R_p,b += μ ∫N_b, R_μ = ∫ p dV
//                        (so ∫ q div v = μ ∫ q: μ V is any mismatch of the boundary's
//                        fluxes with an incompressible content, reported)
//   MovingWallTerm       v_a = v̂_a = ḋ_a at wall nodes by multipliers λ_a:
//                          R_v,a += λ_a,   R_λa = v_a − ḋ_a   (∂ḋ/∂d by the scheme)
//                        one-way, the wall's motion is given to the blood; two-way
//                        (`loads_wall`), λ_a is also the force the blood exerts on the
//                        wall at its shared node a (Newton's third law):
//                          R_u,a −= λ_a   (an external force on the wall; K_u,λ = −I)
//                        so the interface traction balances node by node and the blood's
//                        pressure loads the wall. The same term shuts valve rings:
//                        while a ring's valve is shut its nodes stick (v = v̂), while open
//                        the rows read λ_a = 0 (the ring's flux constraint takes over)
//   ValveStates          which valves are open: from the current iterate in a step's first
//                        five iterations (the predictor's guess corrected), then held to
//                        the step's end, so that Newton never chases a valve flipping
//                        between iterations (a known failure of 3D–0D coupling); a shut
//                        ring's flux row reads λ_k = 0
// The current face geometry is x = X + d (mesh_displacement, when the scene has one).
#include "common/mesh/TetMesh.h"
#include "coordinator/macro/MacroPartition.h"
#include "coordinator/macro/MacroTerm.h"

#include <algorithm>
#include <functional>
#include <memory>

namespace fe2 {

/// One face triangle's nodes and where their velocity and mesh motion are.
struct FluidFace {
  std::vector<int> nodes;  ///< TetMesh::face_nodes
  int boundary = 0;        ///< index of its boundary in the term's list
};

/// Reads the current positions and mesh velocities of `nodes` (x = X + d, v̂ = ḋ).
void fluid_face_geometry(const TetMesh& mesh, const Field* d, const std::vector<int>& nodes, const MacroState& s,
                         Eigen::Matrix3Xd& x, Eigen::Matrix3Xd& w);

/// Σ over `faces` of ∫(v − v̂)·n da, per boundary index (`boundaries` of them).
std::vector<double> face_fluxes(const TetMesh& mesh, const Field& v, const Field* d, const std::vector<FluidFace>& faces,
                                size_t boundaries, const MacroState& s);

class OpenBoundaryTerm final : public MacroTerm {
 public:
  struct Boundary {
    std::string set;
    std::function<double(double)> pressure;  ///< traction −P n (empty: `traction` instead)
    double backflow = 0.0;
    std::function<Vec3(double)> traction;    ///< a traction vector t (force per current area)
  };
  /// The partition's triangles of the boundaries' face sets that bound `regions`.
  OpenBoundaryTerm(const TetMesh& mesh, const MacroPartition& partition, const std::vector<int>& regions,
                   std::vector<Boundary> boundaries, double density);
  std::string name() const override { return "fluid open boundary"; }
  Physics physics() const override { return Physics::fluid; }
  void declare(MacroSystem& system) override;
  void assemble(const MacroState& state, MacroAssembly& out) override;
  /// flux:<set> = ∫(v − v̂)·n da per boundary (out of the fluid); kinetic_flux:<set> and
  /// backflow_power:<set>, the energy it lets out by convection and what its backflow
  /// term dissipates (face_energy_flux).
  void observe(const MacroState& state, std::vector<Observable>& out) const override;

 private:
  const TetMesh& mesh_;
  std::vector<Boundary> boundaries_;
  double density_;
  std::vector<FluidFace> faces_;
  const Field *v_ = nullptr, *d_ = nullptr;
  std::vector<std::vector<int>> dofs_;
  std::vector<int> local_;  ///< per face: its backflow matrix, or −1
};

class FluxConstraintTerm final : public MacroTerm {
 public:
  /// A two-way valve ring's dependence on the circulation: its flow Q is the valve's,
  /// driven by the ring's own pressure λ (Circulation::ValvePorts), so its row
  /// R_λ = ∫(v − v̂)·n da − Q has columns −∂Q/∂p_c and −∂Q/∂λ_b' (every coupled ring b').
  struct RingCoupling {
    std::vector<double> dQ_dp;     ///< ∂Q/∂p_c per cavity
    std::vector<double> dQ_dring;  ///< ∂Q/∂λ_b' per boundary b' of this term (0: uncoupled)
    int holds_pressure_of = -1;    ///< ≥ 0: λ is that cavity's p_c instead, R_λ = A (λ − p_c),
                                   ///< A the ring's area: the inflow ring while the wall is
                                   ///< inflated (a pressure face), and a shut ring (its λ
                                   ///< then starts from p_c when it opens)
  };
  struct Boundary {
    std::string set;
    std::function<double(double)> flux;
    std::function<bool()> active;  ///< empty: always; else a valve ring's (shut: λ = 0)
    std::function<RingCoupling()> coupling;  ///< empty: Q depends on time alone
    double backflow = 0.0;                   ///< β of the backflow term while active (0: off)
    double density = 0.0;                    ///< ρ of the backflow term
  };
  FluxConstraintTerm(const TetMesh& mesh, const MacroPartition& partition, const std::vector<int>& regions,
                     std::vector<Boundary> boundaries);
  std::string name() const override { return "fluid flux constraint"; }
  Physics physics() const override { return Physics::fluid; }
  void declare(MacroSystem& system) override;
  /// flux:<set> = ∫(v − v̂)·n da and flux_pressure:<set> = λ per boundary.
  void observe(const MacroState& state, std::vector<Observable>& out) const override;
  /// The face areas (reference): R_λ's scale, so its measure is a mean normal velocity.
  void add_residual_scale(const Field& field, Eigen::VectorXd& scale) const override;
  void assemble(const MacroState& state, MacroAssembly& out) override;

 private:
  const TetMesh& mesh_;
  bool owns_globals_;
  std::vector<Boundary> boundaries_;
  std::vector<FluidFace> faces_;
  const Field *v_ = nullptr, *d_ = nullptr, *lambda_ = nullptr;
  std::vector<std::vector<int>> dofs_;  ///< per face: velocity DOFs, then λ
  std::vector<int> local_;
  std::vector<int> local_shut_;  ///< per boundary: the λλ entry of a shut valve's row (−1: never shut)
  const Field* cavity_pressure_ = nullptr;  ///< the circulation's p_c (coupled rings)
  std::vector<int> local_coupled_;  ///< per boundary: row λ_b, columns coupled_columns_[b] (−1: uncoupled)
  /// per boundary: λ_b, every p_c, then every other coupled ring's λ (global DOFs)
  std::vector<std::vector<int>> coupled_columns_;
  std::vector<double> area_;        ///< per boundary: its reference area
};

/// Per valve ring, open or shut (see above). The valve closure term updates the states
/// at the start of each of its assemblies: from the current iterate during a step's
/// first `free_iterations`, then held to the step's end.
class ValveStates {
 public:
  /// `decide`: every ring's state from the current iterate and the states it had (empty
  /// before the first decision).
  using Decide = std::function<std::vector<bool>(const std::vector<bool>& previous)>;
  explicit ValveStates(Decide decide, int free_iterations = 5)
      : decide_(std::move(decide)), free_iterations_(free_iterations) {}
  void update() {
    if (iteration_++ < free_iterations_ || open_.empty()) open_ = decide_(open_);
  }
  /// Whether the states have been decided once (before that, open() decides them).
  bool decided() const { return !open_.empty(); }
  /// Two-way rings: the states are updated where the circulation is evaluated, before it
  /// (so that its valves and the rings agree within every iteration), not by the closure.
  void update_before_circulation() { before_circulation_ = true; }
  bool updated_before_circulation() const { return before_circulation_; }
  /// Held for whole steps (free_iterations 0): whether the converged step agrees with
  /// the states it was solved with; if not, the states are changed to what it says (the
  /// step is then solved again). A ring that chatters (its states this step were all
  /// contradicted: open, blood flows back; shut, the cavity's pressure would open it)
  /// stays shut. With free iterations: always.
  bool accept() {
    if (free_iterations_ > 0 || open_.empty()) return true;
    std::vector<bool> next = decide_(open_);
    if (next == open_) return true;
    tried_.push_back(open_);
    if (std::find(tried_.begin(), tried_.end(), next) != tried_.end())
      for (size_t k = 0; k < next.size(); ++k) next[k] = next[k] && open_[k];
    if (next == open_) return true;
    open_ = std::move(next);
    return false;
  }
  /// The step was committed: its tried states are forgotten.
  void committed() {
    tried_.clear();
    release();
  }
  /// The states, for checkpoints.
  const std::vector<bool>& states() const { return open_; }
  void set_states(std::vector<bool> open) { open_ = std::move(open); }
  bool open(int ring) {
    if (open_.empty()) open_ = decide_(open_);  // a ring without closure nodes of its own
    return open_.at(static_cast<size_t>(ring));
  }
  /// The next assembly starts a step (after a commit or a rollback).
  void release() { iteration_ = 0; }

 private:
  Decide decide_;
  int free_iterations_;
  bool before_circulation_ = false;
  std::vector<std::vector<bool>> tried_;  ///< the states this step was solved with
  std::vector<bool> open_;
  int iteration_ = 0;
};

class MovingWallTerm final : public MacroTerm {
 public:
  /// `nodes`: fluid_scene.h's moving_wall_nodes (or a valve's ring nodes), in the
  /// multiplier field's order; the first coordinator assembles them all (a handful of
  /// rows each). With `valves`, node k sticks only while one of the rings ring_of_node[k]
  /// is shut.
  MovingWallTerm(const MacroPartition& partition, std::vector<int> nodes, std::string multiplier = "fluid_wall_multiplier",
                 std::shared_ptr<ValveStates> valves = nullptr, std::vector<std::vector<int>> ring_of_node = {});
  /// Two-way: the multipliers also act on the wall's displacement (see above).
  static std::unique_ptr<MovingWallTerm> loading_wall(const MacroPartition& partition, std::vector<int> nodes);
  std::string name() const override { return valves_ ? "fluid valve closure" : "fluid moving wall"; }
  Physics physics() const override { return Physics::fluid; }
  void declare(MacroSystem& system) override;
  /// 1 per multiplier (the measure is |v − v̂| in velocity units).
  void add_residual_scale(const Field& field, Eigen::VectorXd& scale) const override;
  void assemble(const MacroState& state, MacroAssembly& out) override;
  /// Valve rings held for whole steps: whether the converged step agrees with their states.
  bool accept(const MacroState&) override { return !valves_ || valves_->accept(); }
  void commit(const MacroState&) override { if (valves_) valves_->committed(); }
  void rollback() override { if (valves_) valves_->release(); }
  /// The valve rings' states.
  void save(ByteWriter& w) const override;
  void restore(ByteReader& r) override;

 private:
  bool owns_globals_;
  std::vector<int> nodes_;
  std::string multiplier_;
  std::shared_ptr<ValveStates> valves_;
  std::vector<std::vector<int>> ring_of_node_;
  bool loads_wall_ = false;
  const Field *lambda_ = nullptr, *v_ = nullptr, *d_ = nullptr, *u_ = nullptr;
  struct Node {
    std::vector<int> dofs;  ///< v (3), λ (3), then d (3) if the mesh moves there
    std::vector<int> wall;  ///< two-way: the wall's displacement DOFs (3) at the node, or none
    int local = -1;         ///< rows v, λ (and the wall's); columns dofs
  };
  std::vector<Node> rows_;
};

class PressureLevelTerm final : public MacroTerm {
 public:
  PressureLevelTerm(const TetMesh& mesh, std::vector<int> elements);
  std::string name() const override { return "fluid pressure level"; }
  Physics physics() const override { return Physics::fluid; }
  void declare(MacroSystem& system) override;
  /// The fluid's volume: the measure is the mean pressure.
  void add_residual_scale(const Field& field, Eigen::VectorXd& scale) const override;
  void assemble(const MacroState& state, MacroAssembly& out) override;
  /// fluid_volume_imbalance = μ V = ∫div v_h: the volume rate by which what the boundary
  /// lets through (flux faces, moving walls) fails to match an incompressible content;
  /// 0 when they agree (the multiplier then only fixes the level).
  void observe(const MacroState& state, std::vector<Observable>& out) const override;

 private:
  const TetMesh& mesh_;
  std::vector<int> elements_;
  const Field *mu_ = nullptr;
  std::vector<std::vector<int>> dofs_;  ///< per element: its 4 pressure DOFs, then μ
  std::vector<Eigen::Vector4d> weights_;
  std::vector<int> local_;
};

}  // namespace fe2
