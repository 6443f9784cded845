#pragma once
// Cavities coupled strongly to a 0D circulation: each cavity pressure p_c is an unknown
// of the macro system (the field "cavity_pressure", one scalar per coupled cavity in
// RunSpec::coupled_cavities order) and this term adds, per
// cavity with endocardial surface Γ_c and volume V_c(ū) (cavity_volume.h):
//
//   R_u += −p_c ∫_Γc N n da             (follower pressure; K_uu = −p_c ∂(∫N n da)/∂ū,
//                                          K_u,pc = −∫_Γc N n da)
//   R_c  = V_c(ū) − V_c,n − Δt Q_net,c(p)  (the volume the circulation lets in over the
//                                          step, backward Euler; Circulation.h)
//   K_c,u = ∂V_c/∂ū,   K_c,p = −Δt ∂Q_net,c/∂p
//
// With both valves closed Q_net ≈ 0 and R_c is the isovolumic constraint; open, it is
// the flow balance. The circulation's state advances with the step from its committed
// value at every evaluation and is committed / rolled back with the step.
//
// R_c has the units of a volume; its scale is the cavity's unloaded volume.
//
// While the wall is inflated to end-diastole before the first beat (time.inflation_steps,
// t ≤ 0) the circulation stands still and each cavity's pressure is prescribed instead,
// ramped from 0 at t_start to the circulation's filling pressure p_fill,c at t = 0:
//   R_c = (V_c,ref / p_s) (p_c − p_fill,c (t − t_start)/(−t_start)),  p_s = max(p_fill,c, 1 kPa).
// The circulation's state is unchanged by it; the last committed cavity pressures (the
// phase's dp) follow the wall. What the cavity takes in meanwhile is reported as its
// inflow through an open inflow valve (Q_in = Q_net = (V_c − V_c,n)/Δt): the blood a
// cavity with a fluid receives through its inflow ring.
//
// A cavity filled with blood that loads the wall (fluid.coupling "two_way", the cavity
// named by valve rings) takes neither the lumped load nor the volume row: the blood loads
// the wall, and its rings pass the circulation's flows (the volume balance). Its p_c is
// the blood's mean pressure over the cavity's fluid elements Ω_b,c (reference volumes),
//   R_c = ∫_Ωb,c (p_c − p) dV,
// the pressure the circulation reports and opens a shut valve by. The rings meet the
// circulation's valves (couple_rings, Circulation::ValvePorts): a valve whose ring is shut
// is shut in the circulation too, and an open valve passes the flow its ring's own
// pressure λ drives, Q(λ) (an impedance condition: the blood's inertia and the valve
// share the pressure drop, rather than the valve's flow at p_c being forced through the
// ring whatever λ it takes), with ∂Q/∂λ and ∂Q/∂p_c in the rings' rows. While
// inflating p_c is prescribed as above and the inflow ring holds it.
//
// The pressure load on a face is assembled by the coordinator owning the face's tet; the
// volume rows R_c need the whole surface (and the circulation), so the coordinator owning
// the global unknowns assembles them (MacroPartition). MUMPS sums the distributed input.
#include "common/circulation/Circulation.h"
#include "coordinator/macro/MacroPartition.h"
#include "coordinator/macro/MacroTerm.h"
#include "coordinator/RunSpec.h"

#include <functional>

namespace fe2 {

class CavityPressureTerm final : public MacroTerm {
 public:
  CavityPressureTerm(const RunSpec& spec, const MacroPartition& partition);
  std::string name() const override { return "cavity pressure"; }
  Physics physics() const override { return Physics::circulation; }
  void declare(MacroSystem& system) override;
  void assemble(const MacroState& state, MacroAssembly& out) override;
  /// The cavity pressures' scale: the reference volumes (added where the rows are).
  void add_residual_scale(const Field& field, Eigen::VectorXd& scale) const override;
  void commit(const MacroState& state) override;
  void rollback() override;
  /// The circulation's committed state and V_c of the last step.
  void save(ByteWriter& w) const override;
  void restore(ByteReader& r) override;

  /// The circulation's answer at the last assembly (valid where the rows are).
  const CavityFlows& flows() const { return flows_; }
  /// V_c at the end of the last committed step, per circulation cavity.
  const std::vector<double>& committed_volumes() const { return V_n_; }
  /// The reference (unloaded) cavity volumes, to scale the volume residuals.
  const std::vector<double>& reference_volumes() const { return V_ref_; }
  /// The number of circulation cavities (cavity_pressure's size).
  int count() const { return static_cast<int>(cavities_.size()); }
  /// Whether cavity i is filled with two-way blood (see above).
  bool filled_with_blood(int i) const { return cavities_.at(static_cast<size_t>(i)).blood; }
  /// The last assembly was of the end-diastolic inflation.
  bool inflating() const { return inflating_; }
  /// How the blood's valve rings meet the circulation, from their pressures (the field
  /// fluid_flux_pressure's values), asked once at every assembly before the circulation
  /// is evaluated (ignored while inflating).
  using RingPorts = std::function<Circulation::ValvePorts(std::span<const double> ring_pressures)>;
  void couple_rings(RingPorts ports) { ports_ = std::move(ports); }

 private:
  struct Face {
    std::vector<int> nodes, dofs;
    int local_uu = -1, local_up = -1;
  };
  struct Cavity {
    std::string surface;
    int dof = -1;
    std::vector<std::array<int, 3>> triangles;  ///< the owned part of the surface
    std::vector<Face> faces;
    std::vector<int> volume_nodal;  ///< the nodal DOFs 3a + i ∂V/∂ū touches (fixed by the mesh)
    std::vector<int> volume_dofs;   ///< the same as DOFs of the displacement field
    int local_pu = -1;
    bool blood = false;             ///< filled with two-way blood (see above)
    std::vector<int> blood_elements;  ///< the partition's elements of Ω_b,c
    std::vector<std::vector<int>> blood_dofs;  ///< per element: p_c, then its 4 pressure DOFs
    std::vector<int> blood_local;
  };
  /// The blood's rows R_c = ∫(p_c − p) dV of the cavities filled with it.
  void assemble_blood_rows(const MacroState& state, MacroAssembly& out) const;
  /// The rows R_c of the end-diastolic inflation (prescribed cavity pressures).
  void assemble_inflation(double t, const std::vector<double>& p, MacroAssembly& out) const;

  const RunSpec& spec_;
  const Circulation& circulation_;
  bool owns_rows_;  ///< this coordinator assembles R_c (MacroPartition::owns_globals)
  std::vector<Cavity> cavities_;
  int local_pp_ = -1;
  const Field* u_ = nullptr;
  const Field* pc_ = nullptr;
  std::vector<int> cavity_dofs_;
  std::vector<double> committed_, current_;  ///< circulation state
  std::vector<double> V_n_, V_ref_;
  std::vector<double> p_fill_;  ///< per cavity: the filling pressure of end-diastole
  CavityFlows flows_, committed_flows_;
  bool inflating_ = false;
  RingPorts ports_;
  const Field* rings_ = nullptr;  ///< fluid_flux_pressure, if any
};

}  // namespace fe2
