#!/usr/bin/env bash
# A run that fails writes what it can and says why (issue 29 §6):
#   failed_run_output.sh FE2HEART SPEC OUT
# SPEC must fail after some converged steps with cavities (the coarse P2/P1 ellipsoid).
# Requires: exit 3; summary.json has converged false and the error names the cause
# (formulation.pressure "P1+P0"); pv_curve.png is drawn from the converged steps; and
# the log blames no missing matplotlib (the failed step's entry, which has no volumes,
# used to break the plot script, and the warning guessed matplotlib was missing).
set -uo pipefail
fe2heart=$1 spec=$2 out=$3
[[ "$out" == */cli_out/* ]] || { echo "OUT '$out' must contain /cli_out/"; exit 1; }
rm -rf "$out"
"$fe2heart" run "$spec" --out "$out" > /dev/null 2>&1
rc=$?
fail=0
((rc == 3)) || { echo "FAIL: exit $rc, expected 3"; fail=1; }
[[ -s "$out/pv_curve.png" ]] || { echo "FAIL: no pv_curve.png"; fail=1; }
if grep -q "python3-matplotlib\|no pv_curve" "$out/fe2heart.log"; then
  echo "FAIL: the log says:"; grep "python3-matplotlib\|no pv_curve" "$out/fe2heart.log"; fail=1
fi
grep -q 'run stopped: .*formulation.pressure "P1+P0" holds every element' "$out/fe2heart.log" ||
  { echo "FAIL: the log's error does not name the pressure space"; fail=1; }
/usr/bin/python3 - "$out" <<'PY' || fail=1
import json, sys
s = json.load(open(f"{sys.argv[1]}/summary.json"))
bad = []
if s.get("converged") is not False: bad.append("'converged' is not false")
if "P1+P0" not in s.get("error", ""): bad.append(f"error does not name P1+P0: {s.get('error')!r}")
print(f"summary.json: converged={s.get('converged')} steps={s.get('steps')}")
for b in bad: print("FAIL:", b)
sys.exit(1 if bad else 0)
PY
((fail == 0)) && echo PASS
exit $fail
