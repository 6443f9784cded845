#!/usr/bin/python3
"""A run's trace_iterations.jsonl records the macro CPU of its coordinator group: every
iteration names COORDINATORS coordinators, the busiest one's CPU is at most the group's
sum, and with several coordinators the sum exceeds the busiest one's (each did macro work). With --blood (a scene with a fluid),
every iteration also records the blood's terms' assembly, within the whole assembly, and
the blood is most of it (its P2 blocks and shape derivatives against the wall's points).
    check_macro_cpu_trace.py RUN_DIR COORDINATORS [--blood]"""
import json
import sys

run, coordinators = sys.argv[1], int(sys.argv[2])
blood = "--blood" in sys.argv[3:]
rows = [json.loads(line) for line in open(f"{run}/trace_iterations.jsonl") if line.strip()]
bad = [r for r in rows if r["coordinators"] != coordinators or not 0 < r["macro_cpu_max"] <= r["macro_cpu_sum"]]
shared = sum(r["macro_cpu_sum"] > 1.2 * r["macro_cpu_max"] for r in rows)
print(f"{len(rows)} iterations; {len(bad)} inconsistent; {shared} with the group's macro CPU above 1.2x its busiest's")
if bad:
    sys.exit(f"inconsistent macro CPU records, e.g. {bad[0]}")
if coordinators > 1 and shared < len(rows) // 2:
    sys.exit("the coordinators' macro CPU is not summed over the group")
if blood:
    bad = [r for r in rows if not 0 < r.get("assemble_fluid", 0) <= r["assemble"]]
    fluid = sum(r.get("assemble_fluid", 0) for r in rows)
    share = fluid / sum(r["assemble"] for r in rows)
    print(f"the blood's terms: {fluid:.3g} s of assembly, {share:.3f} of it; {len(bad)} iterations without a record")
    if bad:  # checked first: a trace without the records fails here, naming an iteration
        sys.exit(f"iterations whose blood assembly is missing or above the whole assembly, e.g. {bad[0]}")
    if share < 0.5:
        sys.exit(f"the blood's share of the assembly {share:.3f}: expected most of it (> 0.5)")
