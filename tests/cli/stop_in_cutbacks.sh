#!/usr/bin/env bash
# A stop signal is honoured within seconds even while a step keeps cutting back
# (issue 29 §6): stop_in_cutbacks.sh FE2HEART SPEC OUT SIGNAL
# Starts `run SPEC --out OUT` on a step that never converges, waits for its second
# cut-back, sends SIGNAL (TERM or INT) and requires: the run exits 0 within 10 s,
# OUT/checkpoint.bin holds the committed state (t = 0, nothing converged yet: step 0 of
# the checkpoint), summary.json says "stopped" and "complete": false, and the log says
# which signal stopped it and that the step in progress was abandoned.
set -uo pipefail
fe2heart=$1 spec=$2 out=$3 sig=$4
[[ "$out" == */cli_out/* ]] || { echo "OUT '$out' must contain /cli_out/"; exit 1; }
rm -rf "$out"
"$fe2heart" run "$spec" --out "$out" > /dev/null 2>&1 &
pid=$!
for _ in $(seq 1 1200); do  # up to 120 s for two cut-backs
  (( $(grep -c "cutting the step" "$out/fe2heart.log" 2>/dev/null || echo 0) >= 2 )) && break
  kill -0 "$pid" 2>/dev/null || break
  sleep 0.1
done
if ! kill -0 "$pid" 2>/dev/null; then echo "FAIL: the run ended before it could be signalled"; exit 1; fi
sent=$(date +%s.%N)
kill "-$sig" "$pid"
for _ in $(seq 1 100); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
if kill -0 "$pid" 2>/dev/null; then
  echo "FAIL: still running 10 s after SIG$sig (a step in cut-backs must not hold a stop request)"
  kill -9 "$pid"; wait "$pid" 2>/dev/null; exit 1
fi
wait "$pid"
rc=$?
took=$(awk "BEGIN { printf \"%.1f\", $(date +%s.%N) - $sent }")
echo "SIG$sig after two cut-backs: exit $rc after ${took} s"
fail=0
((rc == 0)) || { echo "FAIL: exit $rc, expected 0"; fail=1; }
[[ -s "$out/checkpoint.bin" ]] || { echo "FAIL: no $out/checkpoint.bin"; fail=1; }
grep -q "stopped by signal SIG$sig after step 0" "$out/fe2heart.log" || { echo "FAIL: the log does not name SIG$sig"; fail=1; }
grep -q "the step in progress was abandoned" "$out/fe2heart.log" || { echo "FAIL: the log does not say the step was abandoned"; fail=1; }
/usr/bin/python3 - "$out" <<'PY' || fail=1
import json, sys
s = json.load(open(f"{sys.argv[1]}/summary.json"))
bad = []
if "stopped" not in s: bad.append("summary.json has no 'stopped'")
if s.get("complete") is not False: bad.append("'complete' is not false")
if s.get("steps") != 0: bad.append(f"steps {s.get('steps')}, expected 0")
for b in bad: print("FAIL:", b)
sys.exit(1 if bad else 0)
PY
((fail == 0)) && echo PASS
exit $fail
