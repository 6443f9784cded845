#!/usr/bin/python3
"""Compares the output.units files of two runs: the same unit_*.pvd / unit_*_*.vtu names
in REF/units and OUT/units, the same number of values in every DataArray, and every
value equal to TOL times the largest magnitude of its array (each VTU's point and cell
data: displacement, fluctuation, P, det_F, active_tension, region).

    compare_unit_files.py REF OUT TOL [MIN_FILES]

Exits 1 on a difference (naming file, array and the worst difference), 2 on unreadable
input. Standard library only."""
import os
import re
import sys


def arrays(path):
    text = open(path).read()
    out = {}
    for m in re.finditer(r'<DataArray([^>]*)>(.*?)</DataArray>', text, re.S):
        name = re.search(r'Name="([^"]*)"', m.group(1))
        out[name.group(1) if name else "points"] = [float(x) for x in m.group(2).split()]
    return out


def main():
    if len(sys.argv) < 4:
        print(__doc__)
        return 2
    ref, out, tol = sys.argv[1], sys.argv[2], float(sys.argv[3])
    min_files = int(sys.argv[4]) if len(sys.argv) > 4 else 1
    try:
        names = sorted(os.listdir(os.path.join(ref, "units")))
        other = sorted(os.listdir(os.path.join(out, "units")))
    except OSError as e:
        print(f"cannot list the units folders: {e}")
        return 2
    if names != other:
        print(f"different unit files: {names} vs {other}")
        return 1
    vtus = [n for n in names if n.endswith(".vtu")]
    if len(vtus) < min_files:
        print(f"only {len(vtus)} unit VTU files in {ref}/units, expected at least {min_files}")
        return 1
    worst = 0.0
    for n in vtus:
        a, b = arrays(os.path.join(ref, "units", n)), arrays(os.path.join(out, "units", n))
        if sorted(a) != sorted(b):
            print(f"{n}: arrays {sorted(a)} vs {sorted(b)}")
            return 1
        for key in a:
            x, y = a[key], b[key]
            if len(x) != len(y) or not x:
                print(f"{n} {key}: {len(x)} vs {len(y)} values")
                return 1
            scale = max(max(abs(v) for v in x), 1e-300)
            d = max(abs(p - q) for p, q in zip(x, y)) / scale
            worst = max(worst, d)
            if d > tol:
                print(f"{n} {key}: relative difference {d:.3e} > {tol:g}")
                return 1
    for n in names:
        if n.endswith(".pvd") and open(os.path.join(ref, "units", n)).read() != open(os.path.join(out, "units", n)).read():
            print(f"{n}: the series differ")
            return 1
    print(f"{len(vtus)} unit files agree: worst relative difference {worst:.3e} (tolerance {tol:g})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
