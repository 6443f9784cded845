#include "common/fluid/fluid_schema.h"

#include "common/spec/spec_schemas.h"

namespace fe2 {

using namespace schema;
using std::nullopt;

namespace {

Schema set_key(const char* what) { return string(nullopt, what); }

Schema components() {
  return integers(-1, std::vector<double>{0, 1, 2}, Range::closed(0, 2),
                  "prescribed components: any of 0 (x), 1 (y), 2 (z); the others are free (a slip plane "
                  "prescribes only its normal one)");
}

Schema boundary() {
  return object(
      true, "a boundary condition of the fluid on a node set (velocities) or face set (pressure, flux)",
      {{"kind", choice(nullopt, {"no_slip", "velocity", "moving_wall", "pressure", "traction", "flux", "valve"},
                       "no_slip: v = 0; velocity: v prescribed; moving_wall: v = the mesh velocity (no-slip "
                       "on a wall the mesh follows; needs mesh_motion); pressure: traction −P n on an open "
                       "boundary; traction: a force per area t on a face; flux: ∫(v − v̂)·n da = Q, its multiplier the face's pressure; valve: a "
                       "flux face whose Q is the circulation's flow through a cavity's valve")}},
      "kind",
      {{"no_slip", {{"set", set_key("named node set (or face)")}, {"components", components()}}},
       {"velocity",
        {{"set", set_key("named node set (or face)")},
         {"components", components()},
         {"value", numbers(3, nullopt, "velocity at t_end (length/s)")},
         {"ramp", ramp_schema()}}},
       {"moving_wall", {{"set", set_key("named node set, face or interface (the wall the blood touches)")}}},
       {"pressure",
        {{"set", set_key("named boundary face set of the fluid")},
         {"value", number(nullopt, Range::any(), "pressure P at t_end (Pa)")},
         {"ramp", ramp_schema()},
         {"backflow", number(0.0, Range::non_negative(),
                             "β of the backflow stabilization (Moghadam et al. 2011): dissipates the "
                             "kinetic energy of flow coming back in; 0.2–1 on outlets that may see "
                             "reversed flow, 0: off")}}},
       {"traction",
        {{"set", set_key("named boundary face set of the fluid")},
         {"value", numbers(3, nullopt, "traction t at t_end (Pa): the force per area the outside exerts on the blood")},
         {"ramp", ramp_schema()},
         {"backflow", number(0.0, Range::non_negative(), "β of the backflow stabilization (see pressure)")}}},
       {"flux",
        {{"set", set_key("named boundary face set of the fluid")},
         {"value", number(nullopt, Range::any(), "flux Q at t_end, out of the fluid (volume/s)")},
         {"ramp", ramp_schema()},
         {"backflow", number(0.0, Range::non_negative(),
                             "β of the backflow stabilization (see pressure): for a face blood enters by "
                             "(Q < 0), ≥ 0.5")}}},
       {"valve",
        {{"set", set_key("named boundary face set of the fluid: the valve's ring")},
         {"cavity", string(nullopt, "the circulation's cavity whose valve this ring is")},
         {"side", choice(nullopt, {"inflow", "outflow"},
                         "inflow: the cavity's inflow valve (mitral), blood enters; outflow: its outflow "
                         "valve (aortic), blood leaves")},
         {"backflow", number(0.5, Range::non_negative(),
                             "β of the backflow stabilization (see pressure): blood enters through an "
                             "inflow ring, and its kinetic energy ½ρ|c·n||v|² would come in unbounded "
                             "through the ring's natural boundary term; β ≥ 0.5 takes it out (0: off)")}}}});
}

Schema mesh_motion() {
  return object(false,
                "the fluid mesh's motion (ALE): its displacement extends its boundary values into the "
                "fluid; absent: the mesh stays where it is",
                {{"kind", choice("harmonic", {"harmonic", "elastic"},
                                 "extension: harmonic (Laplace per component) or linear elastic (ν = 0.3)")},
                 {"stiffening", number(1.0, Range::closed(0.0, 4.0),
                                       "χ of the Jacobian-based stiffening (V̄/V_e)^χ: small elements deform "
                                       "less (0: none)")},
                 {"boundaries",
                  array(true, "where the mesh displacement is given; every fluid boundary node should be in one",
                        object(true, "a mesh-motion boundary",
                               {{"set", set_key("named node set (or face)")},
                                {"follow", choice("fixed", {"fixed", "wall"},
                                                  "fixed: d = 0; wall: d = the wall's displacement on the "
                                                  "set's nodes shared with the wall")}}),
                        1)}});
}

}  // namespace

Schema fluid_schema() {
  return object(
      false,
      "blood: incompressible Newtonian Navier–Stokes in ALE form on the fluid regions (paper Eq. 1, "
      "§II-A), solved with the wall in one Newton loop; absent: no fluid (nothing allocated)",
      {{"regions", required(custom("array of region tags or names", "the regions of the fluid",
                                   {{"type", "array"}, {"items", {{"type", {"string", "integer"}}}}, {"minItems", 1}}))},
       {"density", number(nullopt, Range::positive(),
                          "ρ in units consistent with the mesh's lengths, seconds and Pa: blood 1.06e-3 with "
                          "lengths in mm (1060 kg/m³), 1060 with lengths in m")},
       {"viscosity", number(nullopt, Range::positive(), "dynamic viscosity μ (Pa s): blood about 3.5e-3")},
       {"element", choice("auto", {"auto", "taylor_hood", "taylor_hood_supg", "p1p1"},
                          "taylor_hood: P2/P1 (quadratic meshes); taylor_hood_supg: P2/P1 with SUPG/LSIC "
                          "stabilization (convection-dominated flows: a ventricle); p1p1: "
                          "SUPG/PSPG/LSIC-stabilized P1/P1 "
                          "(linear meshes); auto: the one of the mesh's order")},
       {"convection",
        choice("advective", {"advective", "skew_symmetric"},
               "the convective term: advective, ρ(c·∇)v; skew_symmetric adds Temam's ½ρ(div v)v, zero for the "
               "exact flow, so that the blood's kinetic energy changes by exactly what its open faces carry, the "
               "forces' work and the viscous dissipation, on the moving mesh too (the advective form is off by "
               "½∫ρ|v|² div v, which a Taylor–Hood velocity keeps). skew_symmetric suits enclosed blood (a cavity "
               "with valve rings); at a pressure inlet it lets the inflow's kinetic energy in unchecked "
               "(configs/tube-flow.json does not converge past t = 0.4 s with it)")},
       {"time", choice("bdf2", {"bdf2", "bdf1", "steady"},
                       "∂v/∂t by BDF2 (second order, variable step), BDF1, or none (the steady equations)")},
       {"body_force", numbers(3, std::vector<double>{0, 0, 0}, "body force per unit mass (length/s²)")},
       {"initial_velocity", numbers(3, std::vector<double>{0, 0, 0}, "uniform velocity at the start")},
       {"residual_pressure",
        number(1.0, Range::positive(),
               "Pa: the momentum residual is measured against the forces of at least this pressure "
               "(a flow at rest has no forces to compare with)")},
       {"coupling",
        choice("one_way", {"one_way", "two_way"},
               "one_way: the blood follows the wall (its moving walls' forces do not act back); two_way: the "
               "force each moving wall exerts on the blood acts back on the wall (shared interface nodes, "
               "the traction balanced node by node), so the blood's pressure loads the wall")},
       {"boundaries", array(true, "the fluid's boundary conditions, applied in order (a later velocity "
                                  "condition on a node replaces an earlier one)",
                            boundary(), 1)},
       {"mesh_motion", mesh_motion()}});
}

}  // namespace fe2
