#pragma once
// A 0D blood circulation coupled strongly to the cavities of a wall model.
//
// The circulation is a network of compartments (nodes) joined by connections:
//   compartments: a cavity (its pressure p_c is an input: the wall model's unknown),
//     a fixed pressure, a compliance (p = V/C), a time-varying elastance
//     (p = E(t)(V − V0), TimeVaryingElastance.h) or a junction (no volume: flows balance);
//   connections: a resistor Q = Δp/R, a valve (smooth diode, smooth_valve.h) or an
//     inertance L dQ/dt = Δp − R Q.
// Each step [t_n, t_{n+1}] is backward Euler: given the cavity pressures p at t_{n+1},
// every internal unknown y (compartment volumes, junction pressures, inertance flows) is
// solved implicitly,
//   V_k − V_k,n − Δt Σ_e ±Q_e(y, p) = 0,   Δt Σ_e ±Q_e = 0 (junctions),
//   L (Q_e − Q_e,n) + Δt (R Q_e − Δp_e) = 0 (inertances),
// by a dense Newton, and each cavity's net inflow Q_net,c(p) = Q_in,c − Q_out,c follows,
// with its exact Jacobian ∂Q_net/∂p = ∂Q/∂p − ∂Q/∂y (∂r/∂y)⁻¹ ∂r/∂p (implicit function
// theorem on the converged update). The wall model then enforces
//   V_wall,c(ū) − V_c,n − Δt Q_net,c(p) = 0.
// After the Newton solve every volume is updated once more from the converged flows,
// V_k = V_k,n + Δt Σ_e ±Q_e, so a closed network conserves the total blood volume
// (compartments + cavities) to round-off, whatever the Newton tolerance.
//
// Like a cell model (common/cellmodels/CellModel.h), a Circulation owns no state: the
// owner keeps the committed state (state_size() doubles), passes it to step(), and
// commits, rolls back or serializes the current one. step() is deterministic.
//
// Units: pressure Pa, volume mm³, time s, flow mm³/s, resistance Pa·s/mm³, compliance
// mm³/Pa, elastance Pa/mm³, inertance Pa·s²/mm³.
#include "common/circulation/TimeVaryingElastance.h"
#include "common/circulation/smooth_valve.h"

#include <memory>
#include <span>
#include <string>
#include <vector>

namespace fe2 {

/// What one step gives the wall model, and what it reports.
struct CavityFlows {
  int n = 0;                          ///< number of cavities
  std::vector<double> Q_net;          ///< per cavity: Q_in − Q_out at t_{n+1} (mm³/s)
  std::vector<double> dQ_dp;          ///< n × n row-major: ∂Q_net,i/∂p_j (mm³/(s·Pa))
  std::vector<double> Q_in, Q_out;    ///< per cavity: through its inflow / outflow valve
  std::vector<double> dQin_dp, dQout_dp;  ///< n × n row-major: ∂Q_in,i/∂p_j, ∂Q_out,i/∂p_j
  /// n × 2n row-major: ∂Q_in,i/∂π_j, ∂Q_out,i/∂π_j over the ring pressures π of
  /// ValvePorts (column j < n: cavity j's inflow ring, n + j: its outflow ring); zero
  /// columns for valves that see p_c.
  std::vector<double> dQin_dport, dQout_dport;
  std::vector<bool> inflow_open, outflow_open;  ///< not held shut, Δp > 0 across the valve
  /// Δp across each cavity's inflow / outflow valve with the cavity side at p_c (whatever
  /// ValvePorts says): a shut ring's opening test.
  std::vector<double> inflow_drop, outflow_drop;
  /// Not held shut, and Δp < −width (the valve's switching width) at the pressure the valve
  /// sees: blood flows back through it; an open ring's closing test (at Δp ≈ 0 an open
  /// valve passes nothing, and its state is then the open one).
  std::vector<bool> inflow_reversed, outflow_reversed;
  std::vector<std::string> phase;     ///< per cavity, Circulation::phase()
  std::vector<double> pressures;      ///< per compartment (compartment_names()), Pa
  std::vector<double> volumes;        ///< per compartment, mm³ (0 for fixed and junctions)
  std::vector<double> flows;          ///< per connection (connection_names()), mm³/s
  int newton_iterations = 0;          ///< of the internal solve
  double dQ(int i, int j) const { return dQ_dp[static_cast<size_t>(i * n + j)]; }
};

class Circulation {
 public:
  // --- Building the network (circulation_factory.cpp; tests).
  enum class NodeKind { cavity, fixed, compliance, elastance, junction };
  enum class LinkKind { resistor, valve, inertance };
  struct Node {
    std::string name;
    NodeKind kind = NodeKind::fixed;
    double pressure = 0.0;        ///< fixed: its pressure; compliance, junction: initial p
    double compliance = 0.0;      ///< compliance: C (mm³/Pa)
    TimeVaryingElastance elastance;  ///< elastance: E(t), V0, V_init
    int cavity = -1;              ///< cavity: its index
  };
  struct Link {
    std::string name;
    int from = -1, to = -1;       ///< node indices; Q > 0 flows from → to
    LinkKind kind = LinkKind::resistor;
    double R = 0.0;               ///< resistor, inertance (Pa·s/mm³)
    double L = 0.0;               ///< inertance (Pa·s²/mm³), > 0
    ValveParameters valve;
  };

  /// `cavity_names` in order; each cavity needs a node of kind cavity and its inflow and
  /// outflow valves (link indices) for the phase. `left_ventricle` is the cavity index of
  /// the systemic ventricle.
  Circulation(std::string kind, std::vector<std::string> cavity_names, std::vector<Node> nodes,
              std::vector<Link> links, std::vector<int> inflow_valve,
              std::vector<int> outflow_valve, double period, std::string description,
              int left_ventricle);

  // --- The coupling interface.
  int cavities() const { return static_cast<int>(cavity_names_.size()); }
  const std::vector<std::string>& cavity_names() const { return cavity_names_; }
  /// The cavity that pumps into the systemic arteries (the spec's "lv"): its pressure peak
  /// marks systole.
  int left_ventricle() const { return left_ventricle_; }
  /// Doubles of state: the internal unknowns, then the cavity pressures of the last step
  /// (for the phase's sign of dp).
  int state_size() const { return unknowns_ + cavities(); }
  /// Initial compartment volumes and pressures from the spec; inertance flows 0.
  void initial_state(std::span<double> state) const;
  /// One backward-Euler step to t_new = t_n + dt at cavity pressures p_cav (Pa):
  /// reads `committed`, writes `current` (both state_size()). Throws NumericalError
  /// naming the compartment if the internal Newton fails.
  CavityFlows step(double t_new, double dt, std::span<const double> p_cav,
                   std::span<const double> committed, std::span<double> current) const;
  /// How a 3D model's valve rings meet the cavities' valves (per cavity; empty vectors:
  /// none). A valve held shut passes nothing whatever its pressure drop (its ring is shut:
  /// what leaves a cavity is what its rings pass). An open valve given a ring pressure π
  /// sees π on the cavity side instead of p_c: the flow through a ring is driven by the
  /// ring's own pressure (an impedance condition, the stable form of 3D–0D coupling),
  /// while p_c stays the cavity's mean pressure (phase, report, opening test).
  struct ValvePorts {
    std::vector<bool> inflow_shut, outflow_shut;
    std::vector<double> inflow_pressure, outflow_pressure;  ///< NaN: p_c
  };
  CavityFlows step(double t_new, double dt, std::span<const double> p_cav, std::span<const double> committed,
                   std::span<double> current, const ValvePorts& ports) const;
  /// "filling" (inflow valve open), "ejection" (outflow valve open), "isovolumic
  /// contraction" / "isovolumic relaxation" (both closed; dp ≥ 0 / dp < 0 over the step),
  /// "both valves open" (never in a sane circulation).
  static std::string phase(bool inflow_open, bool outflow_open, double dp);
  /// Sets the cavity pressures of the last step in `state` (the owner's initial
  /// pressures, so the first step's phase sees the right sign of dp).
  void set_cavity_pressures(std::span<double> state, std::span<const double> p_cav) const;
  /// Per cavity, the pressure upstream of its inflow valve at t = 0 in `state` (the
  /// preload, or the atrium's): the filling pressure of end-diastole, to which a wall is
  /// inflated before the first beat.
  std::vector<double> filling_pressures(std::span<const double> state) const;
  /// The network held at `state` with the cavities at `p_cav` and no flow (a wall being
  /// inflated before the first beat): every compartment's pressure and volume at t,
  /// zero flows, phase "inflation", both valves reported shut.
  CavityFlows at_rest(double t, std::span<const double> p_cav, std::span<const double> state) const;
  /// Heart period of its time-varying elastances (s).
  double period() const { return period_; }
  /// Blood held by the compartments of `state` (mm³; cavities excluded).
  double blood_volume(std::span<const double> state) const;
  /// True if no fixed-pressure compartment: blood volume is then conserved.
  bool closed() const;
  /// "windkessel" or "closed_loop".
  const std::string& kind() const { return kind_; }
  /// One line with the model and the parameter values that matter (logged).
  const std::string& description() const { return description_; }

  // --- Reporting.
  std::vector<std::string> compartment_names() const;
  std::vector<std::string> connection_names() const;
  const std::vector<Node>& nodes() const { return nodes_; }
  const std::vector<Link>& links() const { return links_; }

 private:
  struct Evaluation;
  /// Per link: held shut; the pressure its cavity end sees and that pressure's column
  /// among the inputs (p_cav, then the ring pressures π: n + j inflow, 2n + j outflow).
  struct LinkPorts {
    std::vector<char> shut;
    std::vector<int> node;        ///< the cavity end that sees a ring pressure, or −1
    std::vector<double> pressure;
    std::vector<int> column;
  };
  LinkPorts link_ports(const ValvePorts& ports) const;
  void evaluate(double t, double dt, std::span<const double> p_cav, std::span<const double> y_n,
                std::span<const double> y, Evaluation& e, const LinkPorts& ports) const;
  /// Every compartment's pressure and volume at (t, p_cav, y) into f.pressures, f.volumes.
  void report_compartments(double t, std::span<const double> p_cav, std::span<const double> y,
                           CavityFlows& f) const;
  double node_pressure(int k, double t, std::span<const double> p_cav,
                       std::span<const double> y) const;

  std::string kind_;
  std::vector<std::string> cavity_names_;
  std::vector<Node> nodes_;
  std::vector<Link> links_;
  std::vector<int> inflow_valve_, outflow_valve_;
  double period_ = 0.0;
  std::string description_;
  int left_ventricle_ = 0;
  std::vector<int> node_unknown_;   ///< per node: its unknown (V or p) or -1
  std::vector<int> link_unknown_;   ///< per link: its unknown (Q) or -1
  std::vector<std::string> unknown_name_;
  int unknowns_ = 0;
};

using CirculationPtr = std::shared_ptr<const Circulation>;

}  // namespace fe2
