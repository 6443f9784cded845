#!/usr/bin/env bash
# A run killed and restarted from its checkpoint: run SPEC on NP1 ranks with
# FE2HEART_FAULT=KILL (a unit's rank kill -9s itself, as a dying node would), expect the
# job to die with a checkpoint left in OUT, then restart in place on NP2 ranks and run a
# farm_check command on the result. NP1 and NP2 are "ranks" or "ranks/coordinators".
#   restart_case.sh MPIEXEC FE2HEART SPEC OUT NP1 KILL NP2 -- farm_check args...
set -uo pipefail
mpiexec=$1 fe2heart=$2 spec=$3 out=$4 np1=$5 kill=$6 np2=$7
shift 8  # and --
launch() {  # "ranks[/coordinators]" -> mpirun and fe2heart arguments
  local n=${1%%/*} c=
  [[ $1 == */* ]] && c=${1##*/}
  echo "-n $n $fe2heart run $spec --out $out ${c:+--coordinators $c}"
}
rm -rf "$out"
# shellcheck disable=SC2046
FE2HEART_FAULT="$kill" timeout 300 "$mpiexec" $(launch "$np1") --log-level warn > "$out.first.log" 2>&1
rc=$?
if ((rc == 0)); then echo "the run on $np1 ranks was to be killed ($kill) but finished"; exit 1; fi
if [[ ! -f $out/checkpoint.bin ]]; then
  echo "the killed run (exit $rc) left no checkpoint.bin in $out:"; ls "$out"; cat "$out.first.log"; exit 1
fi
echo "first run killed as planned (exit $rc); checkpoint: $(stat -c %s "$out/checkpoint.bin") bytes"
# shellcheck disable=SC2046
timeout 300 "$mpiexec" $(launch "$np2") --restart "$out" --log-level info
rc=$?
if ((rc != 0)); then echo "the restart on $np2 ranks failed with exit $rc"; exit 1; fi
exec "$@"
