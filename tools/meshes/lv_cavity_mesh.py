#!/usr/bin/python3
"""An idealized left ventricle with the blood in its cavity, made with Gmsh's OpenCASCADE kernel.

Truncated prolate ellipsoids with the long axis along z, apex toward -z, cut by the base
plane z = --base-z (the geometry of fe2heart's "lv" mesh kind, in mm): the wall between
the endocardium (semi-axes --endo) and the epicardium (--epi), and the cavity inside the
endocardium, closed at the base plane. Wall and cavity are meshed together, so they share
their nodes on the endocardium. Two discs in the cavity's base are the valve rings:
mitral (radius --mitral, centred at x = -(--mitral-offset)) and aortic (--aortic at
x = +--aortic-offset).

Physical groups: volumes `myocardium` (region 1) and `blood` (region 2); surfaces
`endo` (the wall–blood interface: an interior surface, read as an interface and a node
set), `epi`, `base` (the wall's base ring), `mitral`, `aortic` (the rings) and
`base_cap` (the rest of the cavity's base plane). Writes MSH 4.1 ASCII, linear or
quadratic. The default is configs/meshes/lv_cavity.msh:

  /usr/bin/python3 tools/meshes/lv_cavity_mesh.py configs/meshes/lv_cavity.msh --size 10 --order 2

Gmsh's output differs between runs in the last digits of the curved nodes' coordinates
(round-off in its optimizer); the shipped file is the one the tests were measured on.

Needs Debian's python3-gmsh (tools/bootstrap.sh installs it).
"""
import argparse
import math
import sys

import gmsh

from msh_output import mesh_and_write


def ellipsoid(occ, a, c):
    tag = occ.addSphere(0, 0, 0, 1.0)
    occ.dilate([(3, tag)], 0, 0, 0, a, a, c)
    return tag


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("output", help="the .msh file to write")
    parser.add_argument("--endo", type=float, nargs=2, default=(22.0, 56.0), help="endocardium semi-axes (short, long)")
    parser.add_argument("--epi", type=float, nargs=2, default=(32.0, 66.0), help="epicardium semi-axes (short, long)")
    parser.add_argument("--base-z", type=float, default=14.0, help="the base plane (default 14)")
    parser.add_argument("--mitral", type=float, default=10.0, help="mitral ring radius (default 10)")
    parser.add_argument("--mitral-offset", type=float, default=8.0, help="mitral centre at x = -this (default 8)")
    parser.add_argument("--aortic", type=float, default=6.0, help="aortic ring radius (default 6)")
    parser.add_argument("--aortic-offset", type=float, default=13.0, help="aortic centre at x = +this (default 13)")
    parser.add_argument("--size", type=float, default=10.0, help="target element size in mm (default 10)")
    parser.add_argument("--order", type=int, choices=(1, 2), default=2, help="element order (default 2)")
    args = parser.parse_args()
    (ae, ce), (ao, co), b = args.endo, args.epi, args.base_z
    if not (0 < ae < ao and 0 < ce < co):
        sys.exit(f"lv_cavity_mesh.py: --endo {ae} {ce}, --epi {ao} {co}: expected 0 < endo < epi in both axes")
    if not abs(b) < ce:
        sys.exit(f"lv_cavity_mesh.py: --base-z {b}: expected a plane cutting the endocardium, |base_z| < {ce}")
    r_base = ae * math.sqrt(1 - (b / ce) ** 2)  # the cavity's radius in the base plane
    m0, a0 = -args.mitral_offset, args.aortic_offset
    if not (abs(m0) + args.mitral < r_base and abs(a0) + args.aortic < r_base):
        sys.exit(f"lv_cavity_mesh.py: the rings must lie inside the cavity's base (radius {r_base:.2f})")
    if not a0 - args.aortic > m0 + args.mitral:
        sys.exit("lv_cavity_mesh.py: the mitral and aortic rings overlap")
    if not args.size > 0:
        sys.exit(f"lv_cavity_mesh.py: --size {args.size}: expected a size > 0 (mm)")

    gmsh.initialize(["lv_cavity_mesh.py"])
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.option.setNumber("General.NumThreads", 1)  # one thread: the same mesh every run
        gmsh.model.add("lv_cavity")
        occ = gmsh.model.occ
        big = 4 * co
        above = occ.addBox(-big, -big, b, 2 * big, 2 * big, big)
        epi = ellipsoid(occ, ao, co)
        endo = ellipsoid(occ, ae, ce)
        cavity, _ = occ.cut([(3, endo)], [(3, above)], removeTool=False)
        solid, _ = occ.cut([(3, epi)], [(3, above)])
        mitral = occ.addDisk(m0, 0, b, args.mitral, args.mitral)
        aortic = occ.addDisk(a0, 0, b, args.aortic, args.aortic)
        # Fragment: the wall, the cavity (sharing the endocardium) and the rings cut into
        # the cavity's base face.
        out, _ = occ.fragment(solid + cavity, [(2, mitral), (2, aortic)])
        occ.synchronize()
        volumes = [t for d, t in out if d == 3]
        if len(volumes) != 2:
            sys.exit(f"lv_cavity_mesh.py: expected 2 volumes after the fragment, got {len(volumes)}")

        # OCC's bounding boxes of trimmed entities are loose: tell the volumes apart by
        # their masses (the wall is the larger at these proportions; checked below).
        wall = max(volumes, key=lambda v: occ.getMass(3, v))
        blood = min(volumes, key=lambda v: occ.getMass(3, v))
        groups = {}
        eps = 1e-3 * co  # OCC boxes carry the surfaces' tolerance
        for dim, tag in gmsh.model.getEntities(2):
            up, _ = gmsh.model.getAdjacencies(dim, tag)
            up = set(up)
            x0, y0, z0, x1, y1, z1 = gmsh.model.getBoundingBox(dim, tag)
            flat = z1 - z0 < eps and abs(z0 - b) < 1e-3 * co
            if up == {wall, blood}:
                name = "endo"
            elif up == {wall}:
                name = "base" if flat else "epi"
            elif up == {blood} and flat:
                cx = 0.5 * (x0 + x1)
                w = 0.5 * (x1 - x0)
                if abs(cx - m0) < 1e-3 * co and abs(w - args.mitral) < 1e-3 * co:
                    name = "mitral"
                elif abs(cx - a0) < 1e-3 * co and abs(w - args.aortic) < 1e-3 * co:
                    name = "aortic"
                else:
                    name = "base_cap"
            else:
                continue  # a ring disc left outside the cavity would be a bug: checked below
            groups.setdefault(name, []).append(tag)
        mesh_and_write("lv_cavity_mesh.py", args.output, args.order, args.size, groups,
                       ("endo", "epi", "base", "mitral", "aortic", "base_cap"),
                       [("myocardium", [wall], 1), ("blood", [blood], 2)])
    finally:
        gmsh.finalize()


if __name__ == "__main__":
    main()
