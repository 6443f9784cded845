#!/usr/bin/python3
"""Where a pressure wave's front is along a tube, and how fast it travels, from a run's probes.

  /usr/bin/python3 tools/wave_front.py OUT_DIR [--prefix wall_z] [--level 0.5] [--json FILE]

OUT_DIR is a `fe2heart run` folder whose summary.json has probes in the tube's wall
(configs/tube-fsi.json: wall_z02 ... wall_z18, material points along a tube that runs
along z through the origin). A probe's height is its radial displacement (distance
from the z axis less the reference one). The front reaches a probe when its height
first passes --level times the wave's height, the largest height the first probe
reaches; the time is interpolated linearly between steps. Prints each probe's arrival,
the front's position at each step (the farthest probe reached, interpolated between
probes by their heights) and the speed: the least-squares slope of position against
arrival time. --json writes the same as JSON.
"""
import argparse
import json
import os
import sys

import numpy as np


def arrivals(summary, reference, prefix, level):
    # Along the tube from the inlet: by the probes' reference z, not their names.
    names = sorted((n for n in summary["probes"] if n.startswith(prefix)), key=lambda n: reference[n][2])
    if len(names) < 2:
        sys.exit(f"wave_front.py: {len(names)} probe(s) named {prefix}*: expected at least two along the tube")
    history = summary["history"]
    t = np.array([h["time"] for h in history])
    z = np.array([reference[n][2] for n in names])
    r0 = np.array([np.hypot(*reference[n][:2]) for n in names])
    # Heights per step and probe; before the first step the wall is at rest (t = 0).
    t = np.concatenate(([0.0], t))
    history = [{"probes": reference}] + history
    height = np.array([[np.hypot(*h["probes"][n][:2]) for n in names] for h in history]) - r0
    wave = height[:, 0].max()
    if not wave > 0:
        sys.exit(f"wave_front.py: the first probe {names[0]} never moves outward: no wave")
    threshold = level * wave
    arrive = []
    for j in range(len(names)):
        above = np.nonzero(height[:, j] >= threshold)[0]
        if len(above) == 0:
            arrive.append(None)
            continue
        k = above[0]
        h0, h1 = height[k - 1, j], height[k, j]
        arrive.append(float(t[k - 1] + (threshold - h0) / (h1 - h0) * (t[k] - t[k - 1])))
    return names, z, t, height, threshold, arrive


def front_positions(z, height, threshold):
    """Per step: the farthest point along the tube whose height has reached the threshold."""
    out = []
    for row in height:
        reached = np.nonzero(row >= threshold)[0]
        if len(reached) == 0:
            out.append(None)
            continue
        j = reached[-1]
        if j + 1 < len(z) and row[j] > row[j + 1]:
            # Between probe j (above) and j+1 (below): where the height crosses the threshold.
            f = (row[j] - threshold) / (row[j] - row[j + 1])
            out.append(float(z[j] + f * (z[j + 1] - z[j])))
        else:
            out.append(float(z[j]))
    return out


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("out", help="a fe2heart run folder")
    parser.add_argument("--prefix", default="wall_z", help="probe names along the tube (default wall_z)")
    parser.add_argument("--level", type=float, default=0.5, help="fraction of the wave's height that marks the front")
    parser.add_argument("--json", help="also write the arrivals, positions and speed to this file")
    args = parser.parse_args()
    if not 0.0 < args.level < 1.0:
        sys.exit(f"wave_front.py: --level {args.level}: expected a fraction in (0, 1)")
    path = os.path.join(args.out, "summary.json")
    try:
        summary = json.load(open(path))
    except (OSError, ValueError) as e:
        sys.exit(f"wave_front.py: {path}: {e}")
    # The probes' reference points are the spec's (summary.json holds where they went).
    try:
        reference = json.load(open(os.path.join(args.out, "spec.json")))["probes"]
    except (OSError, ValueError, KeyError) as e:
        sys.exit(f"wave_front.py: {os.path.join(args.out, 'spec.json')}: {e} (expected the run's spec with its probes)")
    names, z, t, height, threshold, arrive = arrivals(summary, reference, args.prefix, args.level)
    print(f"wave height {threshold / args.level:.4g} mm (largest at {names[0]}); front at {args.level:g} of it")
    for n, zj, a in zip(names, z, arrive):
        print(f"  {n}  z = {zj:6.2f} mm  arrives {'never' if a is None else f'{1e3 * a:.3f} ms'}")
    reached = [(zj, a) for zj, a in zip(z, arrive) if a is not None]
    speed = None
    if len(reached) >= 2:
        zs, ts = np.array(reached).T
        speed = float(np.polyfit(ts, zs, 1)[0])
        print(f"front speed {speed / 1e3:.3f} m/s (least squares over {len(reached)} probes)")
    positions = front_positions(z, height, threshold)
    print("front position per step:")
    for tk, p in zip(t[1:], positions[1:]):
        print(f"  t = {1e3 * tk:8.3f} ms  z = {'-' if p is None else f'{p:.2f} mm'}")
    if args.json:
        with open(args.json, "w") as f:
            json.dump({"threshold": threshold, "arrivals": dict(zip(names, arrive)), "speed": speed,
                       "front": [{"time": float(tk), "z": p} for tk, p in zip(t, positions)]}, f, indent=1)


if __name__ == "__main__":
    main()
