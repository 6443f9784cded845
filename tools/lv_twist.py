#!/usr/bin/python3
"""The rotation of a beat's probes about the heart's long axis, step by step: the
apical and basal rotation and the LV twist that echocardiography reports (speckle
tracking), read from a run's probes.

Angles are seen from the apex, counterclockwise positive (the echocardiographic
convention: in systole a human apex turns counterclockwise by about 10–15°, the base
clockwise by a few degrees). The axis runs from the apex to the base: --axis-point and
--axis-direction, by default the z axis through the origin pointing to the base (the
LV generator's ellipsoid, `mesh.kind` "lv").

    lv_twist.py SPEC SUMMARY [--probes a,b,...] [--axis-point x,y,z] [--axis-direction x,y,z]
                [--json OUT]

prints, for each probe, its rotation at every step and its extreme over the run, and
with --json writes {"time": [...], "rotation_deg": {probe: [...]}, "extreme_deg": {...}}.
The probes' reference positions are the spec's `probes`; their deformed positions are
summary.json's history[*].probes."""
import argparse
import json
import math
import sys


def vector(text, key):
    try:
        v = [float(c) for c in text.split(",")]
    except ValueError:
        v = []
    if len(v) != 3:
        sys.exit(f"lv_twist.py: {key} must be three comma-separated numbers, got '{text}'")
    return v


def rotation_deg(reference, deformed, point, axis):
    """Signed angle (degrees, seen from the apex, counterclockwise positive) between the
    projections of reference and deformed, taken from the axis, on the plane normal to it."""
    def radial(x):
        d = [x[i] - point[i] for i in range(3)]
        along = sum(d[i] * axis[i] for i in range(3))
        return [d[i] - along * axis[i] for i in range(3)]
    a, b = radial(reference), radial(deformed)
    cross = [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
    about_axis = math.degrees(math.atan2(sum(cross[i] * axis[i] for i in range(3)), sum(a[i] * b[i] for i in range(3))))
    return -about_axis  # the axis points to the base; seen from the apex the sense flips


def twist(spec, summary, names, point, axis):
    probes = spec.get("probes", {})
    names = names or sorted(probes)
    for n in names:
        if n not in probes:
            sys.exit(f"lv_twist.py: probe '{n}' is not among the spec's probes {sorted(probes)}")
    hist = summary.get("history", [])
    if not hist:
        sys.exit("lv_twist.py: summary.json has no history (no step was run)")
    norm = math.sqrt(sum(c * c for c in axis))
    if norm == 0.0:
        sys.exit("lv_twist.py: --axis-direction is the zero vector")
    axis = [c / norm for c in axis]
    for n in names:
        r = [probes[n][i] - point[i] for i in range(3)]
        off = math.sqrt(max(0.0, sum(c * c for c in r) - sum(r[i] * axis[i] for i in range(3)) ** 2))
        if off < 1e-9 * max(1.0, math.sqrt(sum(c * c for c in r))):
            sys.exit(f"lv_twist.py: probe '{n}' at {probes[n]} lies on the axis: it has no rotation")
    for h in hist:
        missing = [n for n in names if n not in h.get("probes", {})]
        if missing:
            sys.exit(f"lv_twist.py: step {h.get('step', '?')} of the summary has no position for probe(s) "
                     f"{missing}: was it run with this spec?")
    times = [h["time"] for h in hist]
    rot = {n: [rotation_deg(probes[n], h["probes"][n], point, axis) for h in hist] for n in names}
    extreme = {n: max(v, key=abs) for n, v in rot.items()}
    return {"time": times, "rotation_deg": rot, "extreme_deg": extreme}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("spec")
    ap.add_argument("summary")
    ap.add_argument("--probes", default="", help="comma-separated probe names (default: all)")
    ap.add_argument("--axis-point", default="0,0,0")
    ap.add_argument("--axis-direction", default="0,0,1")
    ap.add_argument("--json", default="")
    a = ap.parse_args()
    try:
        spec = json.load(open(a.spec))
        summary = json.load(open(a.summary))
    except (OSError, json.JSONDecodeError) as e:
        sys.exit(f"lv_twist.py: {e}")
    names = [n for n in a.probes.split(",") if n]
    result = twist(spec, summary, names, vector(a.axis_point, "--axis-point"),
                   vector(a.axis_direction, "--axis-direction"))
    names = list(result["rotation_deg"])
    print("time (s)  " + "  ".join(f"{n:>12}" for n in names))
    for i, t in enumerate(result["time"]):
        print(f"{t:8.3f}  " + "  ".join(f"{result['rotation_deg'][n][i]:12.2f}" for n in names))
    print("extreme   " + "  ".join(f"{result['extreme_deg'][n]:12.2f}" for n in names))
    if a.json:
        with open(a.json, "w") as f:
            json.dump(result, f, indent=1)


if __name__ == "__main__":
    main()
