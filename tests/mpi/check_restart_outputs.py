#!/usr/bin/env python3
"""After a run killed and restarted in place (restart_case.sh): its traces, ParaView
series and fields continue the uninterrupted run's without gaps or repeats.
  check_restart_outputs.py REF OUT [--same-fields]
- trace_iterations.jsonl: the same (step, iteration) sequence as REF's (the killed run's
  lines after its checkpoint were cut away, the restarted run's appended once);
- trace_units.jsonl: the same (step, iteration, unit) records, as a multiset;
- displacement.pvd: the same time steps, each VTU present;
- --same-fields: every displacement_*.vtu byte-identical to REF's (one coordinator)."""
import json
import os
import sys
import xml.etree.ElementTree as ET


def lines(path):
    with open(path) as f:
        return [json.loads(line) for line in f if line.strip()]


def main():
    ref, out = sys.argv[1], sys.argv[2]
    same_fields = "--same-fields" in sys.argv[3:]
    ok = True

    a = [(r["step"], r["iteration"]) for r in lines(f"{ref}/trace_iterations.jsonl")]
    b = [(r["step"], r["iteration"]) for r in lines(f"{out}/trace_iterations.jsonl")]
    print(f"trace_iterations: {len(a)} lines in the reference, {len(b)} after the restart")
    if a != b:
        print("  the (step, iteration) sequences differ")
        ok = False

    ua = sorted((r["step"], r["iteration"], r["unit"]) for r in lines(f"{ref}/trace_units.jsonl"))
    ub = sorted((r["step"], r["iteration"], r["unit"]) for r in lines(f"{out}/trace_units.jsonl"))
    print(f"trace_units: {len(ua)} records in the reference, {len(ub)} after the restart")
    if ua != ub:
        print("  the (step, iteration, unit) records differ")
        ok = False

    def series(d):
        root = ET.parse(f"{d}/displacement.pvd").getroot()
        return [(float(e.get("timestep")), e.get("file")) for e in root.iter("DataSet")]

    sa, sb = series(ref), series(out)
    print(f"displacement.pvd: {len(sa)} steps in the reference, {len(sb)} after the restart")
    if sa != sb:
        print(f"  the series differ: {sa} vs {sb}")
        ok = False
    for _, f in sb:
        if not os.path.exists(f"{out}/{f}"):
            print(f"  {f} is listed but missing")
            ok = False
        elif same_fields:
            with open(f"{ref}/{f}", "rb") as x, open(f"{out}/{f}", "rb") as y:
                if x.read() != y.read():
                    print(f"  {f} differs from the reference's")
                    ok = False
    print("PASS" if ok else "FAIL")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
