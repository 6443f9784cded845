#!/usr/bin/env bash
# One task-farm case: run SPEC on NP ranks into OUT (extra fe2heart args after --),
# then run a farm_check command on the result.
#   run_case.sh MPIEXEC FE2HEART NP SPEC OUT [fe2heart args...] -- farm_check args...
set -uo pipefail
mpiexec=$1 fe2heart=$2 np=$3 spec=$4 out=$5
shift 5
args=()
while (($#)) && [[ $1 != -- ]]; do args+=("$1"); shift; done
shift  # --
rm -rf "$out"
timeout 300 "$mpiexec" -n "$np" "$fe2heart" run "$spec" --out "$out" --log-level warn "${args[@]}"
rc=$?
if ((rc != 0)); then echo "fe2heart run on $np ranks failed with exit $rc"; exit 1; fi
exec "$@"
