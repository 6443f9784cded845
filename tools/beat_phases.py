#!/usr/bin/python3
"""Cost of a coupled beat by circulation phase, from a run's summary.json.

For each phase of the first cavity (filling, isovolumic contraction, ejection,
isovolumic relaxation): steps, Newton iterations per step (median and max), wall seconds
per step (median) and unit refreshes per step (median). Shows the
systolic cost spike the task farm has to absorb.

    /usr/bin/python3 tools/beat_phases.py RUN_DIR
"""
import json
import os
import statistics
import sys


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    path = os.path.join(sys.argv[1], "summary.json")
    try:
        with open(path) as f:
            s = json.load(f)
    except (OSError, ValueError) as e:
        sys.exit(f"beat_phases: cannot read {path}: {e}")
    rows = {}
    order = []
    for h in s.get("history", []):
        circ = h.get("circulation") or {}
        if not circ:
            continue
        phase = next(iter(circ.values()))["phase"]
        if phase not in rows:
            rows[phase] = []
            order.append(phase)
        rows[phase].append(h)
    if not rows:
        sys.exit(f"beat_phases: {path} has no circulation phases (a run with a circulation?)")
    print(f"{'phase':24s} {'steps':>5s} {'Newton/step':>12s} {'max':>4s} {'wall s/step':>12s} "
          f"{'refreshes/step':>15s}")
    total = {"steps": 0, "iterations": 0, "wall": 0.0}
    for phase in order:
        hs = rows[phase]
        its = [h["iterations"] for h in hs]
        wall = [h.get("wall_seconds", 0.0) for h in hs]
        ref = [h.get("refreshes", 0) for h in hs]
        print(f"{phase:24s} {len(hs):5d} {statistics.median(its):12.1f} {max(its):4d} "
              f"{statistics.median(wall):12.3f} {statistics.median(ref):15.1f}")
        total["steps"] += len(hs)
        total["iterations"] += sum(its)
        total["wall"] += sum(wall)
    print(f"{'all':24s} {total['steps']:5d} {total['iterations'] / total['steps']:12.2f} "
          f"{'':4s} {total['wall'] / total['steps']:12.3f}   (means; {total['wall']:.1f} s of steps)")


if __name__ == "__main__":
    main()
