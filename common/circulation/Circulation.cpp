#include "common/circulation/Circulation.h"

#include "common/error.h"

#include <Eigen/Dense>
#include <spdlog/fmt/fmt.h>

#include <cmath>

namespace fe2 {

/// Residual, Jacobians and flows of the step system at one iterate y.
struct Circulation::Evaluation {
  Eigen::VectorXd r;        ///< m residuals (mm³)
  Eigen::MatrixXd J;        ///< ∂r/∂y (m × m)
  Eigen::MatrixXd Jp;       ///< ∂r/∂p_cav (m × n_cav)
  Eigen::VectorXd Q;        ///< per link
  Eigen::MatrixXd dQ_dy;    ///< per link × m
  Eigen::MatrixXd dQ_dp;    ///< per link × n_cav
};

Circulation::Circulation(std::string kind, std::vector<std::string> cavity_names,
                         std::vector<Node> nodes, std::vector<Link> links,
                         std::vector<int> inflow_valve, std::vector<int> outflow_valve,
                         double period, std::string description, int left_ventricle)
    : kind_(std::move(kind)),
      cavity_names_(std::move(cavity_names)),
      nodes_(std::move(nodes)),
      links_(std::move(links)),
      inflow_valve_(std::move(inflow_valve)),
      outflow_valve_(std::move(outflow_valve)),
      period_(period),
      description_(std::move(description)),
      left_ventricle_(left_ventricle) {
  const int n = static_cast<int>(nodes_.size());
  FE2_CHECK(static_cast<int>(inflow_valve_.size()) == cavities() &&
                static_cast<int>(outflow_valve_.size()) == cavities(),
            "each of the {} cavities needs an inflow and an outflow valve", cavities());
  std::vector<int> seen(cavities(), 0);
  for (const Node& node : nodes_) {
    if (node.kind != NodeKind::cavity) continue;
    FE2_CHECK(node.cavity >= 0 && node.cavity < cavities(), "cavity node '{}' has index {}",
              node.name, node.cavity);
    ++seen[node.cavity];
  }
  for (int c = 0; c < cavities(); ++c)
    FE2_CHECK(seen[c] == 1, "cavity '{}' has {} nodes", cavity_names_[c], seen[c]);
  node_unknown_.assign(n, -1);
  link_unknown_.assign(links_.size(), -1);
  for (int k = 0; k < n; ++k) {
    const NodeKind kk = nodes_[k].kind;
    if (kk == NodeKind::compliance || kk == NodeKind::elastance || kk == NodeKind::junction) {
      node_unknown_[k] = unknowns_++;
      unknown_name_.push_back(nodes_[k].name);
    }
  }
  for (size_t e = 0; e < links_.size(); ++e) {
    const Link& l = links_[e];
    FE2_CHECK(l.from >= 0 && l.from < n && l.to >= 0 && l.to < n && l.from != l.to,
              "connection '{}' must join two different compartments", l.name);
    if (l.kind == LinkKind::inertance) {
      link_unknown_[e] = unknowns_++;
      unknown_name_.push_back(l.name);
    }
  }
  for (int c = 0; c < cavities(); ++c)
    for (int v : {inflow_valve_[c], outflow_valve_[c]})
      FE2_CHECK(v >= 0 && v < static_cast<int>(links_.size()) && links_[v].kind == LinkKind::valve,
                "cavity '{}' needs valves", cavity_names_[c]);
}

void Circulation::initial_state(std::span<double> state) const {
  FE2_CHECK(static_cast<int>(state.size()) == state_size(), "state of {} doubles, expected {}",
            state.size(), state_size());
  for (size_t k = 0; k < nodes_.size(); ++k) {
    const int u = node_unknown_[k];
    if (u < 0) continue;
    const Node& node = nodes_[k];
    if (node.kind == NodeKind::compliance) state[u] = node.compliance * node.pressure;
    else if (node.kind == NodeKind::elastance) state[u] = node.elastance.parameters().V_init;
    else state[u] = node.pressure;  // junction
  }
  for (size_t e = 0; e < links_.size(); ++e)
    if (link_unknown_[e] >= 0) state[link_unknown_[e]] = 0.0;
  for (int c = 0; c < cavities(); ++c) state[unknowns_ + c] = 0.0;
}

void Circulation::set_cavity_pressures(std::span<double> state, std::span<const double> p_cav) const {
  FE2_CHECK(static_cast<int>(p_cav.size()) == cavities() &&
                static_cast<int>(state.size()) == state_size(),
            "set_cavity_pressures: {} pressures, state {}", p_cav.size(), state.size());
  for (int c = 0; c < cavities(); ++c) state[unknowns_ + c] = p_cav[c];
}

std::vector<double> Circulation::filling_pressures(std::span<const double> state) const {
  FE2_CHECK(static_cast<int>(state.size()) == state_size(), "state of {} doubles, expected {}", state.size(),
            state_size());
  const std::span<const double> p_cav = state.subspan(static_cast<size_t>(unknowns_));
  std::vector<double> p;
  for (int c = 0; c < cavities(); ++c) p.push_back(node_pressure(links_[inflow_valve_[c]].from, 0.0, p_cav, state));
  return p;
}

void Circulation::report_compartments(double t, std::span<const double> p_cav, std::span<const double> y,
                                      CavityFlows& f) const {
  for (size_t k = 0; k < nodes_.size(); ++k) {
    f.pressures.push_back(node_pressure(static_cast<int>(k), t, p_cav, y));
    const bool stores = nodes_[k].kind == NodeKind::compliance || nodes_[k].kind == NodeKind::elastance;
    f.volumes.push_back(stores ? y[node_unknown_[k]] : 0.0);
  }
}

CavityFlows Circulation::at_rest(double t, std::span<const double> p_cav, std::span<const double> state) const {
  FE2_CHECK(static_cast<int>(state.size()) == state_size() && static_cast<int>(p_cav.size()) == cavities(),
            "at_rest: state of {} doubles, {} cavity pressures", state.size(), p_cav.size());
  CavityFlows f;
  f.n = cavities();
  f.Q_net.assign(f.n, 0.0);
  f.dQ_dp.assign(static_cast<size_t>(f.n) * f.n, 0.0);
  f.Q_in.assign(f.n, 0.0);
  f.Q_out.assign(f.n, 0.0);
  f.dQin_dp.assign(f.dQ_dp.size(), 0.0);
  f.dQout_dp.assign(f.dQ_dp.size(), 0.0);
  f.dQin_dport.assign(2 * f.dQ_dp.size(), 0.0);
  f.dQout_dport.assign(2 * f.dQ_dp.size(), 0.0);
  f.inflow_open.assign(f.n, false);
  f.outflow_open.assign(f.n, false);
  f.inflow_reversed.assign(f.n, false);
  f.outflow_reversed.assign(f.n, false);
  for (int c = 0; c < f.n; ++c) {
    const Link& in = links_[static_cast<size_t>(inflow_valve_[c])];
    const Link& out = links_[static_cast<size_t>(outflow_valve_[c])];
    f.inflow_drop.push_back(node_pressure(in.from, t, p_cav, state) - node_pressure(in.to, t, p_cav, state));
    f.outflow_drop.push_back(node_pressure(out.from, t, p_cav, state) - node_pressure(out.to, t, p_cav, state));
  }
  f.phase.assign(f.n, "inflation");
  report_compartments(t, p_cav, state, f);
  f.flows.assign(links_.size(), 0.0);
  return f;
}

double Circulation::node_pressure(int k, double t, std::span<const double> p_cav,
                                  std::span<const double> y) const {
  const Node& node = nodes_[k];
  switch (node.kind) {
    case NodeKind::cavity: return p_cav[node.cavity];
    case NodeKind::fixed: return node.pressure;
    case NodeKind::compliance: return y[node_unknown_[k]] / node.compliance;
    case NodeKind::elastance: return node.elastance.pressure(t, y[node_unknown_[k]]);
    case NodeKind::junction: return y[node_unknown_[k]];
  }
  return 0.0;
}

Circulation::LinkPorts Circulation::link_ports(const ValvePorts& ports) const {
  const int nc = cavities();
  const size_t nl = links_.size();
  LinkPorts lp{std::vector<char>(nl, 0), std::vector<int>(nl, -1), std::vector<double>(nl, 0.0),
               std::vector<int>(nl, -1)};
  auto held = [](const std::vector<bool>& shut, int c) { return static_cast<int>(shut.size()) > c && shut[static_cast<size_t>(c)]; };
  for (int c = 0; c < nc; ++c)
    for (const bool outflow : {false, true}) {
      const size_t e = static_cast<size_t>(outflow ? outflow_valve_[c] : inflow_valve_[c]);
      if (held(outflow ? ports.outflow_shut : ports.inflow_shut, c)) lp.shut[e] = 1;
      const std::vector<double>& pressure = outflow ? ports.outflow_pressure : ports.inflow_pressure;
      if (static_cast<int>(pressure.size()) <= c || std::isnan(pressure[static_cast<size_t>(c)])) continue;
      const double pi = pressure[static_cast<size_t>(c)];
      if (!std::isfinite(pi))
        throw NumericalError(fmt::format("circulation: non-finite {} ring pressure {} in cavity '{}'",
                                         outflow ? "outflow" : "inflow", pi, cavity_names_[c]));
      const Link& l = links_[e];
      lp.node[e] = nodes_[l.from].kind == NodeKind::cavity && nodes_[l.from].cavity == c ? l.from : l.to;
      lp.pressure[e] = pi;
      lp.column[e] = (outflow ? 2 : 1) * nc + c;
    }
  return lp;
}

void Circulation::evaluate(double t, double dt, std::span<const double> p_cav,
                           std::span<const double> y_n, std::span<const double> y,
                           Evaluation& ev, const LinkPorts& ports) const {
  const int m = unknowns_, nc = cavities(), nl = static_cast<int>(links_.size());
  const int nn = static_cast<int>(nodes_.size());
  // Each node's pressure and its derivative: dp/dy_u = a (u = its unknown) or dp/dp_c = 1.
  std::vector<double> p(nn), a(nn, 0.0);
  for (int k = 0; k < nn; ++k) {
    p[k] = node_pressure(k, t, p_cav, y);
    switch (nodes_[k].kind) {
      case NodeKind::compliance: a[k] = 1.0 / nodes_[k].compliance; break;
      case NodeKind::elastance: a[k] = nodes_[k].elastance.elastance(t); break;
      case NodeKind::junction: a[k] = 1.0; break;
      default: break;
    }
  }
  // Inputs: p_cav (nc), then the ring pressures (2 nc, LinkPorts::column).
  ev.Q.setZero(nl);
  ev.dQ_dy.setZero(nl, m);
  ev.dQ_dp.setZero(nl, 3 * nc);
  // Link e's end k: its pressure, and s · ∂p/∂(y, inputs) added to row e of the flow
  // derivatives.
  auto end_pressure = [&](int e, int k) { return ports.node[static_cast<size_t>(e)] == k ? ports.pressure[static_cast<size_t>(e)] : p[k]; };
  auto add_dp = [&](int e, int k, double s) {
    if (ports.node[static_cast<size_t>(e)] == k) ev.dQ_dp(e, ports.column[static_cast<size_t>(e)]) += s;
    else if (node_unknown_[k] >= 0) ev.dQ_dy(e, node_unknown_[k]) += s * a[k];
    else if (nodes_[k].kind == NodeKind::cavity) ev.dQ_dp(e, nodes_[k].cavity) += s;
  };
  ev.r.setZero(m);
  ev.J.setZero(m, m);
  ev.Jp.setZero(m, 3 * nc);
  for (int e = 0; e < nl; ++e) {
    const Link& l = links_[e];
    const double dp = end_pressure(e, l.from) - end_pressure(e, l.to);
    double g = 0.0;  // dQ/dΔp of an algebraic link
    switch (l.kind) {
      case LinkKind::resistor:
        ev.Q[e] = dp / l.R;
        g = 1.0 / l.R;
        break;
      case LinkKind::valve: {
        if (ports.shut[static_cast<size_t>(e)]) break;  // held shut: Q = 0
        const ValveFlow f = valve_flow(l.valve, dp);
        ev.Q[e] = f.Q;
        g = f.dQ;
        break;
      }
      case LinkKind::inertance: {
        const int u = link_unknown_[e];
        ev.Q[e] = y[u];
        ev.dQ_dy(e, u) = 1.0;
        // [L (Q − Q_n) + Δt (R Q − Δp)] / (L/Δt + R): a volume, like the other rows.
        const double D = l.L / dt + l.R;
        ev.r[u] = (l.L * (y[u] - y_n[u]) + dt * (l.R * y[u] - dp)) / D;
        ev.J(u, u) += dt;
        const double s = -dt / D;
        auto add_row = [&](int k, double sign) {
          if (node_unknown_[k] >= 0) ev.J(u, node_unknown_[k]) += sign * s * a[k];
          else if (nodes_[k].kind == NodeKind::cavity) ev.Jp(u, nodes_[k].cavity) += sign * s;
        };
        add_row(l.from, 1.0);
        add_row(l.to, -1.0);
        break;
      }
    }
    if (l.kind != LinkKind::inertance) {
      add_dp(e, l.from, g);
      add_dp(e, l.to, -g);
    }
  }
  // Volume balance of storage compartments, flow balance of junctions.
  for (int k = 0; k < nn; ++k) {
    const int u = node_unknown_[k];
    if (u < 0) continue;
    const bool junction = nodes_[k].kind == NodeKind::junction;
    if (!junction) {
      ev.r[u] = y[u] - y_n[u];
      ev.J(u, u) += 1.0;
    }
    const double w = junction ? dt : -dt;  // junction: Δt Σ ±Q = 0
    for (int e = 0; e < nl; ++e) {
      const double s = links_[e].to == k ? 1.0 : links_[e].from == k ? -1.0 : 0.0;
      if (s == 0.0) continue;
      ev.r[u] += w * s * ev.Q[e];
      ev.J.row(u) += w * s * ev.dQ_dy.row(e);
      ev.Jp.row(u) += w * s * ev.dQ_dp.row(e);
    }
  }
}

CavityFlows Circulation::step(double t_new, double dt, std::span<const double> p_cav,
                              std::span<const double> committed, std::span<double> current) const {
  return step(t_new, dt, p_cav, committed, current, ValvePorts{});
}

CavityFlows Circulation::step(double t_new, double dt, std::span<const double> p_cav,
                              std::span<const double> committed, std::span<double> current,
                              const ValvePorts& valve_ports) const {
  const int m = unknowns_, nc = cavities(), nl = static_cast<int>(links_.size());
  FE2_CHECK(static_cast<int>(committed.size()) == state_size() &&
                static_cast<int>(current.size()) == state_size() &&
                static_cast<int>(p_cav.size()) == nc,
            "step: state {} / {} doubles, {} pressures; expected {} and {}", committed.size(),
            current.size(), p_cav.size(), state_size(), nc);
  FE2_CHECK(dt > 0.0, "step: dt = {} must be > 0", dt);
  for (int c = 0; c < nc; ++c)
    if (!std::isfinite(p_cav[c]))
      throw NumericalError(fmt::format("circulation: non-finite pressure {} in cavity '{}' at t = {} s",
                                       p_cav[c], cavity_names_[c], t_new));
  const LinkPorts ports = link_ports(valve_ports);
  const std::span<const double> y_n = committed.first(m);
  std::vector<double> y(committed.begin(), committed.begin() + m);
  // Volume scale of the tolerances: the blood the compartments hold.
  double scale = 1.0;
  for (size_t k = 0; k < nodes_.size(); ++k)
    if (node_unknown_[k] >= 0 && nodes_[k].kind != NodeKind::junction)
      scale += std::abs(y_n[node_unknown_[k]]);
  const double tight = 1e-15 * scale, loose = 1e-9 * scale;
  constexpr int kMaxIterations = 50;

  Evaluation ev;
  int it = 0;
  double previous = std::numeric_limits<double>::infinity();
  for (;; ++it) {
    evaluate(t_new, dt, p_cav, y_n, y, ev, ports);
    int worst = 0;
    const double norm = m ? ev.r.cwiseAbs().maxCoeff(&worst) : 0.0;
    if (!std::isfinite(norm))
      throw NumericalError(fmt::format(
          "circulation: non-finite residual in '{}' at t = {} s (iteration {})",
          unknown_name_[worst], t_new, it));
    // Converged: at round-off, or past the loose tolerance with Newton no longer gaining
    // (round-off floor).
    if (norm <= tight || (norm <= loose && norm > 0.25 * previous)) break;
    if (it == kMaxIterations)
      throw NumericalError(fmt::format(
          "circulation: the implicit step to t = {} s did not converge in {} Newton iterations; "
          "largest residual {:.3e} mm³ in '{}'",
          t_new, kMaxIterations, norm, unknown_name_[worst]));
    previous = norm;
    const Eigen::VectorXd delta = ev.J.partialPivLu().solve(-ev.r);
    for (int u = 0; u < m; ++u) y[u] += delta[u];
  }

  // Exact volume bookkeeping from the converged flows (conservation to round-off).
  for (size_t k = 0; k < nodes_.size(); ++k) {
    const int u = node_unknown_[k];
    if (u < 0 || nodes_[k].kind == NodeKind::junction) continue;
    double net = 0.0;
    for (int e = 0; e < nl; ++e)
      net += links_[e].to == static_cast<int>(k) ? ev.Q[e]
             : links_[e].from == static_cast<int>(k) ? -ev.Q[e] : 0.0;
    y[u] = y_n[u] + dt * net;
  }

  CavityFlows f;
  f.n = nc;
  f.newton_iterations = it;
  f.Q_net.assign(nc, 0.0);
  f.dQ_dp.assign(static_cast<size_t>(nc * nc), 0.0);
  // dy/dp = −J⁻¹ ∂r/∂p (the converged update's sensitivity), then the chain rule.
  Eigen::MatrixXd dy_dp = Eigen::MatrixXd::Zero(m, 3 * nc);
  if (m) dy_dp = ev.J.partialPivLu().solve(-ev.Jp);
  const Eigen::MatrixXd dQ = ev.dQ_dp + ev.dQ_dy * dy_dp;  // per link × (p_cav, ring pressures)
  for (size_t k = 0; k < nodes_.size(); ++k) {
    if (nodes_[k].kind != NodeKind::cavity) continue;
    const int c = nodes_[k].cavity;
    for (int e = 0; e < nl; ++e) {
      const double s = links_[e].to == static_cast<int>(k) ? 1.0
                       : links_[e].from == static_cast<int>(k) ? -1.0 : 0.0;
      if (s == 0.0) continue;
      f.Q_net[c] += s * ev.Q[e];
      for (int j = 0; j < nc; ++j) f.dQ_dp[static_cast<size_t>(c * nc + j)] += s * dQ(e, j);
    }
  }
  for (int c = 0; c < nc; ++c) {
    f.Q_in.push_back(ev.Q[inflow_valve_[c]]);
    f.Q_out.push_back(ev.Q[outflow_valve_[c]]);
    for (int j = 0; j < nc; ++j) {
      f.dQin_dp.push_back(dQ(inflow_valve_[c], j));
      f.dQout_dp.push_back(dQ(outflow_valve_[c], j));
    }
    for (int j = nc; j < 3 * nc; ++j) {
      f.dQin_dport.push_back(dQ(inflow_valve_[c], j));
      f.dQout_dport.push_back(dQ(outflow_valve_[c], j));
    }
    // Δp with the cavity at p_c, and across the valve as it passes blood (its ring's π).
    const auto drop = [&](int e, bool at_port) {
      const Link& l = links_[static_cast<size_t>(e)];
      const auto end = [&](int k) {
        return at_port && ports.node[static_cast<size_t>(e)] == k ? ports.pressure[static_cast<size_t>(e)]
                                                                   : node_pressure(k, t_new, p_cav, y);
      };
      return end(l.from) - end(l.to);
    };
    f.inflow_drop.push_back(drop(inflow_valve_[c], false));
    f.outflow_drop.push_back(drop(outflow_valve_[c], false));
    const auto passes = [&](int e, double above) {
      return !ports.shut[static_cast<size_t>(e)] && drop(e, true) > above;
    };
    const auto reversed = [&](int e) {
      return !ports.shut[static_cast<size_t>(e)] && drop(e, true) < -links_[static_cast<size_t>(e)].valve.width;
    };
    f.inflow_open.push_back(passes(inflow_valve_[c], 0.0));
    f.outflow_open.push_back(passes(outflow_valve_[c], 0.0));
    f.inflow_reversed.push_back(reversed(inflow_valve_[c]));
    f.outflow_reversed.push_back(reversed(outflow_valve_[c]));
    const bool in_open = f.inflow_open.back(), out_open = f.outflow_open.back();
    f.phase.push_back(phase(in_open, out_open, p_cav[c] - committed[m + c]));
  }
  report_compartments(t_new, p_cav, y, f);
  f.flows.assign(ev.Q.data(), ev.Q.data() + nl);

  std::copy(y.begin(), y.end(), current.begin());
  for (int c = 0; c < nc; ++c) current[m + c] = p_cav[c];
  return f;
}

std::string Circulation::phase(bool inflow_open, bool outflow_open, double dp) {
  if (inflow_open && outflow_open) return "both valves open";
  if (inflow_open) return "filling";
  if (outflow_open) return "ejection";
  return dp >= 0.0 ? "isovolumic contraction" : "isovolumic relaxation";
}

double Circulation::blood_volume(std::span<const double> state) const {
  double v = 0.0;
  for (size_t k = 0; k < nodes_.size(); ++k)
    if (node_unknown_[k] >= 0 && nodes_[k].kind != NodeKind::junction) v += state[node_unknown_[k]];
  return v;
}

bool Circulation::closed() const {
  for (const Node& node : nodes_)
    if (node.kind == NodeKind::fixed) return false;
  return true;
}

std::vector<std::string> Circulation::compartment_names() const {
  std::vector<std::string> out;
  for (const Node& node : nodes_) out.push_back(node.name);
  return out;
}

std::vector<std::string> Circulation::connection_names() const {
  std::vector<std::string> out;
  for (const Link& l : links_) out.push_back(l.name);
  return out;
}

}  // namespace fe2
