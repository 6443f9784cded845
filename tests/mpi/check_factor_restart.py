#!/usr/bin/python3
"""What the first iteration after a restart refactored (output.checkpoint_factors).

    check_factor_restart.py OUT STEP factors|flag [--compare FARM_CHECK REF]

STEP is the first step the restarted run computed (trace numbering). With `factors` the
checkpoint carried every unit's factor: no unit refreshes or rebuilds in that step's
first iteration, and summary.json counts no rebuild. With `flag` it carried only the
matrices: every unit rebuilds its factor there (none refreshes: the policy reuses), and
summary.json's factor_memory.rebuilds counts exactly those. --compare first runs
`FARM_CHECK compare REF OUT 0` (the same answer, bit for bit).
"""
import json
import subprocess
import sys

out, step, mode = sys.argv[1], int(sys.argv[2]), sys.argv[3]
if sys.argv[4:5] == ["--compare"]:
    if subprocess.run([sys.argv[5], "compare", sys.argv[6], out, "0"]).returncode != 0:
        sys.exit(1)
summary = json.load(open(f"{out}/summary.json"))
points = summary["points"]
rows = [json.loads(line) for line in open(f"{out}/trace_units.jsonl")]
first = [r for r in rows if r["step"] == step and r["iteration"] == 1]
rebuilt = sum(r["factor_rebuilt"] for r in first)
refreshed = sum(r["kind"] == "refresh" for r in first)
total = summary["factor_memory"]["rebuilds"]
print(f"step {step}, iteration 1: {len(first)} jobs, {refreshed} refreshes, {rebuilt} factor rebuilds; "
      f"summary factor_memory.rebuilds {total}; {points} points")
expected = 0 if mode == "factors" else points
ok = len(first) == points and refreshed == 0 and rebuilt == expected and total == expected
print("PASS" if ok else f"FAIL: expected {points} jobs, 0 refreshes, {expected} rebuilds (trace and summary)")
sys.exit(0 if ok else 1)
