#!/usr/bin/python3
"""A run's trace_iterations.jsonl records the macro CPU of its coordinator group: every
iteration names COORDINATORS coordinators, the busiest one's CPU is at most the group's
sum, and with several coordinators the sum exceeds the busiest one's (each did macro work).
    check_macro_cpu_trace.py RUN_DIR COORDINATORS"""
import json
import sys

run, coordinators = sys.argv[1], int(sys.argv[2])
rows = [json.loads(line) for line in open(f"{run}/trace_iterations.jsonl") if line.strip()]
bad = [r for r in rows if r["coordinators"] != coordinators or not 0 < r["macro_cpu_max"] <= r["macro_cpu_sum"]]
shared = sum(r["macro_cpu_sum"] > 1.2 * r["macro_cpu_max"] for r in rows)
print(f"{len(rows)} iterations; {len(bad)} inconsistent; {shared} with the group's macro CPU above 1.2x its busiest's")
if bad:
    sys.exit(f"inconsistent macro CPU records, e.g. {bad[0]}")
if coordinators > 1 and shared < len(rows) // 2:
    sys.exit("the coordinators' macro CPU is not summed over the group")
