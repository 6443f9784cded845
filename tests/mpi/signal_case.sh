#!/usr/bin/env bash
# A batch system's stop request: start SPEC on NP ranks, and once a step is done send
# SIGNAL to every fe2heart rank (as Slurm signals every task). The run must write a
# checkpoint at the next step boundary, say so, and exit 0 with an incomplete summary;
# a restart on NP2 ranks then runs to the end, and a farm_check command judges it.
# SIGNAL "FILE": the run is given --stop-file OUT.stop, and that file is written instead.
#   signal_case.sh MPIEXEC FE2HEART SPEC OUT NP SIGNAL NP2 -- farm_check args...
set -uo pipefail
mpiexec=$1 fe2heart=$2 spec=$3 out=$4 np=$5 signal=$6 np2=$7
shift 7
shift  # --
rm -rf "$out" "$out.stop"
mkdir -p "$out"
log=$out.first.log
stop_file=()
[[ $signal == FILE ]] && stop_file=(--stop-file "$out.stop")
"$mpiexec" -n "$np" "$fe2heart" run "$spec" --out "$out" --log-level info "${stop_file[@]}" > "$log" 2>&1 &
job=$!
# Wait for the first finished step (summary.json says "steps": >= 1).
for ((i = 0; i < 600; ++i)); do
  grep -Eq '"steps": [1-9]' "$out/summary.json" 2>/dev/null && break
  kill -0 "$job" 2>/dev/null || break
  sleep 0.2
done
ranks=()
for p in $(pgrep -f -- "--out $out( |$)"); do
  [[ $(cat "/proc/$p/comm" 2>/dev/null) == fe2heart ]] && ranks+=("$p")
done
if ((${#ranks[@]} != np)); then echo "found ${#ranks[@]} fe2heart ranks, expected $np"; cat "$log"; exit 1; fi
if [[ $signal == FILE ]]; then
  echo stop > "$out.stop"
  expected="stopped by the stop file $out.stop"
else
  kill -s "$signal" "${ranks[@]}"
  expected="stopped by signal SIG$signal"
fi
timeout 300 tail --pid="$job" -f /dev/null
wait "$job"
rc=$?
cat "$log"
if ((rc != 0)); then echo "the signalled run exited $rc, expected 0"; exit 1; fi
grep -Eq "$expected after step [0-9]+" "$log" || { echo "no '$expected' in the log"; exit 1; }
grep -q '"stopped"' "$out/summary.json" || { echo "summary.json does not say the run stopped"; exit 1; }
grep -q '"complete": false' "$out/summary.json" || { echo "summary.json says complete"; exit 1; }
[[ -f $out/checkpoint.bin ]] || { echo "no checkpoint.bin"; exit 1; }
timeout 300 "$mpiexec" -n "$np2" "$fe2heart" run "$spec" --out "$out" --restart "$out" --log-level warn
rc=$?
if ((rc != 0)); then echo "the restart on $np2 ranks failed with exit $rc"; exit 1; fi
exec "$@"
