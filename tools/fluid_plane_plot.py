#!/usr/bin/python3
"""Blood velocity on a plane through the cavity, at chosen moments of a run with a fluid.

  /usr/bin/python3 tools/fluid_plane_plot.py OUT_DIR [--plane y=0] [--png FILE]
                   [--at end_of_filling peak_ejection | --at 0.78 0.95]

OUT_DIR is a `fe2heart run` folder with VTU output (displacement.pvd) and summary.json.
Each panel is the plane's in-plane speed (colour) and direction (arrows of one length),
sampled on a grid: each grid point is located in a fluid tetrahedron at its current
position (reference point + displacement, which on the fluid is the ALE mesh
displacement; vertices only) and the velocity interpolated with the element's own basis
(quadratic on 10-node tets). Moments:
  end_of_filling  the last output with blood entering by the inflow ring (flux:<inflow> < 0)
  peak_ejection   the output nearest the largest outflow through the outflow ring
  a number        the output nearest that time (s)
The inflow and outflow rings are the valve faces named in the run's spec (side inflow /
outflow), else --inflow / --outflow.
"""
import argparse
import json
import os
import sys
import xml.etree.ElementTree as ET

import numpy as np


def outputs(folder):
    tree = ET.parse(os.path.join(folder, "displacement.pvd"))
    return [(float(d.get("timestep")), os.path.join(folder, d.get("file"))) for d in tree.iter("DataSet")]


def valve_rings(folder):
    """(inflow, outflow) face names of the spec's valve rings, or (None, None)."""
    try:
        spec = json.load(open(os.path.join(folder, "spec.json")))
    except OSError:
        return None, None
    rings = {b.get("side"): b.get("set") for b in spec.get("fluid", {}).get("boundaries", []) if b.get("kind") == "valve"}
    return rings.get("inflow"), rings.get("outflow")


def moment_times(summary, moments, inflow, outflow):
    history = [h for h in summary["history"] if "observables" in h]
    t = np.array([h["time"] for h in history])
    q = lambda name: np.array([h["observables"].get("flux:" + name, 0.0) for h in history])
    times = []
    for m in moments:
        try:
            times.append((m, float(m)))
            continue
        except ValueError:
            pass
        if m not in ("end_of_filling", "peak_ejection"):
            sys.exit(f"fluid_plane_plot.py: --at {m}: expected end_of_filling, peak_ejection or a time (s)")
        if not outflow or (m == "end_of_filling" and not inflow):
            sys.exit("fluid_plane_plot.py: the run has no valve rings; name them with --inflow/--outflow")
        q_out = q(outflow)
        k_peak = int(np.argmax(q_out))
        if m == "peak_ejection":
            times.append(("peak ejection", t[k_peak]))
            continue
        filling = np.nonzero(q(inflow) < -1e-3 * max(1.0, abs(q_out[k_peak])))[0]
        if len(filling) == 0:
            sys.exit("fluid_plane_plot.py: no filling in this run")
        times.append(("end of filling", t[filling[-1]]))
    return times


# VTK tetra10's edge nodes: (0,1), (1,2), (0,2), (0,3), (1,3), (2,3).
EDGES = [(0, 1), (1, 2), (0, 2), (0, 3), (1, 3), (2, 3)]


def basis(lam, n):
    """Shape function values at barycentric lam of a 4- or 10-node tet."""
    if n == 4:
        return lam
    return np.concatenate([lam * (2 * lam - 1), [4 * lam[a] * lam[b] for a, b in EDGES]])


def sample_plane(vtu, axis, level, region, n=90):
    import meshio

    m = meshio.read(vtu)
    cells = next(c for c in m.cells if c.type.startswith("tetra"))
    regions = np.asarray(m.cell_data["region"][0]).ravel()
    elements = cells.data[regions == region]
    tets = elements[:, :4]
    x = m.points + m.point_data["displacement"]
    v = m.point_data["fluid_velocity"]
    inplane = [i for i in range(3) if i != axis]
    # Tets cut by the plane, and a grid over their extent.
    lo, hi = x[tets][:, :, axis].min(axis=1), x[tets][:, :, axis].max(axis=1)
    keep = (lo <= level) & (hi >= level)
    cut, cut_elements = tets[keep], elements[keep]
    pts = x[cut].reshape(-1, 3)
    a = np.linspace(pts[:, inplane[0]].min(), pts[:, inplane[0]].max(), n)
    b = np.linspace(pts[:, inplane[1]].min(), pts[:, inplane[1]].max(), n)
    A, B = np.meshgrid(a, b)
    P = np.zeros((A.size, 3))
    P[:, axis] = level
    P[:, inplane[0]] = A.ravel()
    P[:, inplane[1]] = B.ravel()
    V = np.full((A.size, 3), np.nan)
    # Barycentric coordinates of every grid point in every cut tet (chunked).
    X0 = x[cut[:, 0]]
    T = np.stack([x[cut[:, k]] - X0 for k in (1, 2, 3)], axis=2)  # (t, 3, 3)
    Tinv = np.linalg.inv(T)
    for s in range(0, len(P), 512):
        d = P[s:s + 512, None, :] - X0[None, :, :]
        lam = np.einsum("tij,ptj->pti", Tinv, d)
        l0 = 1.0 - lam.sum(axis=2)
        inside = (lam.min(axis=2) >= -1e-9) & (l0 >= -1e-9)
        for p in np.nonzero(inside.any(axis=1))[0]:
            t = np.nonzero(inside[p])[0][0]
            V[s + p] = basis(np.concatenate([[l0[p, t]], lam[p, t]]), cut_elements.shape[1]) @ v[cut_elements[t]]
    return A, B, V[:, inplane[0]].reshape(A.shape), V[:, inplane[1]].reshape(A.shape), "xyz"[inplane[0]], "xyz"[inplane[1]]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("folder", help="a fe2heart run folder with VTU output")
    parser.add_argument("--plane", default="y=0", help="axis=level of the plane (default y=0)")
    parser.add_argument("--at", nargs="+", default=["end_of_filling", "peak_ejection"], help="moments (see above)")
    parser.add_argument("--region", type=int, default=2, help="region tag of the fluid (default 2)")
    parser.add_argument("--inflow", help="the inflow ring's face set (default: the spec's inflow valve)")
    parser.add_argument("--outflow", help="the outflow ring's face set (default: the spec's outflow valve)")
    parser.add_argument("--png", help="output file (default FOLDER/fluid_plane.png)")
    args = parser.parse_args()
    try:
        axis_name, level = args.plane.split("=")
        axis, level = "xyz".index(axis_name.strip()), float(level)
    except ValueError:
        sys.exit(f"fluid_plane_plot.py: --plane {args.plane}: expected axis=level, e.g. y=0")
    if not os.path.exists(os.path.join(args.folder, "displacement.pvd")):
        sys.exit(f"fluid_plane_plot.py: {args.folder}: no displacement.pvd (run with output.vtu true)")
    inflow, outflow = valve_rings(args.folder)
    inflow, outflow = args.inflow or inflow, args.outflow or outflow
    summary = json.load(open(os.path.join(args.folder, "summary.json")))
    series = outputs(args.folder)
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    moments = moment_times(summary, args.at, inflow, outflow)
    fig, axes = plt.subplots(1, len(moments), figsize=(5.2 * len(moments), 6.2), squeeze=False)
    for ax, (label, t) in zip(axes[0], moments):
        t_out, vtu = min(series, key=lambda s: abs(s[0] - t))
        A, B, Va, Vb, na, nb = sample_plane(vtu, axis, level, args.region)
        speed = np.hypot(Va, Vb)
        im = ax.pcolormesh(A, B, speed, shading="auto", cmap="viridis")
        k = max(1, A.shape[0] // 24)
        with np.errstate(invalid="ignore", divide="ignore"):
            ua, ub = Va / speed, Vb / speed  # direction only: the colour is the speed
        ax.quiver(A[::k, ::k], B[::k, ::k], ua[::k, ::k], ub[::k, ::k], color="w", pivot="mid", width=0.004,
                  scale_units="xy", scale=1.0 / (0.8 * k * (A[0, 1] - A[0, 0])))
        ax.set_aspect("equal")
        ax.set_title(f"{label}: t = {t_out:.3f} s")
        ax.set_xlabel(f"{na} (mm)")
        ax.set_ylabel(f"{nb} (mm)")
        fig.colorbar(im, ax=ax, label="in-plane speed (mm/s)", shrink=0.8)
    fig.suptitle(f"blood velocity on the plane {args.plane}")
    fig.tight_layout()
    png = args.png or os.path.join(args.folder, "fluid_plane.png")
    fig.savefig(png, dpi=110)
    print(png)


if __name__ == "__main__":
    main()
