// Every key of a run spec and of a unit spec, declared once: the readers name a key and
// take its type, default, range and help from here (SpecNode.h); reading a key not
// declared here, or as another type, is an internal error. Tests read every config and
// the exemplars in tests/data/schema/ and require every key here to be read by some spec.
#include "common/spec/spec_schemas.h"

#include "common/activation/activation_schema.h"
#include "common/cellmodels/cell_model_schema.h"
#include "common/circulation/circulation_schema.h"
#include "common/fluid/fluid_schema.h"
#include "common/materials/material_factory.h"

#include <limits>

namespace fe2 {

namespace {

using namespace schema;
using std::nullopt;

const Range kOpenUnit{0.0, 1.0, true, true};  // (0, 1): tolerances, fractions

// Fresh nodes per branch, so the coverage test sees each branch's keys read.
SchemaKeys isotropic_keys() {
  // −1 < ν < ½ is where the small-strain tensor is positive definite.
  return {{"E", number(nullopt, Range::positive(), "Young's modulus (Pa)")},
          {"nu", number(nullopt, Range{-1.0, 0.5, true, true}, "Poisson's ratio")}};
}

/// "volumetric" and "kappa" of the laws in the material frame (volumetric.h).
SchemaKeys volumetric_keys(double default_kappa) {
  return {{"volumetric", choice("penalty", {"penalty", "none"},
                                "volumetric energy: penalty U = kappa/2 (J-1)^2, or none (a "
                                "mixed formulation's pressure enforces J = 1)")},
          {"kappa", number(default_kappa, Range::positive(),
                           "volumetric penalty kappa (Pa), U = kappa/2 (J-1)^2")}};
}

SchemaKeys guccione_keys() {
  SchemaKeys k = {{"C", number(880.0, Range::positive(), "stiffness scale C (Pa)")},
                  {"bf", number(18.5, Range::positive(), "fibre exponent b_f")},
                  {"bt", number(3.58, Range::positive(), "transverse exponent b_t")},
                  {"bfs", number(1.63, Range::positive(), "fibre-shear exponent b_fs")}};
  for (auto& v : volumetric_keys(1.0e5)) k.push_back(std::move(v));
  return k;
}

/// Holzapfel & Ogden 2009 Table 1 defaults (common/materials/HolzapfelOgden.h).
SchemaKeys holzapfel_ogden_keys() {
  const Range positive = Range::positive(), non_negative = Range::non_negative();
  SchemaKeys k = {
      {"a", number(59.0, positive, "isotropic modulus a (Pa)")},
      {"b", number(8.023, positive, "isotropic exponent b")},
      {"af", number(18472.0, non_negative, "fibre modulus a_f (Pa), acts in fibre tension only")},
      {"bf", number(16.026, positive, "fibre exponent b_f")},
      {"as", number(2481.0, non_negative, "sheet modulus a_s (Pa), acts in sheet tension only")},
      {"bs", number(11.12, positive, "sheet exponent b_s")},
      {"afs", number(216.0, non_negative, "fibre-sheet coupling modulus a_fs (Pa)")},
      {"bfs", number(11.436, positive, "fibre-sheet coupling exponent b_fs")},
      {"isotropic", choice("isochoric", {"isochoric", "full"},
                           "invariant of the isotropic term: isochoric J^(-2/3) I1 (stress-free "
                           "reference) or full I1 (reference stress a I, for a mixed "
                           "formulation)")}};
  for (auto& v : volumetric_keys(1.0e5)) k.push_back(std::move(v));
  return k;
}

/// common/materials/material_factory.cpp
Schema material() {
  static const Schema s = defined(
      "material",
      object(true, "constitutive law",
             {{"model", choice(nullopt,
                               {"neo_hookean", "st_venant_kirchhoff", "guccione", "holzapfel_ogden"},
                               "constitutive law")},
              {"active", cell_model_schema()},
              {"viscosity", number(0.0, Range::non_negative(), kViscosityHelp)}},
             "model",
             {{"neo_hookean", isotropic_keys()},
              {"st_venant_kirchhoff", isotropic_keys()},
              {"guccione", guccione_keys()},
              {"holzapfel_ogden", holzapfel_ogden_keys()}}));
  return s;
}

Schema cell_size() {
  return numbers(3, std::vector<double>{1.0, 0.25, 0.25}, "cell edge lengths L1 (fibre), L2, L3",
                 Range::positive());
}

Schema cell_resolution() {
  return integers(3, std::vector<double>{8, 4, 4}, Range::closed(1, 1000), "hexahedra per axis");
}

/// Materials of a built-in cell layout: one per named region.
Schema region_materials(const std::vector<std::string>& regions) {
  SchemaKeys keys;
  for (const auto& r : regions) keys.emplace_back(r, material());
  return object(true, "one material per region, by region name", std::move(keys));
}

/// worker/MicroModel.cpp (MicroModel::from_spec, MicroSolverOptions::from_spec)
Schema micro_unit() {
  static const Schema s = defined(
      "unit",
      object(
          true, "the micro unit",
          {{"cell", choice("two_cells", {"two_cells", "homogeneous", "laminate", "mesh_file"},
                           "cell geometry: built-in layouts or a Gmsh hex mesh")},
           {"solver",
            object(false, "micro solver",
                   {{"factorization",
                     choice("auto", {"cholesky", "lu", "auto"},
                            "factor of K: CHOLMOD LLᵀ, UMFPACK LU, or LLᵀ while K is symmetric "
                            "positive definite and LU otherwise")},
                    {"refresh",
                     choice("collective", {"every_iteration", "fixed", "adaptive", "collective"},
                            "when to refactor K and recompute χ: every Newton iteration; at "
                            "iteration 1 of every N_t-th step (paper Fig. 6); when the extra "
                            "GMRES work since the last refresh has cost as much as a refresh "
                            "(adaptive: each unit alone; collective: the coordinators, for all "
                            "units of this model at once)")},
                    {"N_t", integer(10, Range::closed(1, 1e6),
                                    "refresh period in steps (fixed policy)")},
                    {"step4", boolean(true, "apply Eq. (11) δw = δw₁ − χ ΔZ̄ when Z̄ moves")},
                    {"gmres_rtol", number(1e-10, kOpenUnit, "Step 1 relative residual tolerance")},
                    {"gmres_forcing",
                     choice("residual", {"constant", "residual"},
                            "Step 1 tolerance over a Newton solve: gmres_rtol every iteration, or "
                            "the inexact-Newton forcing η = ‖r‖/r_ref between gmres_rtol and "
                            "gmres_forcing_max")},
                    {"gmres_forcing_max",
                     number(1e-4, kOpenUnit, "loosest Step 1 tolerance of the residual forcing (default "
                                  "1e-4, or gmres_rtol if that is larger)")},
                    {"gmres_restart", integer(50, Range::closed(1, 1000), "GMRES restart length")},
                    {"gmres_max_iterations",
                     integer(500, Range::closed(1, 1e6), "GMRES iteration cap")},
                    {"solve_flop_cost",
                     number(4.0, Range::closed(1.0, 100.0),
                            "what a flop of a solve costs in flops of a factorization (BLAS-3 runs "
                            "faster per flop): adaptive and collective let a stale Step 1 spend "
                            "refresh flops / (this × flops of one GMRES iteration) iterations "
                            "before the unit refreshes within the job. `fe2heart bench unit` "
                            "measures it: (factor_solve_ms / solve Gflop) / (factorize ms / factor_Gflop)")},
                    {"precision",
                     choice("double", {"double", "single", "half"},
                            "precision of the factor of K (the GMRES preconditioner): double "
                            "(CHOLMOD/UMFPACK), single (half the memory) or half (the single "
                            "LLᵀ kept in IEEE binary16: a quarter); residuals and answer stay "
                            "double")},
                    {"single_factor",
                     choice("supernodal", {"supernodal", "mumps"},
                            "single-precision factor: supernodal LLᵀ on CHOLMOD's analysis (the "
                            "LLᵀ kind; LU is always MUMPS) or MUMPS (LDLᵀ/LU, optionally block "
                            "low-rank)")},
                    {"blr_tolerance",
                     number(0.0, Range{0.0, 1.0, false, true},
                            "block low-rank threshold of the single-precision MUMPS factor "
                            "(CNTL(7)); 0 = full rank")}})}},
          "cell",
          {{"two_cells",
            {{"size", cell_size()},
             {"resolution", cell_resolution()},
             {"gap", number(0.1, Range{0.0, 0.5, false, true},
                            "ECM gap per cell, as a fraction of L1 (0: the cells join end to end)")},
             {"cross_section", number(0.75, kOpenUnit, "cell width as a fraction of L2 and L3")},
             {"materials", region_materials({"ecm", "cell"})}}},
           {"homogeneous",
            {{"size", cell_size()},
             {"resolution", cell_resolution()},
             {"materials", region_materials({"matrix"})}}},
           {"laminate",
            {{"size", cell_size()},
             {"resolution", cell_resolution()},
             {"fraction", number(0.5, kOpenUnit, "volume fraction of phase a")},
             {"axis", choice("x", {"x", "y", "z"}, "layer normal")},
             {"materials", region_materials({"a", "b"})}}},
           {"mesh_file",
            {{"mesh_file", string(nullopt, "Gmsh 4.1 hex mesh of the cell")},
             {"materials", map(true, "one material per region, by physical volume name",
                               "region", material(), 1)}}}}));
  return s;
}

// The fixed axes of the constant and rotating frames.
std::pair<std::string, Schema> frame_fibre() {
  return {"fibre", schema::numbers(3, std::vector<double>{1, 0, 0}, "fibre direction f (unit axis 1)")};
}
std::pair<std::string, Schema> frame_sheet() {
  return {"sheet", schema::numbers(3, std::vector<double>{0, 1, 0}, "sheet direction s (unit axis 2)")};
}

Schema ramp() { return ramp_schema(); }

Schema mesh_order() {
  return integer(1, Range::closed(1, 2), "element order: 1 (4-node) or 2 (10-node tetrahedra)");
}

/// coordinator/RunSpec.cpp
Schema make_run_spec_schema() {
  const Range any = Range::any();
  return object(
      true, "a run spec (fe2heart run, validate)",
      {{"title", string("", "one line saying what this scene solves")},
       {"description", string("", "what the scene shows and how to view it")},
       {"mesh",
        object(true, "macro mesh",
               {{"kind", choice("box", {"box", "gmsh", "lv"},
                                "structured box of tetrahedra, a Gmsh 4.1 file, or an idealized left ventricle")},
                {"wall_regions",
                 optional(custom("array of region tags or names",
                                 "the regions of the solid wall: only their elements carry the displacement, "
                                 "the pressure and the point models (FE² units); the others are left to the "
                                 "fields that live there (default: every region)",
                                 {{"type", "array"},
                                  {"items", {{"type", {"string", "integer"}}}},
                                  {"minItems", 1}}))}},
               "kind",
               {{"box",
                 {{"lo", numbers(3, std::vector<double>{0, 0, 0}, "lower corner")},
                  {"hi", numbers(3, nullopt, "upper corner")},
                  {"divisions", integers(3, nullopt, Range::closed(1, 1000),
                                         "cells per axis (6 tets per cell)")},
                  {"region_slabs",
                   object(false, "split the box into equal slabs with region tags 1..count",
                          {{"axis", choice("x", {"x", "y", "z"}, "slab normal")},
                           {"count", integer(1, Range::closed(1, 1000), "number of slabs")}})},
                  {"order", mesh_order()}}},
                {"gmsh", {{"file", string(nullopt, "Gmsh 4.1 ASCII mesh file")}}},
                {"lv",
                 {{"endo", numbers(2, std::vector<double>{7, 17},
                                   "endocardial semi-axes [short, long] (long axis along z)")},
                  {"epi", numbers(2, std::vector<double>{10, 20}, "epicardial semi-axes [short, long]")},
                  {"base_z", number(5.0, any, "base plane z = base_z; the apex points to -z")},
                  {"divisions", integers(3, std::vector<double>{16, 8, 2}, Range::closed(1, 1000),
                                         "[circumferential, apex-to-base, transmural] divisions (6 tets per cell)")},
                  {"order", mesh_order()},
                  {"cavity",
                   object(false,
                          "mesh the cavity too (blood): regions 'myocardium' (1) and 'blood' (2) sharing the "
                          "endocardium's nodes, 'endo' their interface, the cavity's base 'base_cap'",
                          {{"layers", integer(nullopt, Range::closed(1, 1000),
                                              "layers of cells from the long axis to the endocardium")},
                           {"rings", map(false,
                                         "discs of the cavity's base cap, each its own face set (valve rings: "
                                         "the cap's triangles whose centroid is in the disc)",
                                         "name",
                                         object(true, "a disc in the base plane",
                                                {{"center", numbers(2, nullopt, "centre [x, y] in the base plane")},
                                                 {"radius", number(nullopt, Range::positive(), "radius")}}))}})}}}})},
       {"frame",
        object(false, "material frame (fibre, sheet, normal)",
               {{"kind", choice("constant", {"constant", "rotating", "file", "rule"}, "fibre frame rule")}},
               "kind",
               {{"constant", {frame_fibre(), frame_sheet()}},
                {"rotating",
                 {frame_fibre(), frame_sheet(),
                  {"axis", numbers(3, std::vector<double>{0, 0, 1}, "rotation axis of the fibres")},
                  {"coordinate", numbers(3, std::vector<double>{0, 1, 0},
                                         "direction along which the angle varies (transmural)")},
                  {"from", numbers(2, nullopt, "[coordinate, angle in degrees]")},
                  {"to", numbers(2, nullopt, "[coordinate, angle in degrees]")}}},
                {"file",
                 {{"file", string(nullopt, "fibre file: Gmsh MSH 4.1 views or CSV")},
                  {"format", choice("gmsh", {"gmsh", "csv"},
                                    "gmsh: $ElementData/$NodeData views; csv: lines tag,fx,fy,fz,sx,sy,sz "
                                    "(per point: tag,point,fx,fy,fz,sx,sy,sz)")},
                  {"per", choice("element", {"element", "node", "point"},
                                 "one fibre and sheet per element; per node (interpolated as rotations); or per "
                                 "integration point (csv only), keyed by element tag and the point's 0-based index "
                                 "in the tet rule of formulation.quadrature_degree")},
                  {"fibre_view", string("fibre", "name of the Gmsh view of fibre vectors")},
                  {"sheet_view", string("sheet", "name of the Gmsh view of sheet vectors")}}},
                {"rule",
                 {{"alpha_endo", number(60.0, Range::closed(-180, 180), "helix angle on the endocardium (degrees)")},
                  {"alpha_epi", number(-60.0, Range::closed(-180, 180), "helix angle on the epicardium (degrees)")},
                  {"beta_endo", number(0.0, Range::closed(-180, 180), "sheet angle on the endocardium (degrees)")},
                  {"beta_epi", number(0.0, Range::closed(-180, 180), "sheet angle on the epicardium (degrees)")},
                  {"endo", string("endo", "named surface of the (LV) endocardium: φ = 0")},
                  {"epi", string("epi", "named surface of the epicardium: φ = 1")},
                  {"base", string("base", "named surface of the base: ψ = 1")},
                  {"apex", string("", "named node set of the apex: ψ = 0 (\"\": the epi node farthest from the base)")},
                  {"rv_endo", string("", "named surface of the RV endocardium (biventricular); \"\": LV only")}}}})},
       {"models",
        map(true, "point models by name", "name",
            object(true, "a point model",
                   {{"kind", choice(nullopt, {"fe2", "macro_law"},
                                    "FE² micro unit per point, or the macro law itself")}},
                   "kind",
                   {{"fe2", {{"unit", micro_unit()}}}, {"macro_law", {{"material", material()}}}}),
            1)},
       {"assign",
        object(false, "which model each element uses",
               {{"default", optional(string(nullopt, "model of every element not in 'regions' "
                                                     "(default: the first model)"))},
                {"regions", map(false, "region tag or physical volume name -> model name",
                                "region", string(nullopt, "model for this region"))}})},
       {"dirichlet",
        array(true, "prescribed displacements on node sets",
              object(true, "a Dirichlet condition",
                     {{"set", string(nullopt, "named node set or face")},
                      {"components",
                       integers(-1, std::vector<double>{0, 1, 2}, Range::closed(0, 2),
                                "constrained components: any of 0 (x), 1 (y), 2 (z)")},
                      {"value", numbers(3, std::vector<double>{0, 0, 0},
                                        "prescribed displacement at t_end")},
                      {"ramp", ramp()}}),
              1)},
       {"pressure",
        array(false, "follower pressure on named surfaces",
              object(true, "a follower pressure",
                     {{"surface", string(nullopt, "named boundary surface")},
                      {"value", number(nullopt, any, "pressure at t_end (Pa)")},
                      {"ramp", ramp()}}))},
       {"activation", activation_schema()},
       {"formulation",
        object(false, "macro discretization: displacement only, or mixed displacement–pressure",
               {{"kind", choice("displacement", {"displacement", "mixed"},
                                "displacement only, or a pressure field enforcing J̄ = 1 (mixed)")},
                {"quadrature_degree",
                 optional(integer(nullopt, Range::closed(0, 8),
                                  "tet rule degree; one point model per quadrature point "
                                  "(default 2(order − 1): 1 point for linear, 4 for quadratic tets)"))}},
               "kind",
               {{"displacement", {}},
                {"mixed",
                 {{"bulk_modulus",
                   optional(number(nullopt, Range::positive(),
                                   "κ (Pa) of the perturbed Lagrangian J̄ − 1 = −p/κ; absent: a "
                                   "Lagrange multiplier, J̄ = 1 exactly"))},
                  {"pressure", choice("P1", {"P1", "P1+P0"},
                                      "pressure space: continuous P1, or P1 enriched by a constant per "
                                      "element (P2/(P1+P0): every element keeps its volume)")},
                  {"stabilization_modulus",
                   optional(number(nullopt, Range::positive(),
                                   "μ_s (Pa) of the pressure-projection stabilization of equal-order "
                                   "P1/P1 (required on linear meshes; about the tissue's shear "
                                   "modulus)"))}}}})},
       {"time",
        object(false, "time stepping",
               {{"t_end", number(1.0, Range::positive(), "end time")},
                {"steps", integer(1, Range::closed(1, 1e7), "number of steps")},
                {"scheme", choice("quasi_static", {"quasi_static", "newmark"},
                                  "quasi-static load stepping or Newmark-β dynamics")},
                {"beta", number(0.25, Range{0.0, 0.5, true, false}, "Newmark β")},
                {"gamma", number(0.5, Range::closed(0.0, 1.0), "Newmark γ")},
                {"density", number(1000.0, Range::positive(), "mass density (Newmark)")},
                {"beats", integer(0, Range::closed(0, 10000),
                                  "heart beats to run (t_end = beats x circulation period); 0: t_end and steps")},
                {"steps_per_beat", integer(100, Range::closed(1, 1e7), "steps per beat (with beats)")},
                {"periodic_tolerance",
                 number(0.0, Range::non_negative(),
                        "stop before the last beat once every cavity's EDV changed by less than this (relative) over a beat; 0: run every beat")},
                {"inflation_steps",
                 integer(0, Range::closed(0, 1e5),
                         "steps of the beat's size before t = 0 that inflate the resting wall to the circulation's "
                         "filling pressure (each cavity's pressure ramped to the one upstream of its inflow valve), "
                         "so the first beat starts at end-diastole; needs a circulation; 0: the beat starts from "
                         "the unloaded wall")},
                {"adaptive",
                 boolean(false, "sub-steps sized by Newton's behaviour between the output times t_end·k/steps: "
                                "x1.5 after a sub-step within target_iterations, smaller after a slower one, "
                                "halved on failure down to min_dt, carried from step to step (false: each step "
                                "whole, halved on failure up to newton.max_cutbacks times)")},
                {"target_iterations",
                 integer(8, Range::closed(1, 1000), "adaptive: Newton iterations a sub-step should take")},
                {"max_dt", optional(number(nullopt, Range::positive(),
                                           "adaptive: largest sub-step (default t_end/steps)"))},
                {"min_dt", optional(number(nullopt, Range::positive(),
                                           "adaptive: a run whose failed sub-step would be halved below this "
                                           "stops (default t_end/steps/1024)"))}})},
       {"newton",
        object(false, "Newton–Raphson",
               {{"max_iterations", integer(20, Range::closed(1, 1000),
                                           "iterations per step before a cutback")},
                {"rtol", number(1e-8, kOpenUnit, "macro residual / max(‖f_int‖, ‖f_ext‖)")},
                {"field_rtol",
                 map(false,
                     "a tolerance per macro field (displacement, pressure, cavity_pressure), on the "
                     "norm summary.json logs for it; a field not named here takes rtol",
                     "field", number(nullopt, kOpenUnit, "the field's residual norm to reach"))},
                {"micro_rtol", number(1e-8, kOpenUnit, "unit residual ‖r‖ / r_ref")},
                {"max_cutbacks", integer(4, Range::closed(0, 30),
                                         "step halvings before giving up (fixed steps; time.adaptive stops at time.min_dt)")},
                {"line_search",
                 choice("none", {"none", "backtracking"},
                        "none: the full Newton correction; backtracking: Armijo backtracking on the "
                        "residual (merit: the largest field residual over its tolerance), which shortens a "
                        "correction that raises it or inverts an element")},
                {"line_search_min_step", number(1.0 / 64, Range{0.0, 1.0, true, false},
                                                "backtracking: the shortest fraction of a correction tried "
                                                "before the iteration takes it anyway")},
                {"macro_solver",
                 object(false, "when the macro factor is refreshed",
                        {{"refresh", choice("every_iteration", {"every_iteration", "adaptive"},
                                            "every_iteration: factor S̄ at every Newton iteration; adaptive: keep the "
                                            "factor as GMRES preconditioner across iterations and steps")},
                         {"gmres_rtol", number(1e-12, Range{0.0, 1e-3, true, true},
                                               "‖b − S̄x‖ / ‖b‖ GMRES reaches with a kept factor (with "
                                               "gmres_forcing eisenstat_walker: the floor of η_k)")},
                         {"gmres_forcing", choice("constant", {"constant", "eisenstat_walker"},
                                            "how far GMRES with a kept factor solves: constant, to gmres_rtol; "
                                            "eisenstat_walker, to the inexact-Newton forcing term η_k = "
                                            "0.9(‖R̃_k‖/‖R̃_k−1‖)², safeguarded, in [gmres_rtol, 0.1] "
                                            "(loose far from the solution, tight near it)")},
                         {"max_gmres_iterations", integer(10, Range::closed(1, 500),
                                                          "a solve that needs more refactors for the next one")},
                         {"ordering", choice("metis", {"metis", "mumps"},
                                             "fill-reducing ordering of S̄'s factor: metis, METIS's nested "
                                             "dissection passed to MUMPS as the user's order; mumps, MUMPS's "
                                             "own automatic choice among the orderings its build has "
                                             "(Debian's: PORD, AMD, AMF, QAMD)")}})}})},
       {"circulation", circulation_schema()},
       {"fluid", fluid_schema()},
       {"cavities",
        map(false, "cavities whose deformed volume is reported every step", "name",
            object(true, "a cavity",
                   {{"surface", string(nullopt, "the named face that bounds it (endocardium, "
                                                "normals out of the solid); the open base is "
                                                "closed by a fan from its rim's centroid")}}))},
       {"probes", map(false, "named material points to report", "name",
                      numbers(3, nullopt, "reference position"))},
       {"farm",
        object(false, "MPI task farm (ranks, scheduling)",
               {{"coordinators", integer(1, Range::closed(1, 1e6),
                                         "ranks that own the macro problem (or --coordinators)")},
                {"coordinators_work",
                 boolean(true, "coordinator ranks also hold units (paper ranks 0–63)")},
                {"policy", choice("cost_based", {"round_robin", "contiguous", "cost_based"},
                                  "unit placement: static, or rebalanced by measured cost")},
                {"rebalance_at", choice("iteration", {"iteration", "step"},
                                        "when the cost-based policy may migrate units")},
                {"batch", integer(4, Range::closed(1, 1e6), "jobs a worker pulls at once, per thread")},
                {"threads_per_rank",
                 integer(1, Range::closed(1, 256),
                         "threads that run a rank's unit jobs: 1, the rank's main thread between "
                         "its messages; more, that many threads while the main thread only talks "
                         "MPI. The answer is bit for bit that of one thread; set "
                         "OPENBLAS_NUM_THREADS=1")},
                {"min_gain", number(0.03, Range::closed(0.0, 1.0),
                                    "least relative makespan gain worth a migration")},
                {"tolerated_imbalance",
                 number(0.05, Range::closed(0.0, 10.0),
                        "no rebalance while predicted max/mean load <= 1 + this")},
                {"latency", number(2e-6, Range::non_negative(), "network model: seconds per message")},
                {"bandwidth", number(5e9, Range::positive(), "network model: bytes per second")},
                {"stall_timeout",
                 number(600.0, Range::positive(),
                        "liveness limit, wall seconds: a rank that waits this long for a message "
                        "stops the job naming the silent rank; must exceed the longest wait of a "
                        "healthy run: one Newton iteration (micro phase and macro solve) plus an "
                        "output write")},
                {"factor_memory_budget",
                 custom("bytes: a number > 0 or a size such as \"2G\", \"500M\"",
                        "sparse factors a worker rank may hold; past it the least recently used "
                        "factors of other units are dropped and rebuilt on their next job "
                        "(counted in summary.factor_memory); default: unlimited",
                        {{"anyOf",
                          {{{"type", "number"}, {"exclusiveMinimum", 0}},
                           {{"type", "string"},
                            {"pattern", "^[0-9]*[.]?[0-9]+([eE][+-]?[0-9]+)?[kKMGT]?$"}}}}})},
                {"macro_law_points",
                 choice("local", {"local", "farm"},
                        "where macro-law points are evaluated: local (by the coordinator that "
                        "owns their element, no messages) or farm (as jobs on the workers, like "
                        "FE² units)")}})},
       {"output",
        object(false, "results",
               {{"every", integer(1, Range::closed(1, 1e7), "write every k-th step")},
                {"vtu", boolean(true, "write VTU/PVD for ParaView")},
                {"checkpoint_every", integer(0, Range::closed(0, 1e7),
                                             "write a checkpoint (checkpoint.bin) every k-th step; 0: only "
                                             "on SIGTERM/SIGUSR1")},
                {"checkpoint_factors",
                 boolean(false, "store each FE² unit's numeric factor in the checkpoint, so that a "
                                "restart does not refactor (CHOLMOD LLᵀ units; UMFPACK LU, MUMPS "
                                "and dropped factors are rebuilt from their matrix as without it); "
                                "the checkpoint grows by the factors' size")},
                {"units", custom("array of unit ids",
                                 "FE² units (integration point ids) whose micro fields are "
                                 "written at every output step, into units/",
                                 {{"type", "array"},
                                  {"items", {{"type", "integer"}, {"minimum", 0}}},
                                  {"uniqueItems", true}})}})}});
}

/// tools/unit_spec.cpp
Schema make_unit_spec_schema() {
  const json nine = {{"type", "array"},
                     {"items", {{"type", "number"}}},
                     {"minItems", 9},
                     {"maxItems", 9}};
  return exactly_one_of(
      {"Zbar", "Zbar_path"},
      object(true, "a unit spec (fe2heart unit)",
             {{"title", string("", "what this unit exploration shows")},
              {"description", string("", "longer notes")},
              {"unit", micro_unit()},
              {"Zbar", optional(numbers(9, nullopt, "macro displacement gradient, column-major"))},
              {"Zbar_path", custom("array of 9-number arrays",
                                   "macro gradients to equilibrate in turn",
                                   {{"type", "array"}, {"minItems", 1}, {"items", nine}})},
              {"newton",
               object(false, "unit Newton iterations",
                      {{"rtol", number(1e-10, kOpenUnit, "‖r‖ / r_ref to reach")},
                       {"max_iterations", integer(30, Range::closed(1, 1000), "iteration cap")}})}}));
}

}  // namespace

Schema ramp_schema() {
  return choice("linear", {"linear", "constant"}, "value(t) = value·t/t_end (linear) or value (constant)");
}

const SchemaNode& run_spec_schema() {
  static const Schema s = make_run_spec_schema();
  return *s;
}

const SchemaNode& unit_spec_schema() {
  static const Schema s = make_unit_spec_schema();
  return *s;
}

const SchemaNode& material_schema() { return *material(); }

const SchemaNode& micro_unit_schema() { return *micro_unit(); }

}  // namespace fe2
