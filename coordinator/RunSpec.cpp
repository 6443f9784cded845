#include "coordinator/RunSpec.h"

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
#include "common/spec/spec_schemas.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>

namespace fe2 {

double ramp_factor(Ramp ramp, double t, double t_end) {
  return ramp == Ramp::constant ? 1.0 : t / t_end;
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

int RunSpec::model_index_of_tet(int e) const {
  auto it = model_of_region.find(mesh.region[e]);
  return it == model_of_region.end() ? default_model : it->second;
}

std::vector<int> RunSpec::model_of_points() const {
  std::vector<int> m;
  m.reserve(num_points());
  for (int e = 0; e < mesh.num_tets(); ++e) m.insert(m.end(), points_per_element, model_index_of_tet(e));
  return m;
}

namespace {

Vec3 vec3(SpecNode& s, const std::string& key, std::optional<Vec3> def, const std::string& help) {
  std::optional<std::vector<double>> d;
  if (def) d = std::vector<double>{(*def)[0], (*def)[1], (*def)[2]};
  const auto v = s.numbers(key, 3, d, help);
  return Vec3(v[0], v[1], v[2]);
}

Ramp read_ramp(SpecNode& s) {
  return s.choice("ramp", "linear", {"linear", "constant"},
                  "value(t) = value·t/t_end (linear) or value (constant)") == "linear"
             ? Ramp::linear
             : Ramp::constant;
}

int axis_index(const std::string& a) { return a[0] - 'x'; }

void read_mesh(SpecNode m, RunSpec& spec) {
  const std::string kind = m.choice("kind", "box", {"box", "gmsh", "lv"},
                                    "structured box of tetrahedra, a Gmsh 4.1 file, or an idealized left ventricle");
  const auto order = [&] {
    return m.integer("order", 1, Range::closed(1, 2), "element order: 1 (4-node) or 2 (10-node tetrahedra)");
  };
  if (kind == "box") {
    const Vec3 lo = vec3(m, "lo", Vec3::Zero(), "lower corner");
    const Vec3 hi = vec3(m, "hi", std::nullopt, "upper corner");
    const auto div = m.numbers("divisions", 3, std::nullopt, "cells per axis (6 tets per cell)");
    std::array<int, 3> d{};
    for (int i = 0; i < 3; ++i) {
      if (!(div[i] >= 1 && div[i] <= 1000 && div[i] == std::floor(div[i])))
        m.fail("divisions", "three integers in [1, 1000]");
      d[i] = static_cast<int>(div[i]);
    }
    for (int i = 0; i < 3; ++i)
      if (!(hi[i] > lo[i])) m.fail("hi", "a corner above 'lo' in every axis");
    SpecNode slabs = m.child("region_slabs", false,
                             "split the box into equal slabs with region tags 1..count");
    const int axis = axis_index(slabs.choice("axis", "x", {"x", "y", "z"}, "slab normal"));
    const int count = slabs.integer("count", 1, Range::closed(1, 1000), "number of slabs");
    slabs.finish();
    spec.mesh = make_box_mesh(lo, hi, d, count > 1 ? axis : -1, count, order());
    spec.mesh_source = "box generator";
  } else if (kind == "lv") {
    // Truncated prolate ellipsoids; defaults: problem 2 of Land et al. 2015 (mm).
    LvMeshParams p;
    const auto endo = m.numbers("endo", 2, std::vector<double>{7, 17},
                                "endocardial semi-axes [short, long] (long axis along z)");
    const auto epi = m.numbers("epi", 2, std::vector<double>{10, 20}, "epicardial semi-axes [short, long]");
    if (!(endo[0] > 0 && endo[1] > 0)) m.fail("endo", "two semi-axes > 0");
    if (!(epi[0] > endo[0] && epi[1] > endo[1])) m.fail("epi", "semi-axes larger than 'endo' (the epicardium encloses it)");
    p.endo_short = endo[0];
    p.endo_long = endo[1];
    p.epi_short = epi[0];
    p.epi_long = epi[1];
    p.base_z = m.number("base_z", 5.0, Range::any(), "base plane z = base_z; the apex points to -z");
    if (!(std::abs(p.base_z) < p.endo_long)) m.fail("base_z", "a plane cutting the endocardium, |base_z| < endo[1]");
    const auto div = m.numbers("divisions", 3, std::vector<double>{16, 8, 2},
                               "[circumferential, apex-to-base, transmural] divisions (6 tets per cell)");
    for (int i = 0; i < 3; ++i)
      if (!(div[i] >= (i == 0 ? 3 : 1) && div[i] <= 1000 && div[i] == std::floor(div[i])))
        m.fail("divisions", "three integers in [1, 1000], the first (circumferential) >= 3");
    p.circumferential = static_cast<int>(div[0]);
    p.longitudinal = static_cast<int>(div[1]);
    p.transmural = static_cast<int>(div[2]);
    p.order = order();
    spec.mesh = make_lv_mesh(p);
    spec.mesh_source = "LV generator";
  } else {
    std::filesystem::path p = m.string("file", std::nullopt, "Gmsh 4.1 ASCII mesh file");
    if (p.is_relative()) p = std::filesystem::path(spec.base_dir) / p;
    spec.mesh = read_gmsh_tets(p.string());
    spec.mesh_source = p.string();
  }
  m.finish();
}

void read_frame(SpecNode f, RunSpec& spec) {
  // Every kind is read in common/fibres/frame_spec.cpp; a fibre file's tags refer to
  // the Gmsh mesh file (generated meshes: tag = index + 1).
  const bool gmsh = spec.raw.contains("mesh") && spec.raw["mesh"].is_object() &&
                    spec.raw["mesh"].value("kind", std::string("box")) == "gmsh";
  FrameSpec& fr = spec.frame;
  fr.field = read_frame_field_spec(f, spec.mesh, spec.base_dir, gmsh ? spec.mesh_source : "");
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
  fs.mixed = f.choice("kind", "displacement", {"displacement", "mixed"},
                      "displacement only, or a pressure field enforcing J̄ = 1 (mixed)") == "mixed";
  if (f.has("quadrature_degree"))
    fs.quadrature_degree = f.integer("quadrature_degree", std::nullopt, Range::closed(0, 8),
                                     "tet rule degree; one point model per quadrature point "
                                     "(default 2(order − 1): 1 point for linear, 4 for quadratic tets)");
  const int degree = fs.quadrature_degree < 0 ? default_point_degree(spec.mesh.order()) : fs.quadrature_degree;
  spec.points_per_element = static_cast<int>(tet_rule(degree).size());
  if (fs.mixed) {
    if (f.has("bulk_modulus"))
      fs.bulk_modulus = f.number("bulk_modulus", std::nullopt, Range::positive(),
                                 "κ (Pa) of the perturbed Lagrangian J̄ − 1 = −p/κ; absent: a "
                                 "Lagrange multiplier, J̄ = 1 exactly");
    if (f.has("stabilization_modulus"))
      fs.stabilization_modulus =
          f.number("stabilization_modulus", std::nullopt, Range::positive(),
                   "μ_s (Pa) of the pressure-projection stabilization of equal-order P1/P1 "
                   "(required on linear meshes; about the tissue's shear modulus)");
    fs.element_pressure = f.choice("pressure", "P1", {"P1", "P1+P0"},
                                   "pressure space: continuous P1, or P1 enriched by a constant per "
                                   "element (P2/(P1+P0): every element keeps its volume)") == "P1+P0";
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
  spec.newton_max_iterations = n.integer("max_iterations", 20, Range::closed(1, 1000),
                                         "iterations per step before a cutback");
  spec.newton_rtol = n.number("rtol", 1e-8, Range{0.0, 1.0, true, true},
                              "macro residual / max(‖f_int‖, ‖f_ext‖)");
  spec.micro_rtol = n.number("micro_rtol", 1e-8, Range{0.0, 1.0, true, true},
                             "unit residual ‖r‖ / r_ref");
  spec.max_cutbacks = n.integer("max_cutbacks", 4, Range::closed(0, 30),
                                "step halvings before giving up");
  {
    SpecNode m = n.child("macro_solver", false, "when the macro factor is refreshed");
    MacroSolverOptions& o = spec.macro_solver;
    o.refresh = m.choice("refresh", "every_iteration", {"every_iteration", "adaptive"},
                         "every_iteration: factor S̄ at every Newton iteration; adaptive: keep the "
                         "factor as GMRES preconditioner across iterations and steps") == "adaptive"
                    ? MacroSolverOptions::Refresh::adaptive
                    : MacroSolverOptions::Refresh::every_iteration;
    o.gmres_rtol = m.number("gmres_rtol", 1e-12, Range{0.0, 1e-3, true, true},
                            "‖b − S̄x‖ / ‖b‖ GMRES reaches with a kept factor");
    o.max_gmres_iterations = m.integer("max_gmres_iterations", 10, Range::closed(1, 500),
                                       "a solve that needs more refactors for the next one");
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
    SpecNode m = models.child(name, true, "a point model");
    PointModelSpec pm;
    pm.name = name;
    const std::string kind = m.choice("kind", std::nullopt, {"fe2", "macro_law"},
                                      "FE² micro unit per point, or the macro law itself");
    if (kind == "fe2") {
      pm.kind = PointModelSpec::Kind::fe2;
      MicroModelPlan plan = MicroModel::plan(m.child("unit", true, "the micro unit"), spec.base_dir);
      plan.options.newton_rtol = spec.micro_rtol;  // Step 1 never solves below half of it
      pm.plan = std::make_shared<const MicroModelPlan>(std::move(plan));
    } else {
      pm.kind = PointModelSpec::Kind::macro_law;
      SpecNode mat = m.child("material", true, "constitutive law");
      pm.material = make_material(mat);
    }
    m.finish();
    spec.models.push_back(std::move(pm));
  }
  auto index_of = [&](SpecNode& node, const std::string& key, const std::string& name) {
    for (size_t i = 0; i < names.size(); ++i)
      if (names[i] == name) return static_cast<int>(i);
    const std::string guess = closest_match(name, names);
    node.fail(key, "the name of a model in /models" +
                       (guess.empty() ? std::string() : "; did you mean \"" + guess + "\"?"));
  };
  // The default model depends on the spec (its first model), so the key has none.
  const std::string def =
      assign.has("default")
          ? assign.string("default", std::nullopt,
                          "model of every element not in 'regions' (default: the first model)")
          : names.front();
  spec.default_model = index_of(assign, "default", def);
  SpecNode regions = assign.child("regions", false, "region tag -> model name");
  for (auto it = regions.raw().begin(); it != regions.raw().end(); ++it) {
    const std::string tag = it.key();
    const std::string model = regions.string(tag, std::nullopt, "model for this region tag");
    char* end = nullptr;
    const long t = std::strtol(tag.c_str(), &end, 10);
    int found = -1;
    if (end && *end == '\0') found = static_cast<int>(t);
    for (const auto& [rt, rn] : spec.mesh.region_names)
      if (rn == tag) found = rt;
    // A region the mesh lacks would silently leave its intended elements on the default.
    std::set<int> present(spec.mesh.region.begin(), spec.mesh.region.end());
    if (found < 0 || !present.count(found)) {
      std::vector<std::string> known;
      for (int r : present) {
        const auto nm = spec.mesh.region_names.find(r);
        known.push_back(nm == spec.mesh.region_names.end()
                            ? std::to_string(r)
                            : fmt::format("{} (\"{}\")", r, nm->second));
      }
      throw InputError(fmt::format("{}/{}: got region \"{}\", which is not in the mesh {}; "
                                   "expected one of its regions: {}",
                                   regions.path(), tag, tag, spec.mesh_source,
                                   fmt::join(known, ", ")));
    }
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
  const json* v = out.declared_value("units", "array of unit ids",
                                     "FE² units (integration point ids) whose micro fields "
                                     "are written at every output step, into units/");
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

}  // namespace

RunSpec read_run_spec(const json& j, const std::string& file, SpecDoc* doc, bool build_units) {
  RunSpec spec;
  spec.file = file;
  spec.raw = j;
  spec.base_dir = file.empty() ? "." : std::filesystem::path(file).parent_path().string();
  if (spec.base_dir.empty()) spec.base_dir = ".";
  SpecNode root(j, "", doc, &run_spec_schema());
  spec.title = root.string("title", "", "one line saying what this scene solves");
  root.string("description", "", "what the scene shows and how to view it");
  read_mesh(root.child("mesh", true, "macro mesh"), spec);
  read_frame(root.child("frame", false, "material frame (fibre, sheet, normal)"), spec);
  if (root.has("activation")) {
    // An eikonal front follows the fibres: the frame field is built now (and kept, so
    // the macro side does not solve a rule's Laplace problems twice).
    spec.frame.built = make_frame_field(spec.frame.field, spec.mesh);
    const bool gmsh = spec.raw["mesh"].value("kind", std::string("box")) == "gmsh";
    SpecNode activation = root.child(
        "activation", false, "activation time of every material point (when its calcium transient starts)");
    spec.activation = read_activation(activation, spec.mesh, spec.frame.built.get(), spec.base_dir,
                                      gmsh ? spec.mesh_source : "");
  }
  read_formulation(root.child("formulation", false, "macro discretization: displacement only, or "
                                                    "mixed displacement–pressure"),
                   spec);
  read_newton(root.child("newton", false, "Newton–Raphson"), spec);
  read_models(root.child("models", true, "point models by name"),
              root.child("assign", false, "which model each element uses"), spec);

  for (auto& d : root.children("dirichlet", true, "prescribed displacements on node sets")) {
    DirichletSpec ds;
    ds.set = d.string("set", std::nullopt, "named node set or face");
    if (!spec.mesh.node_sets.count(ds.set)) {
      std::vector<std::string> known;
      for (const auto& [n, _] : spec.mesh.node_sets) known.push_back(n);
      const std::string guess = closest_match(ds.set, known);
      d.fail("set", "a node set of the mesh (" + fmt::format("{}", fmt::join(known, ", ")) + ")" +
                        (guess.empty() ? "" : "; did you mean \"" + guess + "\"?"));
    }
    const auto comps = d.numbers("components", -1, std::vector<double>{0, 1, 2},
                                 "constrained components: any of 0 (x), 1 (y), 2 (z)");
    ds.fixed = {false, false, false};
    for (double c : comps) {
      if (!(c == 0 || c == 1 || c == 2)) d.fail("components", "components among 0, 1, 2");
      ds.fixed[static_cast<int>(c)] = true;
    }
    ds.value = vec3(d, "value", Vec3::Zero(), "prescribed displacement at t_end");
    ds.ramp = read_ramp(d);
    d.finish();
    spec.dirichlet.push_back(ds);
  }
  if (spec.dirichlet.empty())
    throw InputError("/dirichlet: got nothing, expected at least one Dirichlet condition "
                     "(a free body has no unique quasi-static solution)");
  for (auto& p : root.children("pressure", false, "follower pressure on named surfaces")) {
    PressureSpec ps;
    ps.surface = p.string("surface", std::nullopt, "named boundary surface");
    if (!spec.mesh.faces.count(ps.surface)) {
      std::vector<std::string> known;
      for (const auto& [n, _] : spec.mesh.faces) known.push_back(n);
      p.fail("surface", "a named surface of the mesh (" + fmt::format("{}", fmt::join(known, ", ")) + ")");
    }
    ps.value = p.number("value", std::nullopt, Range::any(), "pressure at t_end (Pa)");
    ps.ramp = read_ramp(p);
    p.finish();
    spec.pressure.push_back(ps);
  }

  SpecNode t = root.child("time", false, "time stepping");
  spec.t_end = t.number("t_end", 1.0, Range::positive(), "end time");
  spec.steps = t.integer("steps", 1, Range::closed(1, 1e7), "number of steps");
  spec.dynamic = t.choice("scheme", "quasi_static", {"quasi_static", "newmark"},
                          "quasi-static load stepping or Newmark-β dynamics") == "newmark";
  spec.beta = t.number("beta", 0.25, Range{0.0, 0.5, true, false}, "Newmark β");
  spec.gamma = t.number("gamma", 0.5, Range::closed(0.0, 1.0), "Newmark γ");
  spec.density = t.number("density", 1000.0, Range::positive(), "mass density (Newmark)");
  spec.beats = t.integer("beats", 0, Range::closed(0, 10000),
                         "heart beats to run (t_end = beats x circulation period); 0: t_end and steps");
  spec.steps_per_beat = t.integer("steps_per_beat", 100, Range::closed(1, 1e7), "steps per beat (with beats)");
  spec.periodic_tolerance =
      t.number("periodic_tolerance", 0.0, Range::non_negative(),
               "stop before the last beat once every cavity's EDV changed by less than this (relative) over a beat; 0: run every beat");
  if (spec.beats > 0 && (t.has("t_end") || t.has("steps")))
    t.fail("beats", "either beats (with steps_per_beat) or t_end and steps, not both");
  t.finish();

  if (build_units) build_unit_models(spec);  // after the cheap checks above

  SpecNode cavities = root.child("cavities", false, "cavities whose deformed volume is reported every step");
  for (auto it = cavities.raw().begin(); it != cavities.raw().end(); ++it) {
    SpecNode c = cavities.child(it.key(), true, "a cavity");
    const std::string surface =
        c.string("surface", std::nullopt,
                 "the named face that bounds it (endocardium, normals out of the solid); the open "
                 "base is closed by a fan from its rim's centroid");
    if (!spec.mesh.faces.count(surface)) {
      std::vector<std::string> known;
      for (const auto& [n, _] : spec.mesh.faces) known.push_back(n);
      c.fail("surface", "a named surface of the mesh (" + fmt::format("{}", fmt::join(known, ", ")) + ")");
    }
    c.finish();
    spec.cavities.emplace_back(it.key(), surface);
  }
  cavities.finish();

  if (root.has("circulation")) {
    SpecNode circ = root.child("circulation", false,
                               "0D circulation coupled strongly to the cavities (their pressures become unknowns)");
    spec.circulation = make_circulation(circ);
    for (const std::string& name : spec.circulation->cavity_names()) {
      int found = -1;
      for (size_t c = 0; c < spec.cavities.size(); ++c)
        if (spec.cavities[c].first == name) found = static_cast<int>(c);
      if (found < 0) {
        std::vector<std::string> known;
        for (const auto& [n, _] : spec.cavities) known.push_back(n);
        throw InputError(fmt::format(
            "/circulation/cavities/{}: no cavity '{}' in /cavities (it has: {}); every cavity of the "
            "circulation needs its bounding surface there",
            name, name, known.empty() ? std::string("none") : fmt::format("{}", fmt::join(known, ", "))));
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

  if (spec.beats > 0 && !spec.circulation)
    throw InputError(fmt::format("/time/beats: got {}, expected 0 without a /circulation (a beat lasts its period)",
                                 spec.beats));

  SpecNode probes = root.child("probes", false, "named material points to report");
  for (auto it = probes.raw().begin(); it != probes.raw().end(); ++it) {
    const std::string name = it.key();
    const Vec3 X = vec3(probes, name, std::nullopt, "reference position");
    try {
      locate_point(spec.mesh, X);
    } catch (const InputError&) {
      probes.fail(name, "a point inside the mesh");
    }
    spec.probes.emplace_back(name, X);
  }
  probes.finish();

  spec.farm = FarmOptions::from_spec(root.child("farm", false, "MPI task farm (ranks, scheduling)"));
  spec.farm.check_factor_budget(spec.models, spec.model_of_points());

  SpecNode out = root.child("output", false, "results");
  spec.output_every = out.integer("every", 1, Range::closed(1, 1e7), "write every k-th step");
  spec.write_vtu = out.boolean("vtu", true, "write VTU/PVD for ParaView");
  spec.output_units = read_output_units(out, spec);
  spec.checkpoint_every = out.integer("checkpoint_every", 0, Range::closed(0, 1e7),
                                      "write a checkpoint (checkpoint.bin) every k-th step; 0: only on "
                                      "SIGTERM/SIGUSR1");
  spec.checkpoint_factors = out.boolean("checkpoint_factors", false,
                                        "store each FE² unit's numeric factor in the checkpoint");
  out.finish();
  root.finish();
  const std::string canonical = j.dump();
  Fnv1a hash;
  hash.add(canonical.data(), canonical.size());
  spec.hash = hash.value();
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
