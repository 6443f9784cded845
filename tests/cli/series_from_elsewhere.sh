#!/usr/bin/env bash
# ParaView series of a run started outside its output folder (issue 7, item 7):
#   series_from_elsewhere.sh FE2HEART SPEC WORKDIR
# Runs SPEC from WORKDIR with a relative --out two levels down, then reads the series
# back from / (check_series.py resolves each file against the .pvd, as ParaView does)
# and compares the last step's displacement at the probes with summary.json.
set -euo pipefail
fe2heart=$1 spec=$2 work=$3
here=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$work"
cd "$work"
rm -rf rel
"$fe2heart" run "$spec" --out rel/run --log-level warn
cd /
exec /usr/bin/python3 "$here/check_series.py" "$work/rel/run"
