#include "coordinator/fluid_spec.h"

#include "common/error.h"
#include "coordinator/RunSpec.h"
#include "coordinator/macro/fluid_scene.h"

#include <algorithm>
#include <type_traits>

namespace fe2 {

namespace {

Vec3 vec3_of(const std::vector<double>& v) { return {v[0], v[1], v[2]}; }

std::array<bool, 3> components_of(SpecNode& b) {
  std::array<bool, 3> c = {false, false, false};
  for (double k : b.numbers("components")) c[static_cast<int>(k)] = true;  // integers in [0, 2]
  return c;
}

/// value · ramp(t) of a boundary entry (a number or three).
template <class Value>
std::function<Value(double)> ramped(SpecNode& b, const RunSpec& spec) {
  Value value;
  if constexpr (std::is_same_v<Value, double>) value = b.number("value");
  else value = vec3_of(b.numbers("value"));
  const Ramp ramp = b.choice("ramp") == "linear" ? Ramp::linear : Ramp::constant;
  const double t_end = spec.t_end;
  return [value, ramp, t_end](double t) { return Value(value * ramp_factor(ramp, t, t_end)); };
}

template <class Named>
void check_set(SpecNode& b, const Named& sets, const std::string& set, const char* what) {
  if (sets.count(set)) return;
  std::vector<std::string> names;
  for (const auto& [name, _] : sets) names.push_back(name);
  b.fail("set", known_names(what, set, names));
}

}  // namespace

std::shared_ptr<const FluidSetup> read_fluid(SpecNode node, const RunSpec& spec) {
  if (!node.has("regions")) {
    node.finish();
    return nullptr;
  }
  auto setup = std::make_shared<FluidSetup>();
  FluidSetup& s = *setup;
  s.regions = read_region_list(node, "regions", spec);
  for (int tag : s.regions)
    if (spec.is_wall_region(tag))
      node.fail("regions", fmt::format("regions that are not wall (region {} is; set /mesh/wall_regions to the "
                                       "wall's regions alone)",
                                       tag));
  s.fluid = {node.number("density"), node.number("viscosity")};
  const std::string element = node.choice("element");
  const int order = spec.mesh.order();
  if (element == "auto") s.element = order == 2 ? FluidElementKind::taylor_hood : FluidElementKind::stabilized_p1p1;
  else if (element == "taylor_hood") s.element = FluidElementKind::taylor_hood;
  else if (element == "taylor_hood_supg") s.element = FluidElementKind::taylor_hood_supg;
  else s.element = FluidElementKind::stabilized_p1p1;
  if (fluid_velocity_order(s.element) != order)
    node.fail("element", fmt::format("the element of the mesh's order ({}): {}", order == 2 ? "quadratic" : "linear",
                                     order == 2 ? "\"taylor_hood\", \"taylor_hood_supg\" or \"auto\""
                                                : "\"p1p1\" or \"auto\""));
  s.convection = node.choice("convection") == "skew_symmetric" ? ConvectiveForm::skew_symmetric : ConvectiveForm::advective;
  const std::string time = node.choice("time");
  s.time = time == "bdf2" ? TimeScheme::bdf2 : time == "bdf1" ? TimeScheme::backward_euler : TimeScheme::none;
  s.body_force = vec3_of(node.numbers("body_force"));
  const Vec3 v0 = vec3_of(node.numbers("initial_velocity"));
  if (v0.squaredNorm() > 0) s.initial_velocity = [v0](const Vec3&) { return v0; };
  s.residual_pressure = node.number("residual_pressure");
  s.rtol = spec.rtol_of("fluid_velocity");

  for (SpecNode& b : node.children("boundaries")) {
    const std::string kind = b.choice("kind");
    const std::string set = b.string("set");
    if (kind == "moving_wall") {
      check_set(b, spec.mesh.node_sets, set, "a named node set, face or interface of the mesh");
      if (!node.has("mesh_motion"))
        b.fail("kind", "no_slip (a moving_wall needs /fluid/mesh_motion: the wall's velocity is the mesh's)");
      s.boundaries.push_back(FluidBoundary::moving_wall(set));
    } else if (kind == "no_slip" || kind == "velocity") {
      check_set(b, spec.mesh.node_sets, set, "a named node set or face of the mesh");
      const std::array<bool, 3> comps = components_of(b);
      if (kind == "no_slip") {
        s.boundaries.push_back(FluidBoundary::no_slip(set, comps));
      } else {
        auto g = ramped<Vec3>(b, spec);
        s.boundaries.push_back(FluidBoundary::prescribed_velocity(set, [g](const Vec3&, double t) { return g(t); }, comps));
      }
    } else {
      check_set(b, spec.mesh.faces, set, "a named boundary face set of the mesh");
      if (kind == "pressure") {
        s.boundaries.push_back(FluidBoundary::pressure(set, ramped<double>(b, spec), b.number("backflow")));
      } else if (kind == "traction") {
        s.boundaries.push_back(FluidBoundary::traction_of(set, ramped<Vec3>(b, spec), b.number("backflow")));
      } else if (kind == "valve") {
        const std::string cavity = b.string("cavity");
        if (!spec.circulation) b.fail("kind", "flux or pressure (a valve ring needs /circulation: its flow)");
        const auto& names = spec.circulation->cavity_names();
        const auto it = std::find(names.begin(), names.end(), cavity);
        if (it == names.end()) b.fail("cavity", known_names("a cavity of the circulation", cavity, names));
        const FluidBoundary::Valve valve{static_cast<int>(it - names.begin()), b.choice("side") == "outflow"};
        for (const FluidBoundary& other : s.boundaries)
          if (other.valve && other.valve->cavity == valve.cavity && other.valve->outflow == valve.outflow)
            b.fail("side", fmt::format("the {} valve of cavity '{}' once (ring '{}' is already its ring)",
                                       valve.outflow ? "outflow" : "inflow", cavity, other.set));
        s.boundaries.push_back(FluidBoundary::valve_flux(set, valve, b.number("backflow")));
      } else {
        s.boundaries.push_back(FluidBoundary::flux(set, ramped<double>(b, spec), b.number("backflow")));
      }
    }
    b.finish();
  }

  if (node.has("mesh_motion")) {
    SpecNode m = node.child("mesh_motion");
    MeshMotionSetup motion;
    motion.kind = m.choice("kind") == "elastic" ? MeshMotionKind::elastic : MeshMotionKind::harmonic;
    motion.stiffening = m.number("stiffening");
    for (SpecNode& b : m.children("boundaries")) {
      const std::string set = b.string("set");
      check_set(b, spec.mesh.node_sets, set, "a named node set or face of the mesh");
      if (b.choice("follow") == "fixed")
        motion.boundaries.push_back({set, [](const Vec3&, double) { return Vec3(Vec3::Zero()); }});
      else
        motion.boundaries.push_back({set, {}});
      b.finish();
    }
    m.finish();
    s.mesh_motion = motion;
  }
  s.two_way = node.choice("coupling") == "two_way";
  s.shape_derivatives = s.two_way;
  if (s.two_way) {
    const bool walls = std::any_of(s.boundaries.begin(), s.boundaries.end(),
                                   [](const FluidBoundary& b) { return b.kind == FluidBoundary::Kind::moving_wall; });
    if (!walls) node.fail("coupling", "\"one_way\" (two_way couples the blood's moving_wall sets to the wall: there are none)");
    // Each of the circulation's cavities is then filled with the blood its valve rings
    // name (CavityPressureTerm.h): the blood, not a lumped pressure, loads its wall.
    if (spec.circulation)
      for (size_t c = 0; c < spec.circulation->cavity_names().size(); ++c)
        if (std::none_of(s.boundaries.begin(), s.boundaries.end(),
                         [&](const FluidBoundary& b) { return b.valve && b.valve->cavity == static_cast<int>(c); }))
          node.fail("coupling", fmt::format("\"one_way\", or valve rings for the circulation's cavity '{}' (two_way "
                                            "blood fills every cavity of the circulation and passes its flows through "
                                            "the rings)",
                                            spec.circulation->cavity_names()[c]));
  }
  node.finish();
  check_fluid_setup(spec.mesh, s);
  return setup;
}

}  // namespace fe2
