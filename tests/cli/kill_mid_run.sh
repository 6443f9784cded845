#!/usr/bin/env bash
# A run killed with SIGKILL keeps what it did (issue 7, items 8 and 9):
#   kill_mid_run.sh FE2HEART SPEC OUT
# Starts `run SPEC --out OUT`, waits until summary.json reports 3 finished steps,
# kills the process with SIGKILL, then requires: summary.json parses, says
# "complete": false and "converged": false, and holds 3 <= steps < time.steps with one
# history entry per step; fe2heart.log has the "step k/N" line of each of those steps.
set -uo pipefail
fe2heart=$1 spec=$2 out=$3
[[ "$out" == */cli_out/* ]] || { echo "OUT '$out' must contain /cli_out/"; exit 1; }
rm -rf "$out"
"$fe2heart" run "$spec" --out "$out" &
pid=$!
for _ in $(seq 1 600); do  # up to 60 s
  grep -Eqs '"steps": ([3-9]|[1-9][0-9])' "$out/summary.json" && break
  kill -0 "$pid" 2>/dev/null || break
  sleep 0.1
done
kill -9 "$pid" 2>/dev/null
wait "$pid" 2>/dev/null
rc=$?
if ((rc != 128 + 9)); then
  echo "FAIL: the run ended with exit $rc before it could be killed mid-way (make its steps slower)"
  exit 1
fi
echo "killed pid $pid with SIGKILL"
exec /usr/bin/python3 - "$out" <<'PY'
import json, re, sys
out = sys.argv[1]
s = json.load(open(f"{out}/summary.json"))
total = json.load(open(f"{out}/spec.json"))["time"]["steps"]
log = open(f"{out}/fe2heart.log").read()
print(f"summary.json: complete={s['complete']} converged={s['converged']} steps={s['steps']} of {total}, "
      f"{len(s['history'])} history entries; fe2heart.log: {len(log.splitlines())} lines")
fail = []
if s["complete"] is not False: fail.append("'complete' is not false")
if s["converged"] is not False: fail.append("'converged' is not false")
if not 3 <= s["steps"] < total: fail.append(f"steps {s['steps']} not in [3, {total})")
if [h["step"] for h in s["history"]] != list(range(s["steps"])):
    fail.append(f"history steps {[h['step'] for h in s['history']]}, expected 0..{s['steps'] - 1}")
for k in range(1, s["steps"] + 1):
    if not re.search(rf"step +{k}/{total} ", log): fail.append(f"fe2heart.log has no line for step {k}/{total}")
for f in fail: print("FAIL:", f)
print("PASS" if not fail else "")
sys.exit(1 if fail else 0)
PY
