#include "coordinator/RunSpec.h"

#include "coordinator/fluid_spec.h"

#include "common/activation/activation_spec.h"
#include "common/circulation/circulation_factory.h"
#include "common/hash.h"
#include "common/materials/material_factory.h"
#include "common/mesh/box_mesh.h"
#include "common/mesh/gmsh_reader.h"
#include "common/mesh/lv_mesh.h"
#include "common/mesh/point_locator.h"
#include "common/fem/quadrature.h"
#include "coordinator/MacroPoints.h"
#include "coordinator/macro/macro_scene.h"
#include "common/spec/spec_schemas.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>

namespace fe2 {

double ramp_factor(Ramp ramp, double t, double t_end) {
  // Before t = 0 (an end-diastolic inflation) a linear ramp has not started.
  return ramp == Ramp::constant ? 1.0 : std::max(t, 0.0) / t_end;
}

Mat3 FrameSpec::at(const Vec3& X) const {
  FE2_CHECK(field.kind == FrameFieldSpec::Kind::constant || field.kind == FrameFieldSpec::Kind::rotating,
            "frame kinds 'file' and 'rule' need make_frame_field(spec.frame.field, mesh), not FrameSpec::at");
  AnalyticFrame a;  // the rule lives in common/fibres/AnalyticFrame
  a.fibre = fibre;
  a.sheet = sheet;
  a.rotating = rotating;
  a.axis = axis;
  a.coordinate = coordinate;
  a.c0 = c0;
  a.c1 = c1;
  a.angle0 = angle0;
  a.angle1 = angle1;
  return a.at(X);
}

bool RunSpec::contracts() const {
  for (const auto& m : models) {
    if (m.material && m.material->active_tension_slot() >= 0) return true;
    if (m.plan)
      for (const auto& law : m.plan->materials)
        if (law->active_tension_slot() >= 0) return true;
  }
  return false;
}

double RunSpec::rtol_of(const std::string& field) const {
  const auto it = field_rtol.find(field);
  return it == field_rtol.end() ? newton_rtol : it->second;
}

bool RunSpec::is_wall_region(int tag) const {
  return wall_regions.empty() || std::binary_search(wall_regions.begin(), wall_regions.end(), tag);
}

bool RunSpec::is_wall(int e) const { return is_wall_region(mesh.region[static_cast<size_t>(e)]); }

std::vector<int> RunSpec::wall_elements_among(const std::vector<int>& elements) const {
  std::vector<int> out;
  for (int e : elements)
    if (is_wall(e)) out.push_back(e);
  return out;
}

std::vector<int> RunSpec::wall_elements() const {
  std::vector<int> all(static_cast<size_t>(mesh.num_tets()));
  for (int e = 0; e < mesh.num_tets(); ++e) all[static_cast<size_t>(e)] = e;
  return wall_elements_among(all);
}

int RunSpec::model_index_of_tet(int e) const {
  auto it = model_of_region.find(mesh.region[e]);
  return it == model_of_region.end() ? default_model : it->second;
}

std::vector<int> RunSpec::model_of_points() const {
  std::vector<int> m;
  m.reserve(num_points());
  for (int e : wall_elements()) m.insert(m.end(), points_per_element, model_index_of_tet(e));
  return m;
}

namespace {

/// The keys of a name-keyed container (node sets, faces, cavities), for errors.
template <class Named>
std::vector<std::string> names_of(const Named& named) {
  std::vector<std::string> out;
  for (const auto& [name, _] : named) out.push_back(name);
  return out;
}

Vec3 vec3(SpecNode& s, const std::string& key) {
  const auto v = s.numbers(key);
  return Vec3(v[0], v[1], v[2]);
}

Ramp read_ramp(SpecNode& s) {
  return s.choice("ramp") == "linear"
             ? Ramp::linear
             : Ramp::constant;
}

int axis_index(const std::string& a) { return a[0] - 'x'; }

/// The region tag of `name` (a tag or a physical volume name) in the spec's mesh, or an
/// InputError at `where` listing the regions the mesh has: a region it lacks would
/// silently leave the elements meant for it with the default.
int region_tag(const RunSpec& spec, const std::string& where, const std::string& name) {
  char* end = nullptr;
  const long t = std::strtol(name.c_str(), &end, 10);
  int found = -1;
  if (end && end != name.c_str() && *end == '\0') found = static_cast<int>(t);
  for (const auto& [rt, rn] : spec.mesh.region_names)
    if (rn == name) found = rt;
  const std::set<int> present(spec.mesh.region.begin(), spec.mesh.region.end());
  if (found >= 0 && present.count(found)) return found;
  std::vector<std::string> known;  // tags, and the names of named regions
  for (int r : present) {
    known.push_back(std::to_string(r));
    const auto nm = spec.mesh.region_names.find(r);
    if (nm != spec.mesh.region_names.end()) known.push_back(nm->second);
  }
  throw InputError(fmt::format("{}: got region \"{}\", which is not in the mesh {}; expected {}", where, name,
                               spec.mesh_source, known_names("one of its regions", name, known)));
}

/// mesh.wall_regions: tags or names, each once; absent: every region is wall. A named
/// interface between the wall and another region (an endocardium with blood on its
/// other side) is a surface of the wall too: a face set of its name, oriented out of the
/// wall, for loads, cavities, excitation and fibres.
void read_wall_regions(SpecNode& m, RunSpec& spec) {
  if (m.has("wall_regions")) spec.wall_regions = read_region_list(m, "wall_regions", spec);
  if (spec.wall_regions.empty()) return;
  for (const auto& [name, tris] : spec.mesh.interfaces)
    if (!spec.mesh.faces.count(name))
      if (auto wall_side = oriented_from(spec.mesh, tris, [&spec](int e) { return spec.is_wall(e); }))
        spec.mesh.faces[name] = std::move(*wall_side);
}

/// A Dirichlet set holds the wall where it meets it (a base plane may cross a cavity
/// region too); one that misses the wall entirely is a mistake.
void check_on_wall(const RunSpec& spec, const std::string& where, const std::string& name,
                   const std::vector<int>& nodes) {
  if (spec.wall_regions.empty()) return;
  std::vector<char> on_wall(static_cast<size_t>(spec.mesh.num_nodes()), 0);
  for (int e : spec.wall_elements())
    for (int a : spec.mesh.element_nodes(e)) on_wall[static_cast<size_t>(a)] = 1;
  for (int a : nodes)
    if (on_wall[static_cast<size_t>(a)]) return;
  throw InputError(fmt::format("{}: node set '{}' has no node on the wall (/mesh/wall_regions); expected a set "
                               "that holds the wall",
                               where, name));
}

/// A surface load or cavity must bound the wall, every triangle of it.
void check_wall_surface(const RunSpec& spec, const std::string& where, const std::string& surface) {
  if (spec.wall_regions.empty()) return;
  const auto& tris = spec.mesh.faces.at(surface);
  const std::vector<int> tet = face_elements(spec.mesh, tris);
  for (size_t k = 0; k < tris.size(); ++k)
    if (!spec.is_wall(tet[k]))
      throw InputError(fmt::format("{}: surface '{}' bounds element {} of region {}, which is not in "
                                   "/mesh/wall_regions; expected a surface of the wall",
                                   where, surface, tet[k], spec.mesh.region[static_cast<size_t>(tet[k])]));
}

void read_mesh(SpecNode m, RunSpec& spec) {
  const std::string kind = m.choice("kind");
  const auto order = [&] { return m.integer("order"); };
  if (kind == "box") {
    const Vec3 lo = vec3(m, "lo");
    const Vec3 hi = vec3(m, "hi");
    const auto div = m.numbers("divisions");  // integers in [1, 1000] (the schema)
    const std::array<int, 3> d{static_cast<int>(div[0]), static_cast<int>(div[1]),
                               static_cast<int>(div[2])};
    for (int i = 0; i < 3; ++i)
      if (!(hi[i] > lo[i])) m.fail("hi", "a corner above 'lo' in every axis");
    SpecNode slabs = m.child("region_slabs");
    const int axis = axis_index(slabs.choice("axis"));
    const int count = slabs.integer("count");
    slabs.finish();
    spec.mesh = make_box_mesh(lo, hi, d, count > 1 ? axis : -1, count, order());
    spec.mesh_source = "box generator";
  } else if (kind == "lv") {
    // Truncated prolate ellipsoids; defaults: problem 2 of Land et al. 2015 (mm).
    LvMeshParams p;
    const auto endo = m.numbers("endo");
    const auto epi = m.numbers("epi");
    if (!(endo[0] > 0 && endo[1] > 0)) m.fail("endo", "two semi-axes > 0");
    if (!(epi[0] > endo[0] && epi[1] > endo[1])) m.fail("epi", "semi-axes larger than 'endo' (the epicardium encloses it)");
    p.endo_short = endo[0];
    p.endo_long = endo[1];
    p.epi_short = epi[0];
    p.epi_long = epi[1];
    p.base_z = m.number("base_z");
    if (!(std::abs(p.base_z) < p.endo_long)) m.fail("base_z", "a plane cutting the endocardium, |base_z| < endo[1]");
    const auto div = m.numbers("divisions");
    // The schema's integers in [1, 1000]; a ring needs three cells around.
    if (div[0] < 3) m.fail("divisions", m.expected("divisions") + ", the first (circumferential) >= 3");
    p.circumferential = static_cast<int>(div[0]);
    p.longitudinal = static_cast<int>(div[1]);
    p.transmural = static_cast<int>(div[2]);
    p.order = order();
    if (m.has("cavity")) {
      SpecNode cavity = m.child("cavity");
      p.cavity_layers = cavity.integer("layers");
      SpecNode rings = cavity.child("rings");
      for (auto it = rings.raw().begin(); it != rings.raw().end(); ++it) {
        SpecNode ring = rings.child(it.key());
        const auto centre = ring.numbers("center");
        p.rings.push_back({it.key(), centre[0], centre[1], ring.number("radius")});
        ring.finish();
      }
      rings.finish();
      cavity.finish();
    }
    try {
      spec.mesh = make_lv_mesh(p);
    } catch (const InputError& e) {  // the generator's own checks (rings in the cap): say where
      throw InputError(fmt::format("{}: {}", m.path(), e.what()));
    }
    spec.mesh_source = "LV generator";
  } else {
    std::filesystem::path p = m.string("file");
    if (p.is_relative()) p = std::filesystem::path(spec.base_dir) / p;
    spec.mesh = read_gmsh_tets(p.string());
    spec.mesh_source = p.string();
  }
  read_wall_regions(m, spec);
  m.finish();
}

void read_frame(SpecNode f, RunSpec& spec) {
  // Every kind is read in common/fibres/frame_spec.cpp; a fibre file's tags refer to
  // the Gmsh mesh file (generated meshes: tag = index + 1).
  const bool gmsh = spec.raw.contains("mesh") && spec.raw["mesh"].is_object() &&
                    spec.raw["mesh"].value("kind", std::string("box")) == "gmsh";
  FrameSpec& fr = spec.frame;
  fr.field = read_frame_field_spec(f, spec.mesh, spec.base_dir, gmsh ? spec.mesh_source : "",
                                   spec.formulation.quadrature_degree);
  const AnalyticFrame& a = fr.field.analytic;
  fr.fibre = a.fibre;
  fr.sheet = a.sheet;
  fr.rotating = a.rotating;
  fr.axis = a.axis;
  fr.coordinate = a.coordinate;
  fr.c0 = a.c0;
  fr.c1 = a.c1;
  fr.angle0 = a.angle0;
  fr.angle1 = a.angle1;
  f.finish();
}

/// Every cell model's calcium period under /models (the JSON pointer of each "active"
/// object and its calcium.period; absent: 0, one beat).
void collect_calcium_periods(const json& node, const std::string& path,
                             std::vector<std::pair<std::string, double>>& out) {
  if (!node.is_object()) return;
  for (auto it = node.begin(); it != node.end(); ++it) {
    const std::string here = path + "/" + it.key();
    if (it.key() == "active" && it.value().is_object()) {
      const json& a = it.value();
      double period = 0.0;
      if (a.contains("calcium") && a["calcium"].is_object() && a["calcium"].contains("period") &&
          a["calcium"]["period"].is_number())
        period = a["calcium"]["period"].get<double>();
      out.emplace_back(here + "/calcium/period", period);
    } else {
      collect_calcium_periods(it.value(), here, out);
    }
  }
}

/// A run of several heartbeats whose cells beat at another rhythm than the circulation
/// (or once only) is legal but almost never meant: the valves open to a heart that does
/// not contract, or contracts mid-filling.
void warn_on_calcium_period(RunSpec& spec) {
  const double period = spec.circulation->period();
  if (spec.t_end <= period * (1 + 1e-9)) return;  // one beat: the cells' period plays no part
  std::vector<std::pair<std::string, double>> periods;
  collect_calcium_periods(spec.raw.value("models", json::object()), "/models", periods);
  for (const auto& [where, p] : periods)
    if (std::abs(p - period) > 1e-9 * period)
      spec.warnings.push_back(fmt::format(
          "{}: {} but the circulation's period is {} s and the run lasts {:.3g} periods: the cells {}; "
          "set it to {} to make them beat with the circulation",
          where, p == 0.0 ? std::string("absent (one beat)") : fmt::format("{} s", p), period,
          spec.t_end / period, p == 0.0 ? "contract once" : "beat out of step with the valves", period));
}

void read_formulation(SpecNode f, RunSpec& spec) {
  FormulationSpec& fs = spec.formulation;
  fs.mixed = f.choice("kind") == "mixed";
  if (f.has("quadrature_degree"))
    fs.quadrature_degree = f.integer("quadrature_degree");
  const int degree = fs.quadrature_degree < 0 ? default_point_degree(spec.mesh.order()) : fs.quadrature_degree;
  spec.points_per_element = static_cast<int>(tet_rule(degree).size());
  if (fs.mixed) {
    if (f.has("bulk_modulus"))
      fs.bulk_modulus = f.number("bulk_modulus");
    if (f.has("stabilization_modulus"))
      fs.stabilization_modulus = f.number("stabilization_modulus");
    fs.element_pressure = f.choice("pressure") == "P1+P0";
    if (fs.element_pressure && spec.mesh.order() == 1)
      f.fail("pressure", fmt::format("'P1+P0' needs quadratic elements (P2/(P1+P0)); on the linear "
                                     "mesh {} use 'P1' with a stabilization_modulus",
                                     spec.mesh_source));
    // Equal-order P1/P1 violates the inf–sup condition: without stabilization the
    // pressure oscillates (checkerboard) and the Lagrange form is singular.
    if (spec.mesh.order() == 1 && fs.stabilization_modulus == 0.0)
      f.fail("stabilization_modulus",
             fmt::format("a modulus in Pa (about the tissue's shear modulus) for mixed P1/P1 on "
                         "the linear mesh {} (or a quadratic mesh, for Taylor–Hood P2/P1)",
                         spec.mesh_source));
  }
  f.finish();
}

/// /newton: the macro and micro tolerances, cutbacks and the macro solver. Read before
/// /models, whose units take micro_rtol as their Newton tolerance.
void read_newton(SpecNode n, RunSpec& spec) {
  spec.newton_max_iterations = n.integer("max_iterations");
  spec.newton_rtol = n.number("rtol");
  SpecNode per_field = n.child("field_rtol");
  for (auto it = per_field.raw().begin(); it != per_field.raw().end(); ++it)
    spec.field_rtol[it.key()] = per_field.number(it.key());
  per_field.finish();
  spec.micro_rtol = n.number("micro_rtol");
  spec.max_cutbacks = n.integer("max_cutbacks");
  spec.load_steps.max_cutbacks = spec.max_cutbacks;
  spec.line_search.backtracking = n.choice("line_search") == "backtracking";
  spec.line_search.min_step = n.number("line_search_min_step");
  {
    SpecNode m = n.child("macro_solver");
    MacroSolverOptions& o = spec.macro_solver;
    o.refresh = m.choice("refresh") == "adaptive"
                    ? MacroSolverOptions::Refresh::adaptive
                    : MacroSolverOptions::Refresh::every_iteration;
    o.gmres_rtol = m.number("gmres_rtol");
    o.forcing = m.choice("gmres_forcing") == "eisenstat_walker" ? MacroSolverOptions::Forcing::eisenstat_walker
                                                          : MacroSolverOptions::Forcing::constant;
    o.max_gmres_iterations = m.integer("max_gmres_iterations");
    o.ordering = m.choice("ordering") == "mumps" ? MacroSolverOptions::Ordering::mumps
                                                 : MacroSolverOptions::Ordering::metis;
    m.finish();
  }
  n.finish();
}

void read_models(SpecNode models, SpecNode assign, RunSpec& spec) {
  const auto names = [&] {
    std::vector<std::string> n;
    for (auto it = models.raw().begin(); it != models.raw().end(); ++it) n.push_back(it.key());
    return n;
  }();
  if (names.empty())
    throw InputError(fmt::format("{}: got {{}}, expected at least one point model, e.g. "
                                 "{{\"muscle\": {{\"kind\": \"macro_law\", \"material\": ...}}}}",
                                 models.path()));
  for (const auto& name : names) {
    SpecNode m = models.child(name);
    PointModelSpec pm;
    pm.name = name;
    const std::string kind = m.choice("kind");
    if (kind == "fe2") {
      pm.kind = PointModelSpec::Kind::fe2;
      MicroModelPlan plan = MicroModel::plan(m.child("unit"), spec.base_dir);
      plan.options.newton_rtol = spec.micro_rtol;  // Step 1 never solves below half of it
      pm.plan = std::make_shared<const MicroModelPlan>(std::move(plan));
    } else {
      pm.kind = PointModelSpec::Kind::macro_law;
      SpecNode mat = m.child("material");
      pm.material = make_material(mat);
    }
    m.finish();
    spec.models.push_back(std::move(pm));
  }
  auto index_of = [&](SpecNode& node, const std::string& key, const std::string& name) {
    for (size_t i = 0; i < names.size(); ++i)
      if (names[i] == name) return static_cast<int>(i);
    node.fail(key, known_names("the name of a model in /models", name, names));
  };
  // The default model depends on the spec (its first model), so the key has none.
  const std::string def =
      assign.has("default")
          ? assign.string("default")
          : names.front();
  spec.default_model = index_of(assign, "default", def);
  SpecNode regions = assign.child("regions");
  for (auto it = regions.raw().begin(); it != regions.raw().end(); ++it) {
    const std::string tag = it.key();
    const std::string model = regions.string(tag);
    const int found = region_tag(spec, regions.key_path(tag), tag);
    if (!spec.is_wall_region(found))
      throw InputError(fmt::format("{}: got region \"{}\", which is not in /mesh/wall_regions; expected a wall "
                                   "region (only the wall has point models)",
                                   regions.key_path(tag), tag));
    spec.model_of_region[found] = index_of(regions, tag, model);
  }
  regions.finish();
  assign.finish();
}

}  // namespace


namespace {

/// output.units: distinct ids of points that are FE² units (a macro-law point has no
/// micro mesh to write).
std::vector<int> read_output_units(SpecNode& out, const RunSpec& spec) {
  const json* v = out.declared_value("units");
  std::vector<int> units;
  if (!v) return units;
  const int n = spec.num_points();
  const std::string ids = fmt::format("an array of distinct FE² unit ids (integration points 0 to {})", n - 1);
  if (!v->is_array()) out.fail("units", ids);
  const std::vector<int> model = spec.model_of_points();
  for (const json& x : *v) {
    if (!x.is_number_integer() || x.get<long long>() < 0 || x.get<long long>() >= n)
      throw InputError(fmt::format("{}: unit {} is not an integration point; expected {}",
                                   out.key_path("units"), x.dump(), ids));
    const int u = x.get<int>();
    const PointModelSpec& m = spec.models[static_cast<size_t>(model[static_cast<size_t>(u)])];
    if (m.kind != PointModelSpec::Kind::fe2)
      throw InputError(fmt::format("{}: unit {} uses model '{}', a macro law with no micro mesh; "
                                   "expected a point of an FE² model (kind fe2)",
                                   out.key_path("units"), u, m.name));
    if (std::find(units.begin(), units.end(), u) != units.end())
      throw InputError(fmt::format("{}: unit {} is listed twice; expected {}", out.key_path("units"), u, ids));
    units.push_back(u);
  }
  return units;
}

/// An eikonal front follows the fibres: the frame field is built now (and kept, so the
/// macro side does not solve a rule's Laplace problems twice).
void read_activation_of(SpecNode& root, RunSpec& spec) {
  if (!root.has("activation")) return;
  spec.frame.built = make_frame_field(spec.frame.field, spec.mesh);
  const bool gmsh = spec.raw["mesh"].value("kind", std::string("box")) == "gmsh";
  SpecNode activation = root.child("activation");
  spec.activation = read_activation(activation, spec.mesh, spec.frame.built.get(), spec.base_dir,
                                    gmsh ? spec.mesh_source : "");
}

void read_dirichlet(SpecNode& root, RunSpec& spec) {
  for (auto& d : root.children("dirichlet")) {
    DirichletSpec ds;
    ds.set = d.string("set");
    if (!spec.mesh.node_sets.count(ds.set))
      d.fail("set", known_names("a node set of the mesh", ds.set, names_of(spec.mesh.node_sets)));
    check_on_wall(spec, d.key_path("set"), ds.set, spec.mesh.node_sets.at(ds.set));
    const auto comps = d.numbers("components");
    ds.fixed = {false, false, false};
    for (double c : comps) ds.fixed[static_cast<int>(c)] = true;  // integers in [0, 2] (the schema)
    ds.value = vec3(d, "value");
    ds.ramp = read_ramp(d);
    d.finish();
    spec.dirichlet.push_back(ds);
  }
  if (spec.dirichlet.empty())
    throw InputError("/dirichlet: got nothing, expected at least one Dirichlet condition "
                     "(a free body has no unique quasi-static solution)");
}

void read_pressure(SpecNode& root, RunSpec& spec) {
  for (auto& p : root.children("pressure")) {
    PressureSpec ps;
    ps.surface = p.string("surface");
    if (!spec.mesh.faces.count(ps.surface))
      p.fail("surface", known_names("a named surface of the mesh", ps.surface, names_of(spec.mesh.faces)));
    check_wall_surface(spec, p.key_path("surface"), ps.surface);
    ps.value = p.number("value");
    ps.ramp = read_ramp(p);
    p.finish();
    spec.pressure.push_back(ps);
  }
}

void read_time(SpecNode t, RunSpec& spec) {
  spec.t_end = t.number("t_end");
  spec.steps = t.integer("steps");
  spec.dynamic = t.choice("scheme") == "newmark";
  spec.beta = t.number("beta");
  spec.gamma = t.number("gamma");
  spec.density = t.number("density");
  spec.beats = t.integer("beats");
  spec.steps_per_beat = t.integer("steps_per_beat");
  spec.periodic_tolerance = t.number("periodic_tolerance");
  spec.inflation_steps = t.integer("inflation_steps");
  spec.load_steps.adaptive = t.boolean("adaptive");
  spec.load_steps.target_iterations = t.integer("target_iterations");
  if (t.has("max_dt")) spec.load_steps.max_dt = t.number("max_dt");
  if (t.has("min_dt")) spec.load_steps.min_dt = t.number("min_dt");
  if (spec.beats > 0 && (t.has("t_end") || t.has("steps")))
    t.fail("beats", "either beats (with steps_per_beat) or t_end and steps, not both");
  t.finish();
}

void read_cavities(SpecNode cavities, RunSpec& spec) {
  for (auto it = cavities.raw().begin(); it != cavities.raw().end(); ++it) {
    SpecNode c = cavities.child(it.key());
    const std::string surface = c.string("surface");
    if (!spec.mesh.faces.count(surface))
      c.fail("surface", known_names("a named surface of the mesh", surface, names_of(spec.mesh.faces)));
    check_wall_surface(spec, c.key_path("surface"), surface);
    c.finish();
    spec.cavities.emplace_back(it.key(), surface);
  }
  cavities.finish();
}

/// The 0D circulation and the cavities it couples (by name, from /cavities).
void read_circulation(SpecNode& root, RunSpec& spec) {
  if (!root.has("circulation")) return;
  SpecNode circ = root.child("circulation");
  spec.circulation = make_circulation(circ);
  for (const std::string& name : spec.circulation->cavity_names()) {
    int found = -1;
    for (size_t c = 0; c < spec.cavities.size(); ++c)
      if (spec.cavities[c].first == name) found = static_cast<int>(c);
    if (found < 0) {
      throw InputError(fmt::format(
          "/circulation/cavities/{}: no cavity '{}' in /cavities; expected {} (every cavity of the "
          "circulation needs its bounding surface there)",
          name, name, known_names("a cavity of /cavities", name, names_of(spec.cavities))));
    }
    spec.coupled_cavities.push_back(found);
  }
  if (spec.beats > 0) {
    spec.t_end = spec.beats * spec.circulation->period();
    spec.steps = spec.beats * spec.steps_per_beat;
  }
  warn_on_calcium_period(spec);
  for (const auto& ps : spec.pressure)
    for (int c : spec.coupled_cavities)
      if (ps.surface == spec.cavities[c].second)
        throw InputError(fmt::format("/pressure: a prescribed pressure on '{}', the surface of cavity '{}' "
                                     "whose pressure the circulation sets; expected no /pressure entry there",
                                     ps.surface, spec.cavities[c].first));
}

/// time.inflation_steps: steps of the beat's size before t = 0, counted in `steps`.
void add_inflation_steps(RunSpec& spec) {
  if (spec.inflation_steps == 0) return;
  if (!spec.circulation)
    throw InputError(fmt::format("/time/inflation_steps: got {}, expected 0 without a /circulation (the wall is "
                                 "inflated to the circulation's filling pressure)",
                                 spec.inflation_steps));
  spec.t_start = -spec.inflation_steps * (spec.t_end / spec.steps);
  spec.steps += spec.inflation_steps;
}

void read_probes(SpecNode probes, RunSpec& spec) {
  for (auto it = probes.raw().begin(); it != probes.raw().end(); ++it) {
    const std::string name = it.key();
    const Vec3 X = vec3(probes, name);
    bool in_wall = false;
    try {
      in_wall = spec.is_wall(locate_point(spec.mesh, X).tet);
    } catch (const InputError&) {
      probes.fail(name, "a point inside the mesh");
    }
    if (!in_wall) probes.fail(name, "a point inside the wall (/mesh/wall_regions)");
    spec.probes.emplace_back(name, X);
  }
  probes.finish();
}

void read_output(SpecNode out, RunSpec& spec) {
  spec.output_every = out.integer("every");
  spec.write_vtu = out.boolean("vtu");
  spec.output_units = read_output_units(out, spec);
  spec.checkpoint_every = out.integer("checkpoint_every");
  spec.checkpoint_factors = out.boolean("checkpoint_factors");
  out.finish();
}

/// A tolerance for a field this scene lacks would be ignored without a word.
void check_field_tolerances(const RunSpec& spec) {
  if (spec.field_rtol.empty()) return;
  const FieldTable fields = scene_fields(spec);
  std::vector<std::string> names;
  for (const Field& f : fields) names.push_back(f.name());
  for (const auto& [name, _] : spec.field_rtol)
    if (!fields.find(name))
      throw InputError(fmt::format("/newton/field_rtol/{}: got field \"{}\", which this scene does not have; "
                                   "expected {}",
                                   name, name, known_names("one of its macro fields", name, names)));
}

}  // namespace

std::vector<int> read_region_list(SpecNode& node, const std::string& key, const RunSpec& spec) {
  const json* v = node.declared_value(key);
  if (!v || !v->is_array() || v->empty()) node.fail(key, "a non-empty array of region tags or names");
  std::vector<int> tags;
  for (size_t i = 0; i < v->size(); ++i) {
    const json& r = (*v)[i];
    const std::string where = fmt::format("{}/{}", node.key_path(key), i);
    if (!r.is_string() && !r.is_number_integer())
      throw InputError(fmt::format("{}: got {}, expected a region tag (integer) or name (string)", where, r.dump()));
    const int tag = region_tag(spec, where, r.is_string() ? r.get<std::string>() : r.dump());
    if (std::find(tags.begin(), tags.end(), tag) != tags.end())
      throw InputError(fmt::format("{}: got region {} twice, expected each region once", where, r.dump()));
    tags.push_back(tag);
  }
  std::sort(tags.begin(), tags.end());
  return tags;
}

RunSpec read_run_spec(const json& j, const std::string& file, SpecDoc* doc, bool build_units) {
  RunSpec spec;
  spec.file = file;
  spec.raw = j;
  const std::string dir = std::filesystem::path(file).parent_path().string();
  spec.base_dir = dir.empty() ? std::string(".") : dir;
  SpecNode root(j, "", run_spec_schema(), doc);
  spec.title = root.string("title");
  root.string("description");
  read_mesh(root.child("mesh"), spec);
  // Before the frame: a fibre file per point numbers its points by the quadrature rule.
  read_formulation(root.child("formulation"), spec);
  read_frame(root.child("frame"), spec);
  read_activation_of(root, spec);
  read_newton(root.child("newton"), spec);
  read_models(root.child("models"), root.child("assign"), spec);
  // A unit applies its own Newton update δw with the macro one; a shortened macro step
  // would leave it out of step (LineSearch.h).
  for (const auto& m : spec.models)
    if (spec.line_search.backtracking && m.kind == PointModelSpec::Kind::fe2)
      throw InputError(fmt::format("/newton/line_search: got \"backtracking\", which needs macro-law points only; "
                                   "model '{}' has FE² units (use \"none\")",
                                   m.name));

  read_dirichlet(root, spec);
  read_pressure(root, spec);
  read_time(root.child("time"), spec);
  if (build_units) build_unit_models(spec);  // after the cheap checks above

  read_cavities(root.child("cavities"), spec);
  read_circulation(root, spec);
  spec.fluid = read_fluid(root.child("fluid"), spec);
  if (spec.beats > 0 && !spec.circulation)
    throw InputError(fmt::format("/time/beats: got {}, expected 0 without a /circulation (a beat lasts its period)",
                                 spec.beats));
  add_inflation_steps(spec);

  read_probes(root.child("probes"), spec);
  spec.farm = FarmOptions::from_spec(root.child("farm"));
  spec.farm.check_factor_budget(spec.models, spec.model_of_points());

  read_output(root.child("output"), spec);
  root.finish();
  const std::string canonical = j.dump();
  Fnv1a hash;
  hash.add(canonical.data(), canonical.size());
  spec.hash = hash.value();
  check_field_tolerances(spec);
  return spec;
}

RunSpec read_run_spec_file(const std::string& file, bool build_units) {
  return read_run_spec(read_json_file(file), file, nullptr, build_units);
}

void build_unit_models(RunSpec& spec) {
  for (auto& m : spec.models)
    if (m.plan && !m.micro) m.micro = m.plan->build();
}

}  // namespace fe2
