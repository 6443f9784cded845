#!/usr/bin/env python3
"""A run with unit.solver.refresh "collective" (coordinator/farm/CollectiveRefresh.h):
  check_collective.py REF OUT TOL GROUPS MIN_COLLECTIVE MAX_REFRESH_RATIO
- trace_units.jsonl: in every (step, iteration) the units that refreshed are a union of
  whole GROUPS (the models' units, "0-5,6-17"): a model's units refresh together or not at
  all, never alone (the first iteration, where no unit has a factor, refreshes all);
- summary.json: at least MIN_COLLECTIVE collective refreshes, and at most MAX_REFRESH_RATIO
  times the unit refreshes of REF (a run that refactors every unit at every iteration);
- its probes agree with REF's to TOL times the largest probe displacement (both runs
  converge to newton.rtol; kept factors change the path, not the answer)."""
import json
import sys
from collections import defaultdict


def lines(path):
    with open(path) as f:
        return [json.loads(line) for line in f if line.strip()]


def parse_groups(text):
    groups = []
    for part in text.split(","):
        lo, hi = (int(x) for x in part.split("-"))
        groups.append(set(range(lo, hi + 1)))
    return groups


def main():
    ref, out, tol = sys.argv[1], sys.argv[2], float(sys.argv[3])
    groups, min_collective = parse_groups(sys.argv[4]), int(sys.argv[5])
    max_ratio = float(sys.argv[6])
    ok = True

    refreshed = defaultdict(set)
    for r in lines(f"{out}/trace_units.jsonl"):
        key = (r["step"], r["iteration"])
        refreshed.setdefault(key, set())
        if r["kind"] == "refresh":
            refreshed[key].add(r["unit"])
    partial = []
    for key, units in sorted(refreshed.items()):
        for g in groups:
            if units & g and not g <= units:
                partial.append((key, sorted(units & g)))
    print(f"trace_units: {len(refreshed)} iterations; "
          f"{sum(1 for u in refreshed.values() if u)} with refreshes; "
          f"{len(partial)} where part of a model refreshed")
    for key, units in partial[:5]:
        print(f"  step {key[0]} iteration {key[1]}: only units {units} of their model")
    ok = ok and not partial

    s_ref = json.load(open(f"{ref}/summary.json"))
    s_out = json.load(open(f"{out}/summary.json"))
    print(f"collective_refreshes {s_out['collective_refreshes']} (at least {min_collective}); "
          f"unit refreshes {s_out['refreshes']} vs {s_ref['refreshes']} refactoring every iteration "
          f"(at most {max_ratio} of it); "
          f"Newton {s_out['newton_iterations']} vs {s_ref['newton_iterations']}")
    ok = ok and s_out["converged"] and s_out["collective_refreshes"] >= min_collective
    ok = ok and s_out["refreshes"] <= max_ratio * s_ref["refreshes"]

    spec = json.load(open(f"{ref}/spec.json"))
    scale = 0.0
    diff = 0.0
    for name, x0 in spec["probes"].items():
        a, b = s_ref["probes"][name], s_out["probes"][name]
        scale = max(scale, max(abs(a[i] - x0[i]) for i in range(3)))
        diff = max(diff, max(abs(a[i] - b[i]) for i in range(3)))
    print(f"probes: max difference {diff:.3e} of the largest probe displacement {scale:.3e} "
          f"(tolerance {tol:.1e})")
    ok = ok and diff <= tol * scale
    print("PASS" if ok else "FAIL")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
