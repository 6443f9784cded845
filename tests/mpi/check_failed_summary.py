#!/usr/bin/python3
"""check_failed_summary.py SUMMARY STEPS TEXT: the summary.json of a run that failed is
final: "complete": true, "converged": false, STEPS steps done, and an error holding TEXT."""
import json
import sys

path, steps, text = sys.argv[1], int(sys.argv[2]), sys.argv[3]
s = json.load(open(path))
print(f"{path}: complete={s.get('complete')} converged={s.get('converged')} steps={s.get('steps')} "
      f"error={s.get('error')!r}")
fail = []
if s.get("complete") is not True: fail.append("'complete' is not true")
if s.get("converged") is not False: fail.append("'converged' is not false")
if s.get("steps") != steps: fail.append(f"steps {s.get('steps')}, expected {steps}")
if text not in s.get("error", ""): fail.append(f"'error' does not contain {text!r}")
for f in fail: print("FAIL:", f)
sys.exit(1 if fail else 0)
