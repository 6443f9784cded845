#!/usr/bin/python3
"""A straight elastic tube with its fluid core, made with Gmsh's OpenCASCADE kernel.

The tube runs along z from 0 to --length: the fluid core is the cylinder r < --radius,
the wall the annulus --radius < r < --radius + --wall; both meshed together so that they
share their nodes on the lumen (r = --radius).

Physical groups: volumes `blood` (region 1) and `wall` (region 2); surfaces `inlet` and
`outlet` (the fluid's discs at z = 0 and z = length), `lumen` (the fluid–wall interface,
an interior surface: fe2heart reads it as an interface and a node set), `outer` (r =
radius + wall), `wall_inlet` and `wall_outlet` (the wall's annular ends). Writes MSH 4.1
ASCII, linear or quadratic (nodes on the curved surfaces). Lengths in mm.

  /usr/bin/python3 tools/meshes/tube_mesh.py configs/meshes/tube.msh --radius 1 --wall 0.3 \\
      --length 6 --size 0.5 --order 2

Needs Debian's python3-gmsh (tools/bootstrap.sh installs it).
"""
import argparse
import sys

import gmsh

from msh_output import mesh_and_write


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("output", help="the .msh file to write")
    parser.add_argument("--radius", type=float, default=1.0, help="lumen radius in mm (default 1)")
    parser.add_argument("--wall", type=float, default=0.3, help="wall thickness in mm (default 0.3)")
    parser.add_argument("--length", type=float, default=6.0, help="tube length in mm (default 6)")
    parser.add_argument("--size", type=float, default=0.5, help="target element size in mm (default 0.5)")
    parser.add_argument("--order", type=int, choices=(1, 2), default=2, help="element order (default 2)")
    args = parser.parse_args()
    for name in ("radius", "wall", "length", "size"):
        if not getattr(args, name) > 0.0:
            sys.exit(f"tube_mesh.py: --{name} {getattr(args, name)}: expected a length > 0 (mm)")

    gmsh.initialize(["tube_mesh.py"])
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.option.setNumber("General.NumThreads", 1)  # one thread: the same mesh every run
        gmsh.model.add("tube")
        occ = gmsh.model.occ
        core = occ.addCylinder(0, 0, 0, 0, 0, args.length, args.radius)
        outer = occ.addCylinder(0, 0, 0, 0, 0, args.length, args.radius + args.wall)
        # Fragment: the core and the annulus around it, sharing the lumen surface.
        out, _ = occ.fragment([(3, outer)], [(3, core)])
        occ.synchronize()
        volumes = [tag for dim, tag in out if dim == 3]
        if len(volumes) != 2:
            sys.exit(f"tube_mesh.py: expected 2 volumes after the fragment, got {len(volumes)}")

        def mean_radius(dim, tag):
            x0, y0, z0, x1, y1, z1 = gmsh.model.getBoundingBox(dim, tag)
            return max(x1 - x0, y1 - y0) / 2

        blood = min(volumes, key=lambda v: mean_radius(3, v))
        wall = max(volumes, key=lambda v: mean_radius(3, v))
        groups = {}
        eps = 1e-6 * args.length
        for dim, tag in gmsh.model.getEntities(2):
            x0, y0, z0, x1, y1, z1 = gmsh.model.getBoundingBox(dim, tag)
            r = mean_radius(dim, tag)
            if z1 - z0 > eps:  # a cylinder
                name = "lumen" if abs(r - args.radius) < 1e-3 * args.radius else "outer"
            else:  # a disc or an annulus at an end
                up, down = gmsh.model.getAdjacencies(dim, tag)
                in_blood = blood in up
                end = "inlet" if z1 < eps else "outlet"
                name = end if in_blood else f"wall_{end}"
            groups.setdefault(name, []).append(tag)
        mesh_and_write("tube_mesh.py", args.output, args.order, args.size, groups,
                       ("lumen", "outer", "inlet", "outlet", "wall_inlet", "wall_outlet"),
                       [("blood", [blood], 1), ("wall", [wall], 2)])
    finally:
        gmsh.finalize()


if __name__ == "__main__":
    main()
