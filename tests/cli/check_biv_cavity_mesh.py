#!/usr/bin/python3
"""tools/meshes/biv_mesh.py --cavity: the biventricular wall with blood in both cavities.

  check_biv_cavity_mesh.py FE2HEART OUT_DIR

Writes OUT_DIR/biv_blood.msh (--cavity --size 3 --order 2) and checks:
  - regions myocardium (1), lv_blood (2), rv_blood (3); the LV blood's volume within 6 %
    of the truncated ellipsoid it fills (straight-sided vertex tets under-fill curves);
  - the blood shares the endocardia with the wall: every node of an lv_endo (rv_endo)
    triangle is a node of both a wall tet and an LV (RV) blood tet;
  - the four rings lie in the base plane, each inside its own cavity's base;
  - `fe2heart validate` accepts a scene with blood in both cavities, valve rings for both
    ventricles against a biventricular Windkessel, and the endocardia (interfaces of the
    mesh) as the wall's cavity surfaces.
With --rv-cut 4 --lv-axis-nodes 3 --rv-mid-nodes --ring-scale 1.2
(OUT_DIR/biv_blood_cut.msh): no RV blood node lies beyond the cut (x < 4), nodes on the LV's
axis lie inside its blood off every surface, every point of biv_mesh.rv_mid_points is an
RV blood node off every surface, each ring's radius is 1.2 times the first mesh's; the
same with --rv-tip-size 1 --lv-apex-size 1 (OUT_DIR/biv_blood_tip.msh) has elements of
at most 0.7 times the mean edge within 3 mm of the RV blood's apical tip and 0.85 times
that at the LV blood's apex; and --lv-axis-nodes, --rv-mid-nodes or --rv-tip-size
without --cavity, a --rv-tip-size or --lv-apex-size not below --size, and a --ring-scale
whose mitral and aortic rings would touch, are refused naming the option.
Exits 1 naming the first failed check.
"""
import json
import math
import os
import subprocess
import sys

import meshio
import numpy as np


def fail(msg):
    print("check_biv_cavity_mesh.py: " + msg)
    sys.exit(1)


def main():
    fe2heart, out = sys.argv[1], sys.argv[2]
    os.makedirs(out, exist_ok=True)
    msh = os.path.join(out, "biv_blood.msh")
    script = os.path.join(os.path.dirname(__file__), "../../tools/meshes/biv_mesh.py")
    subprocess.run(["/usr/bin/python3", script, msh, "--cavity", "--size", "3", "--order", "2"], check=True)
    m = meshio.read(msh)
    tets = np.vstack([c.data[:, :4] for c in m.cells if c.type.startswith("tetra")])
    region = np.concatenate([m.cell_data["gmsh:physical"][i] for i, c in enumerate(m.cells) if c.type.startswith("tetra")])
    p = m.points
    vol = np.einsum("ij,ij->i", p[tets[:, 1]] - p[tets[:, 0]],
                    np.cross(p[tets[:, 2]] - p[tets[:, 0]], p[tets[:, 3]] - p[tets[:, 0]])) / 6.0
    if set(region) != {1, 2, 3}:
        fail(f"regions {sorted(set(region))}, expected 1 (myocardium), 2 (lv_blood), 3 (rv_blood)")
    if not (vol > 0).all():
        fail("an inverted tet")
    # LV endo 7/17 mm cut at z = 5: π a² ((b + c) − (b³ + c³)/(3c²)).
    a, c, b = 7.0, 17.0, 5.0
    exact = math.pi * a * a * ((b + c) - (b**3 + c**3) / (3 * c * c))
    lv = vol[region == 2].sum()
    print(f"LV blood {lv:.0f} mm³ (ellipsoid {exact:.0f}), RV blood {vol[region == 3].sum():.0f}, wall {vol[region == 1].sum():.0f}")
    if abs(lv / exact - 1) > 0.06:
        fail(f"LV blood {lv:.0f} mm³, expected within 6 % of {exact:.0f}")
    node_regions = {}
    for t, r in zip(tets, region):
        for a_ in t:
            node_regions.setdefault(int(a_), set()).add(int(r))
    names = {name: tag for name, (tag, dim) in m.field_data.items()}
    tri_blocks = [(i, c) for i, c in enumerate(m.cells) if c.type.startswith("triangle")]

    def triangles(name):
        return np.vstack([c.data[:, :3][m.cell_data["gmsh:physical"][i] == names[name]] for i, c in tri_blocks])

    for surface, blood in (("lv_endo", 2), ("rv_endo", 3)):
        for a_ in set(triangles(surface).ravel()):
            if not {1, blood} <= node_regions[int(a_)]:
                fail(f"{surface}: node {a_} is not shared by the wall and its blood")
    for ring, blood in (("mitral", 2), ("aortic", 2), ("tricuspid", 3), ("pulmonary", 3)):
        nodes = set(triangles(ring).ravel())
        if not np.allclose(p[list(nodes), 2], 5.0, atol=1e-6):
            fail(f"{ring}: not in the base plane z = 5")
        if not all(blood in node_regions[int(a_)] for a_ in nodes):
            fail(f"{ring}: not in its cavity's base")
    spec = {
        "title": "biventricular wall with blood in both cavities (check_biv_cavity_mesh.py)",
        "mesh": {"kind": "gmsh", "file": "biv_blood.msh", "wall_regions": ["myocardium"]},
        "models": {"myocardium": {"kind": "macro_law", "material": {"model": "neo_hookean", "E": 30000, "nu": 0.45}}},
        "formulation": {"kind": "mixed"},
        "dirichlet": [{"set": "base"}],
        "cavities": {"lv": {"surface": "lv_endo"}, "rv": {"surface": "rv_endo"}},
        "circulation": {"kind": "windkessel", "period": 0.8, "cavities": {"lv": {}, "rv": {}}},
        "fluid": {
            "regions": ["lv_blood", "rv_blood"], "density": 1.06e-3, "viscosity": 3.5e-3,
            "element": "taylor_hood_supg", "time": "bdf1",
            "boundaries": [{"kind": "moving_wall", "set": "lv_endo"}, {"kind": "moving_wall", "set": "rv_endo"},
                           {"kind": "no_slip", "set": "lv_base_cap"}, {"kind": "no_slip", "set": "rv_base_cap"},
                           {"kind": "valve", "set": "mitral", "cavity": "lv", "side": "inflow"},
                           {"kind": "valve", "set": "aortic", "cavity": "lv", "side": "outflow"},
                           {"kind": "valve", "set": "tricuspid", "cavity": "rv", "side": "inflow"},
                           {"kind": "valve", "set": "pulmonary", "cavity": "rv", "side": "outflow"}],
            "mesh_motion": {"boundaries": [{"set": s, "follow": "wall" if s.endswith("endo") else "fixed"}
                                           for s in ("lv_endo", "rv_endo", "lv_base_cap", "rv_base_cap",
                                                     "mitral", "aortic", "tricuspid", "pulmonary")]}},
        "time": {"beats": 1, "steps_per_beat": 160, "inflation_steps": 10},
        "output": {"vtu": False}}
    path = os.path.join(out, "biv_blood.json")
    json.dump(spec, open(path, "w"), indent=1)
    r = subprocess.run([fe2heart, "validate", path], capture_output=True, text=True)
    if r.returncode != 0:
        fail(f"fe2heart validate {path}: exit {r.returncode}: {r.stdout}{r.stderr}")
    check_cut_and_axis(script, out)
    print("ok")


def check_cut_and_axis(script, out):
    msh = os.path.join(out, "biv_blood_cut.msh")
    subprocess.run(["/usr/bin/python3", script, msh, "--cavity", "--size", "3", "--order", "2",
                    "--rv-cut", "4", "--lv-axis-nodes", "3", "--rv-mid-nodes", "--ring-scale", "1.2"], check=True)
    m = meshio.read(msh)
    p = m.points
    blocks = [(i, c) for i, c in enumerate(m.cells) if c.type.startswith("tetra")]
    tets = np.vstack([c.data[:, :4] for _, c in blocks])
    region = np.concatenate([m.cell_data["gmsh:physical"][i] for i, _ in blocks])
    vol = np.einsum("ij,ij->i", p[tets[:, 1]] - p[tets[:, 0]],
                    np.cross(p[tets[:, 2]] - p[tets[:, 0]], p[tets[:, 3]] - p[tets[:, 0]])) / 6.0
    if not (vol > 0).all():
        fail("--rv-cut/--lv-axis-nodes: an inverted tet")
    rv_x = p[np.unique(tets[region == 3]), 0]
    if rv_x.min() < 4.0 - 1e-6:
        fail(f"--rv-cut 4: an RV blood node at x = {rv_x.min():.3f}")
    on_surface = set(np.concatenate([c.data.ravel() for c in m.cells if c.type.startswith("triangle")]).tolist())
    lv_nodes = set(np.unique(tets[region == 2]).tolist())
    axis = [a for a in lv_nodes - on_surface if abs(p[a, 0]) < 1e-9 and abs(p[a, 1]) < 1e-9]
    # From 3 mm above the apex (z = -17) to the base (z = 5), one per 3 mm: z = -14, ..., 1.
    if len(axis) < 6:
        fail(f"--lv-axis-nodes 3: {len(axis)} interior LV blood nodes on the axis, expected 6")
    rv_nodes = set(np.unique(tets[region == 3]).tolist()) - on_surface
    sys.path.insert(0, os.path.dirname(script))
    import biv_mesh
    biv_mesh.RV_CUT = 4.0
    mid = np.array(biv_mesh.rv_mid_points(3.0))
    interior = p[sorted(rv_nodes)]
    found = [np.linalg.norm(interior - q, axis=1).min() < 1e-9 for q in mid]
    if len(mid) < 10 or not all(found):
        fail(f"--rv-mid-nodes: {sum(found)} of the {len(mid)} mid-cavity points are interior RV blood nodes")
    default_mesh = meshio.read(os.path.join(out, "biv_blood.msh"))
    for ring, (cx, cy, r0) in biv_mesh.valve_rings().items():
        radius = [ring_radius(mesh, ring, cx, cy) for mesh in (default_mesh, m)]
        if abs(radius[0] / r0 - 1) > 1e-6 or abs(radius[1] / (1.2 * r0) - 1) > 1e-6:
            fail(f"--ring-scale 1.2: the {ring} ring's radius {radius[1]:.4f} mm, the default's {radius[0]:.4f}, "
                 f"expected {1.2 * r0:.4f} and {r0:.4f}")
    check_tip_refinement(script, out, m)
    for args, name in ((["--lv-axis-nodes", "3"], "--lv-axis-nodes"), (["--rv-mid-nodes"], "--rv-mid-nodes"),
                       (["--rv-tip-size", "1"], "--rv-tip-size"), (["--cavity", "--size", "3", "--rv-tip-size", "3"], "--rv-tip-size"),
                       (["--size", "3", "--lv-apex-size", "4"], "--lv-apex-size"),
                       (["--cavity", "--ring-scale", "1.5"], "--ring-scale")):
        r = subprocess.run(["/usr/bin/python3", script, os.path.join(out, "no.msh")] + args,
                           capture_output=True, text=True)
        if r.returncode == 0 or name not in r.stdout + r.stderr:
            fail(f"{' '.join(args)}: exit {r.returncode}, {r.stdout}{r.stderr}")
    print(f"--rv-cut 4: RV blood from x = {rv_x.min():.2f}; --lv-axis-nodes 3: {len(axis)} axis nodes; "
          f"--rv-mid-nodes: {len(mid)} mid-cavity nodes")


def mean_edge_at_lowest(mesh, blood):
    """(the mean edge length of the tets centred within 3 mm of the lowest node of the blood
    region `blood` (2: LV, 3: RV), their count)."""
    p = mesh.points
    blocks = [(i, c) for i, c in enumerate(mesh.cells) if c.type.startswith("tetra")]
    tets = np.vstack([c.data[:, :4] for _, c in blocks])
    region = np.concatenate([mesh.cell_data["gmsh:physical"][i] for i, _ in blocks])
    nodes = np.unique(tets[region == blood])
    tip = p[nodes[np.argmin(p[nodes, 2])]]
    near = np.linalg.norm(p[tets].mean(axis=1) - tip, axis=1) < 3.0
    edges = [np.linalg.norm(p[tets[near, i]] - p[tets[near, j]], axis=1) for i in range(4) for j in range(i + 1, 4)]
    return float(np.mean(edges)), int(near.sum())


def check_tip_refinement(script, out, coarse):
    """--rv-tip-size 1 --lv-apex-size 1 on the --rv-cut mesh: finer elements at the RV
    cavity's apical tip and at the LV's endocardial apex."""
    msh = os.path.join(out, "biv_blood_tip.msh")
    subprocess.run(["/usr/bin/python3", script, msh, "--cavity", "--size", "3", "--order", "2", "--rv-cut", "4",
                    "--lv-axis-nodes", "3", "--rv-mid-nodes", "--ring-scale", "1.2", "--rv-tip-size", "1",
                    "--lv-apex-size", "1"], check=True)
    fine = meshio.read(msh)
    # The LV's apex is finer than --size without the option (curvature sizing, the axis
    # nodes 3 mm above it: 2.6 mm against the RV tip's 3.1), so its gain is the smaller.
    for option, blood, where, ratio in (("--rv-tip-size", 3, "the RV blood's tip", 0.7),
                                        ("--lv-apex-size", 2, "the LV's apex", 0.85)):
        (before, n_before), (after, n_after) = mean_edge_at_lowest(coarse, blood), mean_edge_at_lowest(fine, blood)
        print(f"{option} 1: mean edge at {where} {after:.2f} mm ({n_after} tets), without {before:.2f} mm ({n_before})")
        if not after < ratio * before:
            fail(f"{option} 1: mean edge at {where} {after:.3f} mm, expected below {ratio} times "
                 f"the {before:.3f} mm without it")


def ring_radius(mesh, ring, cx, cy):
    """The largest distance of the ring's nodes from its centre (its boundary circle)."""
    tag = mesh.field_data[ring][0]
    nodes = np.unique(np.concatenate([c.data[mesh.cell_data["gmsh:physical"][i] == tag].ravel()
                                      for i, c in enumerate(mesh.cells) if c.type.startswith("triangle")]))
    return np.hypot(mesh.points[nodes, 0] - cx, mesh.points[nodes, 1] - cy).max()


if __name__ == "__main__":
    main()
