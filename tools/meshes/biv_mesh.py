#!/usr/bin/python3
"""An idealized biventricular (BiV) mesh, made with Gmsh's OpenCASCADE kernel.

The classic idealized BiV: four ellipsoids with the long axis along z, all cut by the
base plane z = BASE_Z (the apex toward -z, as in Land et al. 2015, problem 2):
  LV endo and LV epi centred on the z axis (the benchmark LV: 7/17 mm and 10/20 mm),
  RV endo and RV epi shifted along +x, wider than the LV, so the RV sits on the LV free
  wall and its cavity is the part of the RV endo ellipsoid outside the LV epicardium:
    solid = (LV_epi ∪ RV_epi) − LV_endo − (RV_endo − LV_epi) − {z > BASE_Z}.
The septum is the LV wall between the two cavities.

Physical groups: volume `myocardium`; surfaces `lv_endo` (the LV cavity), `rv_endo` (the
RV cavity: RV free-wall endocardium and the septum's RV side), `epi` (everything
outside), `base` (z = BASE_Z). With --cavity the blood too: volumes `lv_blood` and
`rv_blood` filling the cavities up to the base plane and sharing `lv_endo` / `rv_endo`
with the wall (interfaces: the same nodes), and in each cavity's base the valve rings
`mitral`, `aortic` (LV) and `tricuspid`, `pulmonary` (RV), the rest `lv_base_cap` and
`rv_base_cap`. Writes MSH 4.1 ASCII, linear or quadratic (10-node tets,
6-node triangles, nodes on the curved CAD surfaces), readable by fe2heart's
read_gmsh_tets. Lengths in mm.

  /usr/bin/python3 tools/meshes/biv_mesh.py configs/meshes/biv_coarse.msh --size 2.5 [--order 2]

--scale multiplies every length (the ellipsoids and the base plane); --rv-wall sets the
RV free wall's thickness (mm, after scaling) in place of the scaled 3 mm; --rv-cavity
widens the RV endocardium about its centre; --curvature 0 sizes elements from --size
alone. The human-sized heart of configs/biv-beat-fe2.json (LV endo 22.4/54.4 mm, LV wall
9.6 mm, RV wall 4 mm; 204 tets) is

  /usr/bin/python3 tools/meshes/biv_mesh.py configs/meshes/biv_human.msh --scale 3.2 \
      --rv-wall 4 --rv-cavity 1.1 --size 36 --curvature 0 --order 2

With blood in a beating heart two places fold blood elements whose vertices all lie on the
moving endocardium (the mesh motion cannot move them): the thin wrap of the RV crescent,
where the RV endocardium meets the LV epicardium at about 12° (the septum and the free wall
shear across one element), and the LV's apical cap. --rv-cut X ends the RV cavity at the
plane x = X (mm, after scaling; the wrap beyond it is wall, a thicker RV insertion) and
--lv-axis-nodes D puts mesh nodes on the LV's long axis inside its blood, from D mm above
the endocardial apex to the base, one per --size, so the apical elements have a vertex the
mesh motion moves. The biventricular heart with blood of configs/biv-beat-blood.json is

  /usr/bin/python3 tools/meshes/biv_mesh.py configs/meshes/biv_human_blood.msh --scale 3.2 \
      --rv-wall 4 --rv-cavity 1.1 --size 15 --curvature 0 --order 2 --cavity --rv-cut 12 \
      --lv-axis-nodes 10

--rv-mid-nodes puts mesh nodes midway across the RV cavity (between the LV epicardium and
the RV endocardium, one per --size where the cavity is at least half --size thick), so
most RV blood elements get a vertex off the wall (at --size 15, 181 of 563 keep all four
on it, against 343 without). --ring-scale F multiplies the four valve rings' radii (the
default rings are small: ejection through them is a jet); it refuses a scale at which
rings would touch each other or their base's rim. --rv-tip-size S sets the element size to
S mm at the RV cavity's corners off the base (its apical tip, where the RV endocardium
leaves the LV epicardium, and the --rv-cut faces' lower corners), growing back to --size
over 2 --size: the wall and the blood are thin wedges there, and coarse elements make
slivers of them (at --size 15, --rv-tip-size 5 gives 1217 wall tets against 966).
--lv-apex-size S does the same about the LV's endocardial apex (with or without --cavity),
where systole twists the apex against the base.

Gmsh's output differs between runs in the last digits of the curved nodes' coordinates
(round-off in its optimizer); the shipped files are the ones the configs were measured on.
At this coarseness Gmsh can fail ("PLC Error") or emit an inverted tet (fe2heart's reader
names it) for neighbouring sizes: try another --size.

Needs Debian's python3-gmsh (tools/bootstrap.sh installs it).
"""
import argparse
import math
import sys

import gmsh

from msh_output import raise_to_quadratic, write_physical_groups

BASE_Z = 5.0
# (centre x, semi-axis x, semi-axis y, semi-axis z); all centred at y = z = 0.
LV_ENDO = (0.0, 7.0, 7.0, 17.0)
LV_EPI = (0.0, 10.0, 10.0, 20.0)
RV_ENDO = (4.0, 12.0, 10.0, 15.0)
RV_EPI = (4.0, 15.0, 13.0, 18.0)


RV_CUT = None  # x of the plane ending the RV cavity (None: the whole crescent)
RING_SCALE = 1.0  # multiplies every valve ring's radius


def rv_mid_points(size):
    """Points midway across the RV cavity (between the LV epicardium and the RV endocardium
    along rays from the long axis), about `size` apart, where the cavity is at least half
    `size` thick and, with a cut, 0.3 `size` beyond it: with these as mesh nodes the RV
    blood's elements have a vertex off the wall for the mesh motion to move."""
    cx, ax, ay, az = RV_ENDO
    _, ex, _, ez = LV_EPI
    points, z = [], -az + 0.5 * size
    while z < BASE_Z - 0.5 * size:
        r_epi = ex * max(0.0, 1.0 - (z / ez) ** 2) ** 0.5
        k = 1.0 - (z / az) ** 2  # the RV endo's section at this z: ((x-cx)/ax)² + (y/ay)² = k
        n = max(8, int(2.0 * math.pi * (r_epi + 0.5 * size) / size))
        for i in range(n):
            t = 2.0 * math.pi * i / n
            c, s = math.cos(t), math.sin(t)
            a = (c / ax) ** 2 + (s / ay) ** 2  # r² a − 2 r c cx / ax² + cx²/ax² − k = 0
            b = -2.0 * c * cx / ax**2
            d = b * b - 4.0 * a * ((cx / ax) ** 2 - k)
            if k <= 0.0 or d <= 0.0:
                continue
            r_rv = (-b + d**0.5) / (2.0 * a)
            if r_rv - r_epi < 0.5 * size:
                continue
            r = 0.5 * (r_rv + r_epi)
            if RV_CUT is not None and r * c < RV_CUT + 0.3 * size:
                continue
            points.append((r * c, r * s, z))
        z += size
    return points


def scale_geometry(scale, rv_wall, rv_cavity=1.0):
    """Rescale the module's ellipsoids and base plane in place (classify() reads them).
    rv_wall (mm, or None for the scaled default): RV epi semi-axes = RV endo's + rv_wall.
    rv_cavity: multiplies the RV endo semi-axes (about the same centre) before the wall."""
    global BASE_Z, LV_ENDO, LV_EPI, RV_ENDO, RV_EPI
    BASE_Z *= scale
    LV_ENDO, LV_EPI, RV_ENDO, RV_EPI = (tuple(scale * v for v in e) for e in (LV_ENDO, LV_EPI, RV_ENDO, RV_EPI))
    if rv_cavity != 1.0:
        RV_ENDO = (RV_ENDO[0],) + tuple(rv_cavity * a for a in RV_ENDO[1:])
        if rv_wall is None:
            rv_wall = 3.0 * scale
    if rv_wall is not None:
        RV_EPI = (RV_ENDO[0],) + tuple(a + rv_wall for a in RV_ENDO[1:])


def level(e, p):
    """(x - cx)²/ax² + y²/ay² + z²/az² − 1: zero on ellipsoid e, negative inside."""
    cx, ax, ay, az = e
    return ((p[0] - cx) / ax) ** 2 + (p[1] / ay) ** 2 + (p[2] / az) ** 2 - 1.0


def ellipsoid(occ, e):
    cx, ax, ay, az = e
    tag = occ.addSphere(cx, 0.0, 0.0, 1.0)
    occ.dilate([(3, tag)], cx, 0.0, 0.0, ax, ay, az)
    return (3, tag)


def base_section(e):
    """(centre x, semi-axis x, semi-axis y) of ellipsoid e's cut by the base plane."""
    cx, ax, ay, az = e
    f = (1.0 - (BASE_Z / az) ** 2) ** 0.5
    return cx, ax * f, ay * f


def valve_rings():
    """name -> (x, y, radius) of the rings in the cavities' bases: mitral and aortic side
    by side on the LV's base disc; tricuspid and pulmonary in the RV's crescent between
    the LV epicardium and the RV endocardium, at y = ±half its half-width."""
    _, r_lv, _ = base_section(LV_ENDO)
    f = RING_SCALE
    rings = {"mitral": (-0.45 * r_lv, 0.0, 0.4 * f * r_lv), "aortic": (0.5 * r_lv, 0.0, 0.3 * f * r_lv)}
    gap = rings["aortic"][0] - rings["aortic"][2] - (rings["mitral"][0] + rings["mitral"][2])
    if gap < 0.05 * r_lv or rings["mitral"][0] - rings["mitral"][2] < -0.95 * r_lv or \
            rings["aortic"][0] + rings["aortic"][2] > 0.95 * r_lv:
        sys.exit(f"biv_mesh.py: --ring-scale {f:g}: the mitral and aortic rings would touch each other or the "
                 "LV's base rim; expected a smaller scale")
    _, r_epi, _ = base_section(LV_EPI)
    cx, ax, ay = base_section(RV_ENDO)
    for name, y in (("tricuspid", 0.5 * ay), ("pulmonary", -0.5 * ay)):
        inner = (r_epi**2 - y**2) ** 0.5 if abs(y) < r_epi else 0.0
        outer = cx + ax * (1.0 - (y / ay) ** 2) ** 0.5
        if not outer > inner:
            sys.exit("biv_mesh.py: the RV cavity has no room for its rings at the base")
        rings[name] = (0.5 * (inner + outer), y, 0.3 * f * (outer - inner))
        if rings[name][2] > 0.45 * (outer - inner) or rings[name][2] > 0.9 * abs(y):
            sys.exit(f"biv_mesh.py: --ring-scale {f:g}: the {name} ring would touch the RV's base rim or the "
                     "other RV ring; expected a smaller scale")
        if RV_CUT is not None and rings[name][0] - rings[name][2] <= RV_CUT:
            sys.exit(f"biv_mesh.py: --rv-cut {RV_CUT}: the {name} ring (x from {rings[name][0] - rings[name][2]:.1f}) "
                     "would cross the cut; expected a cut short of the RV's rings")
    return rings


def build_geometry(cavity=False):
    """The wall's volume tag, and with `cavity` the LV and RV blood's."""
    occ = gmsh.model.occ
    lv_endo, lv_epi, rv_endo, rv_epi = (ellipsoid(occ, e) for e in (LV_ENDO, LV_EPI, RV_ENDO, RV_EPI))
    lv_epi_tool = occ.copy([lv_epi])
    rv_cavity, _ = occ.cut([rv_endo], lv_epi_tool)
    if RV_CUT is not None:  # the crescent's thin wrap beyond x = RV_CUT becomes wall
        big = 10.0 * max(RV_EPI[1:] + LV_EPI[1:])
        keep = occ.addBox(RV_CUT, -big, -big, 2.0 * big, 2.0 * big, 2.0 * big)
        rv_cavity, _ = occ.intersect(rv_cavity, [(3, keep)])
        if len(rv_cavity) != 1:
            sys.exit(f"biv_mesh.py: --rv-cut {RV_CUT}: the RV cavity became {len(rv_cavity)} volumes, expected 1")
    outer, _ = occ.fuse([lv_epi], [rv_epi])
    above = occ.addBox(-100.0, -100.0, BASE_Z, 200.0, 200.0, 100.0)
    tools = [lv_endo] + rv_cavity + [(3, above)]
    if not cavity:
        solid, _ = occ.cut(outer, tools)
        occ.synchronize()
        if len(solid) != 1:
            sys.exit(f"biv_mesh.py: the boolean operations gave {len(solid)} volumes, expected 1")
        return solid[0][1], None, None
    solid, _ = occ.cut(outer, tools, removeObject=True, removeTool=False)
    lv_blood, _ = occ.cut([lv_endo], [(3, above)], removeTool=False)
    rv_blood, _ = occ.cut(rv_cavity, [(3, above)])
    disks = [(2, occ.addDisk(x, y, BASE_Z, r, r)) for x, y, r in valve_rings().values()]
    out, _ = occ.fragment(solid + lv_blood + rv_blood, disks)
    occ.synchronize()
    volumes = [t for d, t in out if d == 3]
    if len(volumes) != 3:
        sys.exit(f"biv_mesh.py: the boolean operations gave {len(volumes)} volumes, expected 3 (wall, LV and RV blood)")

    # Each cavity's blood lies within its endocardial ellipsoid's x-extent (OCC's boxes are
    # a little loose); the wall reaches out to the epicardia. The RV blood's centre of
    # mass is outside the LV.
    def within(e, v):
        x_max = gmsh.model.getBoundingBox(3, v)[3]
        return x_max < e[0] + 1.05 * e[1]

    lv = [v for v in volumes if within(LV_ENDO, v)]
    rv = [v for v in volumes if v not in lv and within(RV_ENDO, v) and level(LV_EPI, occ.getCenterOfMass(3, v)) > 0.0]
    wall = [v for v in volumes if v not in lv + rv]
    if not (len(lv) == len(rv) == len(wall) == 1):
        sys.exit("biv_mesh.py: could not tell the wall from the LV and RV blood")
    return wall[0], lv[0], rv[0]


def size_ramp(distance, fine, size):
    """A Threshold field: element size `fine` where the field `distance` is 0, growing
    linearly to `size` at 2 `size`."""
    field = gmsh.model.mesh.field
    threshold = field.add("Threshold")
    field.setNumber(threshold, "InField", distance)
    field.setNumber(threshold, "SizeMin", fine)
    field.setNumber(threshold, "SizeMax", size)
    field.setNumber(threshold, "DistMin", 0.0)
    field.setNumber(threshold, "DistMax", 2.0 * size)
    return threshold


def refine_rv_tip(rv, tip_size, size):
    """Element size tip_size at the RV blood's corners off the base plane (its apical tip,
    where the RV endocardium leaves the LV epicardium at a few degrees, and where the
    --rv-cut faces meet that rim), growing linearly to `size` over 2 `size`: there both
    the wall and the blood are thin wedges, which coarse elements turn into the slivers
    that fold first in a beat. Returns the size field."""
    surfaces = gmsh.model.getBoundary([(3, rv)], oriented=False)
    curves = gmsh.model.getBoundary(surfaces, combined=False, oriented=False)
    points = {abs(t) for _, t in gmsh.model.getBoundary(curves, combined=False, oriented=False)}
    eps = 1e-3 * LV_EPI[3]
    tip = [p for p in sorted(points) if gmsh.model.getValue(0, p, [])[2] < BASE_Z - eps]
    if not tip:
        sys.exit("biv_mesh.py: --rv-tip-size: the RV blood has no corner off the base plane")
    distance = gmsh.model.mesh.field.add("Distance")
    gmsh.model.mesh.field.setNumbers(distance, "PointsList", tip)
    return size_ramp(distance, tip_size, size)


def refine_lv_apex(apex_size, size):
    """Element size apex_size at the LV's endocardial apex, growing linearly to `size`
    over 2 `size`: the apex twists against the base in systole, and an FE² wall (its
    units' matrix soft in shear) twists it further than the macro law, folding coarse
    apical blood elements whose vertices sit on the endocardium and the LV's axis.
    Returns the size field."""
    distance = gmsh.model.mesh.field.add("MathEval")
    gmsh.model.mesh.field.setString(distance, "F", f"sqrt(x*x + y*y + (z + {LV_ENDO[3]!r})^2)")
    return size_ramp(distance, apex_size, size)


def classify_with_blood(surface, wall, lv, rv):
    """The name of a surface of the wall and blood volumes, from what it bounds."""
    up, _ = gmsh.model.getAdjacencies(2, surface)
    up = set(up)
    if up == {wall, lv}:
        return "lv_endo"
    if up == {wall, rv}:
        return "rv_endo"
    if up == {wall}:
        return classify(surface)
    x0, y0, z0, x1, y1, z1 = gmsh.model.getBoundingBox(2, surface)
    eps = 1e-3 * LV_EPI[3]  # OCC's boxes carry the surfaces' tolerance
    if not (abs(z0 - BASE_Z) < eps and abs(z1 - BASE_Z) < eps):
        return None
    cx, cy, w = 0.5 * (x0 + x1), 0.5 * (y0 + y1), 0.5 * (x1 - x0)
    for name, (x, y, r) in valve_rings().items():
        if abs(cx - x) < eps and abs(cy - y) < eps and abs(w - r) < eps:
            return name
    return "lv_base_cap" if up == {lv} else "rv_base_cap"


def classify(surface):
    """The name of a boundary surface, from one of its interior mesh nodes."""
    _, coords, _ = gmsh.model.mesh.getNodes(2, surface, includeBoundary=False)
    if len(coords) < 3:
        sys.exit(f"biv_mesh.py: surface {surface} has no interior mesh node; use a smaller --size")
    p = coords[0:3]
    if abs(p[2] - BASE_Z) < 1e-6:
        return "base"
    distances = {name: abs(level(e, p)) for name, e in
                 (("lv_endo", LV_ENDO), ("lv_epi", LV_EPI), ("rv_endo", RV_ENDO), ("rv_epi", RV_EPI))}
    on = min(distances, key=distances.get)
    if distances[on] > 1e-3:
        sys.exit(f"biv_mesh.py: surface {surface} (node {p}) lies on no ellipsoid and not on the base")
    if on == "lv_epi":  # the septum's RV side faces the RV cavity; the rest is outside
        return "rv_endo" if level(RV_ENDO, p) < 0.0 else "epi"
    return {"lv_endo": "lv_endo", "rv_endo": "rv_endo", "rv_epi": "epi"}[on]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("output", help="the .msh file to write")
    parser.add_argument("--size", type=float, default=2.5, help="target element size in mm (default 2.5)")
    parser.add_argument("--order", type=int, choices=(1, 2), default=1, help="element order (default 1)")
    parser.add_argument("--curvature", type=int, default=12,
                        help="elements per 2π of surface curvature (default 12; 0: sizes from --size alone)")
    parser.add_argument("--scale", type=float, default=1.0, help="multiplies every length (default 1)")
    parser.add_argument("--rv-wall", type=float, help="RV free-wall thickness in mm (default: 3 mm x scale)")
    parser.add_argument("--rv-cavity", type=float, default=1.0,
                        help="multiplies the RV endocardium's semi-axes (default 1): a larger RV cavity")
    parser.add_argument("--cavity", action="store_true",
                        help="mesh the blood in both cavities too, with the valve rings in their bases")
    parser.add_argument("--rv-cut", type=float,
                        help="end the RV cavity at the plane x = RV_CUT (mm, after scaling): its thin wrap beyond is wall")
    parser.add_argument("--ring-scale", type=float, default=1.0,
                        help="with --cavity: multiplies the valve rings' radii (default 1: mitral 0.4, aortic 0.3 of "
                             "the LV base radius, the RV's 0.3 of the crescent's width)")
    parser.add_argument("--rv-mid-nodes", action="store_true",
                        help="with --cavity: mesh nodes midway across the RV cavity, one per --size, where it is thick enough")
    parser.add_argument("--rv-tip-size", type=float, metavar="S",
                        help="with --cavity: element size S (mm) at the RV cavity's corners off the base (its apical "
                             "tip on the LV epicardium, the --rv-cut faces' lower corners), growing to --size over 2 --size")
    parser.add_argument("--lv-apex-size", type=float, metavar="S",
                        help="element size S (mm) at the LV's endocardial apex, growing to --size over 2 --size")
    parser.add_argument("--lv-axis-nodes", type=float, metavar="D",
                        help="with --cavity: mesh nodes on the LV's axis inside its blood, from D mm above the apex")
    args = parser.parse_args()
    if not args.size > 0.0:
        sys.exit(f"biv_mesh.py: --size {args.size}: expected a size > 0 (mm)")
    if args.curvature < 0:
        sys.exit(f"biv_mesh.py: --curvature {args.curvature}: expected a count >= 0 (0: off)")
    if not args.scale > 0.0:
        sys.exit(f"biv_mesh.py: --scale {args.scale}: expected a factor > 0")
    if args.rv_wall is not None and not args.rv_wall > 0.0:
        sys.exit(f"biv_mesh.py: --rv-wall {args.rv_wall}: expected a thickness > 0 (mm)")
    if not args.rv_cavity > 0.0:
        sys.exit(f"biv_mesh.py: --rv-cavity {args.rv_cavity}: expected a factor > 0")
    scale_geometry(args.scale, args.rv_wall, args.rv_cavity)
    if not args.ring_scale > 0.0:
        sys.exit(f"biv_mesh.py: --ring-scale {args.ring_scale}: expected a factor > 0")
    global RV_CUT, RING_SCALE
    RV_CUT = args.rv_cut
    RING_SCALE = args.ring_scale
    if args.rv_tip_size is not None and not args.cavity:
        sys.exit("biv_mesh.py: --rv-tip-size refines the RV blood's tip: it needs --cavity")
    for option, fine in (("--rv-tip-size", args.rv_tip_size), ("--lv-apex-size", args.lv_apex_size)):
        if fine is not None and not 0.0 < fine < args.size:
            sys.exit(f"biv_mesh.py: {option} {fine}: expected a size in (0, {args.size:g}) mm (below --size)")
    if args.lv_axis_nodes is not None:
        if not args.cavity:
            sys.exit("biv_mesh.py: --lv-axis-nodes puts nodes in the LV blood: it needs --cavity")
        if not 0.0 < args.lv_axis_nodes < LV_ENDO[3] + BASE_Z:
            sys.exit(f"biv_mesh.py: --lv-axis-nodes {args.lv_axis_nodes}: expected a distance in (0, "
                     f"{LV_ENDO[3] + BASE_Z:g}) mm above the LV's endocardial apex")

    gmsh.initialize(["biv_mesh.py"])
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.option.setNumber("General.NumThreads", 1)  # one thread: the same mesh every run
        gmsh.model.add("biv")
        wall, lv, rv = build_geometry(args.cavity)
        gmsh.option.setNumber("Mesh.MeshSizeMax", args.size)
        gmsh.option.setNumber("Mesh.MeshSizeMin", min(0.3 * args.size, args.rv_tip_size or args.size,
                                                       args.lv_apex_size or args.size))
        gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", args.curvature)  # elements per 2π of curvature
        if args.curvature == 0:  # sizes from --size alone, not spread in from small boundary curves
            gmsh.option.setNumber("Mesh.MeshSizeExtendFromBoundary", 0)
            gmsh.option.setNumber("Mesh.MeshSizeFromPoints", 0)
        if args.lv_axis_nodes is not None:
            # Nodes on the LV's long axis: the apical blood elements get a vertex off the wall.
            z, nodes = -LV_ENDO[3] + args.lv_axis_nodes, []
            while z < BASE_Z - 0.5 * args.size:
                nodes.append(gmsh.model.occ.addPoint(0.0, 0.0, z))
                z += args.size
            gmsh.model.occ.synchronize()
            gmsh.model.mesh.embed(0, nodes, 3, lv)
        ramps = []
        if args.rv_tip_size is not None:
            ramps.append(refine_rv_tip(rv, args.rv_tip_size, args.size))
        if args.lv_apex_size is not None:
            ramps.append(refine_lv_apex(args.lv_apex_size, args.size))
        if ramps:
            finest = gmsh.model.mesh.field.add("Min")
            gmsh.model.mesh.field.setNumbers(finest, "FieldsList", ramps)
            gmsh.model.mesh.field.setAsBackgroundMesh(finest)
        if args.rv_mid_nodes:
            if not args.cavity:
                sys.exit("biv_mesh.py: --rv-mid-nodes puts nodes in the RV blood: it needs --cavity")
            nodes = [gmsh.model.occ.addPoint(*p) for p in rv_mid_points(args.size)]
            gmsh.model.occ.synchronize()
            gmsh.model.mesh.embed(0, nodes, 3, rv)
        gmsh.model.mesh.generate(3)
        if args.order == 2:
            raise_to_quadratic()  # the septum is the thin element that could fold
        groups = {}
        if args.cavity:
            for _, tag in gmsh.model.getEntities(2):
                name = classify_with_blood(tag, wall, lv, rv)
                if name:
                    groups.setdefault(name, []).append(tag)
            needed = ("lv_endo", "rv_endo", "epi", "base", "lv_base_cap", "rv_base_cap") + tuple(valve_rings())
            volumes = [("myocardium", [wall], 1), ("lv_blood", [lv], 2), ("rv_blood", [rv], 3)]
        else:
            for dim, tag in gmsh.model.getBoundary([(3, wall)], oriented=False):
                groups.setdefault(classify(tag), []).append(tag)
            needed = ("lv_endo", "rv_endo", "epi", "base")
            volumes = [("myocardium", [wall], -1)]
        for name in needed:
            if name not in groups:
                sys.exit(f"biv_mesh.py: no surface classified as {name}; check the ellipsoids")
        write_physical_groups(args.output, args.order, groups, volumes)
    finally:
        gmsh.finalize()


if __name__ == "__main__":
    main()
