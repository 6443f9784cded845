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
outside), `base` (z = BASE_Z). Writes MSH 4.1 ASCII, linear or quadratic (10-node tets,
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

Gmsh's output differs between runs in the last digits of the curved nodes' coordinates
(round-off in its optimizer); the shipped files are the ones the configs were measured on.
At this coarseness Gmsh can fail ("PLC Error") or emit an inverted tet (fe2heart's reader
names it) for neighbouring sizes: try another --size.

Needs Debian's python3-gmsh (tools/bootstrap.sh installs it).
"""
import argparse
import sys

import gmsh

from msh_output import raise_to_quadratic, write_physical_groups

BASE_Z = 5.0
# (centre x, semi-axis x, semi-axis y, semi-axis z); all centred at y = z = 0.
LV_ENDO = (0.0, 7.0, 7.0, 17.0)
LV_EPI = (0.0, 10.0, 10.0, 20.0)
RV_ENDO = (4.0, 12.0, 10.0, 15.0)
RV_EPI = (4.0, 15.0, 13.0, 18.0)


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


def build_geometry():
    occ = gmsh.model.occ
    lv_endo, lv_epi, rv_endo, rv_epi = (ellipsoid(occ, e) for e in (LV_ENDO, LV_EPI, RV_ENDO, RV_EPI))
    lv_epi_tool = occ.copy([lv_epi])
    rv_cavity, _ = occ.cut([rv_endo], lv_epi_tool)
    outer, _ = occ.fuse([lv_epi], [rv_epi])
    above = occ.addBox(-100.0, -100.0, BASE_Z, 200.0, 200.0, 100.0)
    solid, _ = occ.cut(outer, [lv_endo] + rv_cavity + [(3, above)])
    occ.synchronize()
    if len(solid) != 1:
        sys.exit(f"biv_mesh.py: the boolean operations gave {len(solid)} volumes, expected 1")
    return solid[0][1]


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

    gmsh.initialize(["biv_mesh.py"])
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.option.setNumber("General.NumThreads", 1)  # one thread: the same mesh every run
        gmsh.model.add("biv")
        volume = build_geometry()
        gmsh.option.setNumber("Mesh.MeshSizeMax", args.size)
        gmsh.option.setNumber("Mesh.MeshSizeMin", 0.3 * args.size)
        gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", args.curvature)  # elements per 2π of curvature
        if args.curvature == 0:  # sizes from --size alone, not spread in from small boundary curves
            gmsh.option.setNumber("Mesh.MeshSizeExtendFromBoundary", 0)
            gmsh.option.setNumber("Mesh.MeshSizeFromPoints", 0)
        gmsh.model.mesh.generate(3)
        if args.order == 2:
            raise_to_quadratic()  # the septum is the thin element that could fold
        groups = {}
        for dim, tag in gmsh.model.getBoundary([(3, volume)], oriented=False):
            groups.setdefault(classify(tag), []).append(tag)
        for needed in ("lv_endo", "rv_endo", "epi", "base"):
            if needed not in groups:
                sys.exit(f"biv_mesh.py: no surface classified as {needed}; check the ellipsoids")
        write_physical_groups(args.output, args.order, groups, [("myocardium", [volume], -1)])
    finally:
        gmsh.finalize()


if __name__ == "__main__":
    main()
