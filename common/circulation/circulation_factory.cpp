#include "common/circulation/circulation_factory.h"

#include "common/circulation/circulation_keys.h"
#include "common/error.h"

#include <spdlog/fmt/fmt.h>

namespace fe2 {
namespace {

using namespace circulation_keys;
using Node = Circulation::Node;
using Link = Circulation::Link;
using NodeKind = Circulation::NodeKind;
using LinkKind = Circulation::LinkKind;

/// The network under construction.
struct Net {
  std::vector<std::string> cavities;
  std::vector<Node> nodes;
  std::vector<Link> links;
  std::vector<int> inflow, outflow;
  int left_ventricle = -1;         ///< cavity index of "lv"
  std::vector<std::string> words;  ///< description pieces

  int node(Node n) {
    nodes.push_back(std::move(n));
    return static_cast<int>(nodes.size()) - 1;
  }
  int cavity(const std::string& name) {
    Node n;
    n.name = name;
    n.kind = NodeKind::cavity;
    n.cavity = static_cast<int>(cavities.size());
    cavities.push_back(name);
    inflow.push_back(-1);
    outflow.push_back(-1);
    return node(std::move(n));
  }
  int fixed(const std::string& name, double p) {
    Node n;
    n.name = name;
    n.kind = NodeKind::fixed;
    n.pressure = p;
    return node(std::move(n));
  }
  int compliance(const std::string& name, double C, double p0) {
    Node n;
    n.name = name;
    n.kind = NodeKind::compliance;
    n.compliance = C;
    n.pressure = p0;
    return node(std::move(n));
  }
  int elastance(const std::string& name, const ElastanceParameters& e, double period) {
    Node n;
    n.name = name;
    n.kind = NodeKind::elastance;
    n.elastance = TimeVaryingElastance(e, period);
    return node(std::move(n));
  }
  int junction(const std::string& name, double p0) {
    Node n;
    n.name = name;
    n.kind = NodeKind::junction;
    n.pressure = p0;
    return node(std::move(n));
  }
  int link(Link l) {
    links.push_back(std::move(l));
    return static_cast<int>(links.size()) - 1;
  }
  int resistor(const std::string& name, int from, int to, double R) {
    Link l;
    l.name = name, l.from = from, l.to = to, l.kind = LinkKind::resistor, l.R = R;
    return link(std::move(l));
  }
  int valve(const std::string& name, int from, int to, const ValveParameters& v) {
    Link l;
    l.name = name, l.from = from, l.to = to, l.kind = LinkKind::valve, l.valve = v;
    return link(std::move(l));
  }
  /// An RL vessel segment; L = 0 makes it a plain resistor.
  int vessel(const std::string& name, int from, int to, double R, double L) {
    if (L == 0.0) return resistor(name, from, to, R);
    Link l;
    l.name = name, l.from = from, l.to = to, l.kind = LinkKind::inertance, l.R = R, l.L = L;
    return link(std::move(l));
  }
};

ValveParameters read_valve(SpecNode& parent, const std::string& key) {
  SpecNode node = parent.child(key);
  const ValveParameters v = read_keys(node, valve_keys());
  if (v.R_closed <= v.R_open)
    node.fail("R_closed", fmt::format("a resistance above R_open = {} Pa s/mm^3 (a closed valve "
                                      "must resist more than an open one)", v.R_open));
  node.finish();
  return v;
}

std::string show_valve(const ValveParameters& v) {
  return fmt::format("R_open {:.3g}, R_closed {:.3g} Pa s/mm³, w {:.3g} Pa", v.R_open, v.R_closed, v.width);
}

/// One cavity of the windkessel kind: preload → inflow valve → cavity → outflow valve →
/// proximal junction → Z_c → compliance C → R_p → distal pressure.
void windkessel_cavity(Net& net, SpecNode& node, const std::string& name, bool left, double period) {
  const int cav = net.cavity(name);
  if (left) net.left_ventricle = net.nodes[cav].cavity;
  SpecNode pre = node.child("preload");
  const std::string pkind = pre.choice("kind");
  int source = -1;
  std::string words;
  if (pkind == "pressure") {
    const double p = pre.number(kPreloadPressure.key);
    source = net.fixed(name + ".preload", p);
    words = fmt::format("preload {:.4g} Pa", p);
  } else {
    const ElastanceParameters a = read_elastance(pre, period);
    const PreloadParameters feed = read_keys(pre, atrium_feed_keys());
    const int venous = net.fixed(name + ".venous", feed.p_venous);
    source = net.elastance(name + ".atrium", a, period);
    net.resistor(name + ".venous_return", venous, source, feed.R_venous);
    words = fmt::format("atrium E {:.3g}–{:.3g} Pa/mm³ fed at {:.4g} Pa", a.E_min, a.E_max, feed.p_venous);
  }
  pre.finish();
  const ValveParameters vin = read_valve(node, "inflow_valve");
  const ValveParameters vout = read_valve(node, "outflow_valve");
  SpecNode wk_node = node.child("windkessel");
  const WindkesselParameters wk = read_keys(wk_node, windkessel_keys());
  wk_node.finish();
  node.finish();

  const int cav_index = net.nodes[cav].cavity;
  net.inflow[cav_index] = net.valve(name + ".inflow_valve", source, cav, vin);
  const int proximal = net.junction(name + ".proximal", wk.p0);
  net.outflow[cav_index] = net.valve(name + ".outflow_valve", cav, proximal, vout);
  const int arterial = net.compliance(name + ".arterial", wk.C, wk.p0);
  net.resistor(name + ".Zc", proximal, arterial, wk.Zc);
  const int distal = net.fixed(name + ".distal", wk.p_distal);
  net.resistor(name + ".Rp", arterial, distal, wk.Rp);
  net.words.push_back(fmt::format(
      "{}: {}; valves in {}, out {}; Windkessel Zc {:.4g}, Rp {:.4g} Pa s/mm³, C {:.4g} mm³/Pa "
      "(R_p C = {:.3g} s), p_distal {:.4g} Pa, p0 {:.4g} Pa",
      name, words, show_valve(vin), show_valve(vout), wk.Zc, wk.Rp, wk.C, wk.Rp * wk.C,
      wk.p_distal, wk.p0));
}

void make_windkessel(Net& net, SpecNode& node, double period) {
  SpecNode cav = node.child("cavities");
  SpecNode lv = cav.child("lv");
  windkessel_cavity(net, lv, "lv", true, period);
  if (cav.has("rv")) {
    SpecNode rv = cav.child("rv");
    windkessel_cavity(net, rv, "rv", false, period);
  } else {
    cav.child("rv");  // declared: rv is a known key
  }
  cav.finish();
}

VesselParameters read_vessels(SpecNode& parent, const std::string& key) {
  SpecNode node = parent.child(key);
  const VesselParameters v = read_keys(node, vessel_keys());
  node.finish();
  return v;
}

/// Regazzoni 2022's loop: LA → mitral → LV → aortic → AR_SYS → VEN_SYS → RA → tricuspid
/// → RV → pulmonary → AR_PUL → VEN_PUL → LA.
void make_closed_loop(Net& net, SpecNode& node, double period) {
  SpecNode cav = node.child("cavities");
  SpecNode lv_node = cav.child("lv");
  const ValveParameters mitral = read_valve(lv_node, "inflow_valve");
  const ValveParameters aortic = read_valve(lv_node, "outflow_valve");
  lv_node.finish();
  const bool rv_coupled = cav.has("rv");
  SpecNode rv_node = cav.child("rv");
  const ValveParameters tricuspid = read_valve(rv_node, "inflow_valve");
  const ValveParameters pulmonary_valve = read_valve(rv_node, "outflow_valve");
  rv_node.finish();
  cav.finish();
  const VesselParameters sys = read_vessels(node, "systemic");
  const VesselParameters pul = read_vessels(node, "pulmonary");
  SpecNode la_node = node.child("left_atrium");
  const ElastanceParameters la = read_elastance(la_node, period);
  la_node.finish();
  SpecNode ra_node = node.child("right_atrium");
  const ElastanceParameters ra = read_elastance(ra_node, period);
  ra_node.finish();
  if (rv_coupled && node.has("right_ventricle"))
    node.fail("right_ventricle", "no right_ventricle: cavities has rv, so the wall model (or "
                                 "the elastance of `ventricles`) is the right ventricle");
  SpecNode irv_node = node.child("right_ventricle");
  const ElastanceParameters irv = read_elastance(irv_node, period);
  irv_node.finish();

  const int lv = net.cavity("lv");
  net.left_ventricle = net.nodes[lv].cavity;
  const int rv = rv_coupled ? net.cavity("rv") : net.elastance("rv", irv, period);
  const int LA = net.elastance("left_atrium", la, period);
  const int RA = net.elastance("right_atrium", ra, period);
  const int ar_sys = net.compliance("systemic_arteries", sys.C_ar, sys.p_ar_init);
  const int ven_sys = net.compliance("systemic_veins", sys.C_ven, sys.p_ven_init);
  const int ar_pul = net.compliance("pulmonary_arteries", pul.C_ar, pul.p_ar_init);
  const int ven_pul = net.compliance("pulmonary_veins", pul.C_ven, pul.p_ven_init);
  net.inflow[net.left_ventricle] = net.valve("mitral_valve", LA, lv, mitral);
  net.outflow[net.left_ventricle] = net.valve("aortic_valve", lv, ar_sys, aortic);
  net.vessel("systemic_arterial_flow", ar_sys, ven_sys, sys.R_ar, sys.L_ar);
  net.vessel("systemic_venous_flow", ven_sys, RA, sys.R_ven, sys.L_ven);
  const int tv = net.valve("tricuspid_valve", RA, rv, tricuspid);
  const int pv = net.valve("pulmonary_valve", rv, ar_pul, pulmonary_valve);
  if (rv_coupled) net.inflow[1] = tv, net.outflow[1] = pv;
  net.vessel("pulmonary_arterial_flow", ar_pul, ven_pul, pul.R_ar, pul.L_ar);
  net.vessel("pulmonary_venous_flow", ven_pul, LA, pul.R_ven, pul.L_ven);
  net.words.push_back(fmt::format(
      "cavities {}; systemic R_ar {:.4g}, C_ar {:.4g}, L_ar {:.3g}, R_ven {:.4g}, C_ven {:.4g}; "
      "pulmonary R_ar {:.4g}, C_ar {:.4g}, R_ven {:.4g}, C_ven {:.4g} (Pa, mm³, s); atria E_max "
      "{:.3g}/{:.3g} Pa/mm³; mitral {}",
      rv_coupled ? "lv, rv" : "lv (rv an internal elastance)", sys.R_ar, sys.C_ar, sys.L_ar,
      sys.R_ven, sys.C_ven, pul.R_ar, pul.C_ar, pul.R_ven, pul.C_ven, la.E_max, ra.E_max,
      show_valve(mitral)));
}

}  // namespace

ElastanceParameters read_elastance(SpecNode& node, double period) {
  const ElastanceParameters e = read_keys(node, elastance_keys());
  if (e.E_max < e.E_min)
    node.fail("E_max", fmt::format("an elastance >= E_min = {} Pa/mm^3", e.E_min));
  if (e.onset >= period)
    node.fail("onset", fmt::format("an onset below the period {} s", period));
  if (e.contraction + e.relaxation > period)
    node.fail("relaxation",
              fmt::format("T_C + T_R = {} + {} s within the period {} s (the beat period is "
                          "shorter than the activation window)",
                          e.contraction, e.relaxation, period));
  return e;
}

std::shared_ptr<const Circulation> make_circulation(SpecNode& node) {
  const std::string kind = node.choice("kind");
  const double period = node.number("period");
  Net net;
  if (kind == "windkessel") make_windkessel(net, node, period);
  else make_closed_loop(net, node, period);
  node.finish();
  std::string description = fmt::format("circulation {} (period {} s): ", kind, period);
  for (size_t i = 0; i < net.words.size(); ++i) description += (i ? "; " : "") + net.words[i];
  // Checked here, not in Circulation's constructor: a check there changes how GCC compiles
  // Circulation::step, and with it the last bits of the coupled runs.
  FE2_CHECK(net.left_ventricle >= 0, "circulation {}: no left ventricle among the cavities", kind);
  return std::make_shared<const Circulation>(kind, net.cavities, std::move(net.nodes),
                                             std::move(net.links), net.inflow, net.outflow,
                                             period, description, net.left_ventricle);
}

}  // namespace fe2
