#!/usr/bin/python3
"""Reads a run's ParaView series back the way ParaView does and checks it.

    check_series.py RUN_DIR

The .pvd's file attributes are resolved against the .pvd's own folder (never the
working directory); every listed VTU must exist and be readable by meshio (a real VTK
XML reader). The last step's displacement, interpolated linearly in the tetrahedron
that holds each probe X of spec.json, must give X + u = summary.json's probe position
to 1e-10. Also: one series entry per step plus the initial state, the last entry's
time equals summary.json's, and the run moved the probes (so the check is not 0 = 0).
Exit 0 on success, 1 with the reasons otherwise.
"""
import json
import os
import sys
import xml.etree.ElementTree as ET

import meshio
import numpy as np


def barycentric(tet, x):
    """Barycentric coordinates of x in the tetrahedron with vertex rows `tet`."""
    T = np.column_stack([tet[1] - tet[0], tet[2] - tet[0], tet[3] - tet[0]])
    b = np.linalg.solve(T, x - tet[0])
    return np.concatenate([[1.0 - b.sum()], b])


def main(run_dir):
    failures = []
    pvd = os.path.join(run_dir, "displacement.pvd")
    summary = json.load(open(os.path.join(run_dir, "summary.json")))
    spec = json.load(open(os.path.join(run_dir, "spec.json")))
    entries = [(float(d.get("timestep")), d.get("file")) for d in ET.parse(pvd).getroot().iter("DataSet")]
    print(f"{pvd}: {len(entries)} data sets: {[f for _, f in entries]}")
    if len(entries) != summary["steps"] + 1:
        failures.append(f"{len(entries)} data sets, expected steps + 1 = {summary['steps'] + 1}")
    meshes = []
    for t, f in entries:
        if os.path.isabs(f):
            failures.append(f"file attribute '{f}' is absolute: the folder could not be moved")
        path = os.path.join(os.path.dirname(pvd), f)  # what ParaView opens
        if not os.path.isfile(path):
            failures.append(f"file attribute '{f}' resolves to '{path}' (relative to the .pvd), "
                            "which does not exist")
            continue
        meshes.append(meshio.read(path))
    if failures:
        return failures
    if abs(entries[-1][0] - summary["time"]) > 1e-12:
        failures.append(f"last data set at t = {entries[-1][0]}, summary.json time {summary['time']}")
    last = meshes[-1]
    points = np.asarray(last.points)
    u = np.asarray(last.point_data["displacement"])
    tets = last.cells_dict["tetra"]
    for name, X in spec["probes"].items():
        X = np.asarray(X, dtype=float)
        for tet in tets:
            b = barycentric(points[tet], X)
            if b.min() >= -1e-12:
                break
        else:
            failures.append(f"probe '{name}' {X} lies in no tetrahedron")
            continue
        x = X + b @ u[tet]
        expected = np.asarray(summary["probes"][name])
        err = np.abs(x - expected).max()
        moved = np.abs(expected - X).max()
        print(f"probe {name}: X + u from the VTU {x.tolist()}, summary.json {expected.tolist()}, "
              f"difference {err:.3e}, displacement {moved:.3e}")
        if not err <= 1e-10:
            failures.append(f"probe '{name}': X + u = {x.tolist()} from the last VTU differs from "
                            f"summary.json's {expected.tolist()} by {err:.3e} (> 1e-10)")
        if not moved > 1e-4:
            failures.append(f"probe '{name}' moved only {moved:.3e}: the comparison would be vacuous")
    return failures


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit("usage: check_series.py RUN_DIR")
    problems = main(sys.argv[1])
    for p in problems:
        print("FAIL:", p)
    print("PASS" if not problems else "")
    sys.exit(1 if problems else 0)
