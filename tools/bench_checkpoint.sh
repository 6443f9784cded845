#!/usr/bin/env bash
# Checkpoint cost at the paper's unit size: six FE² units of 27,780 DOF (two cells,
# 21^3 hexahedra, as `fe2heart bench unit`), two steps, a checkpoint after each; once
# with the rebuild flag (output.checkpoint_factors false: the matrix each factor was made
# of) and once with the CHOLMOD factors themselves (true).
#   tools/bench_checkpoint.sh [FE2HEART] [OUT]     (default build/tools/fe2heart, /tmp/fe2_bench_ckpt)
#   RESTART_ONLY=1 tools/bench_checkpoint.sh ...   only the restarts (OUT/*/full from an earlier run)
#   MODES="factors" tools/bench_checkpoint.sh ...  only some of: flag factors
# Prints per mode: checkpoint size (total, per unit), write time, and for a restart from
# the first checkpoint: the time to read and place every unit's state, and the CPU of the
# first iteration after it (factor rebuilds with the flag; none with factors), beside
# the same iteration of the uninterrupted run and one factorization per unit.
set -euo pipefail
top=$(cd "$(dirname "$0")/.." && pwd)
fe2=${1:-$top/build/tools/fe2heart}
out=${2:-/tmp/fe2_bench_ckpt}
export OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
for mode in ${MODES:-flag factors}; do
  dir=$out/$mode
  factors=false
  [[ $mode == factors ]] && factors=true
  [[ ${RESTART_ONLY:-} ]] || rm -rf "$dir"; rm -rf "$dir/restart"
  mkdir -p "$dir"
  cat > "$dir/spec.json" <<JSON
{
  "title": "Checkpoint benchmark: six two-cell units of 27,780 DOF",
  "mesh": {"kind": "box", "hi": [1, 1, 1], "divisions": [1, 1, 1]},
  "frame": {"kind": "constant"},
  "models": {"cells": {"kind": "fe2", "unit": {
    "cell": "two_cells", "size": [1.0, 1.0, 1.0], "resolution": [21, 21, 21],
    "materials": {"cell": {"model": "neo_hookean", "E": 100000, "nu": 0.45},
                  "ecm": {"model": "neo_hookean", "E": 10000, "nu": 0.45}}}}},
  "assign": {"default": "cells"},
  "dirichlet": [{"set": "xmin"}],
  "pressure": [{"surface": "xmax", "value": -2000}],
  "time": {"t_end": 1.0, "steps": 2},
  "output": {"vtu": false, "checkpoint_every": 1, "checkpoint_factors": $factors}
}
JSON
  [[ ${RESTART_ONLY:-} ]] || mpirun -n 1 "$fe2" run "$dir/spec.json" --out "$dir/full" --log-level info > "$dir/full.log" 2>&1
  mkdir -p "$dir/restart"
  cp "$dir/full/checkpoint.bin.previous" "$dir/restart/checkpoint.bin"
  sync
  mpirun -n 1 "$fe2" run "$dir/spec.json" --out "$dir/restart" --restart "$dir/restart/checkpoint.bin" \
    --log-level info > "$dir/restart.log" 2>&1
  rm -f "$dir/full/checkpoint.bin.previous"  # GBs with factors
  echo "== checkpoint_factors: $factors"
  /usr/bin/python3 - "$dir" <<'PY'
import json, re, sys, datetime
out = sys.argv[1]
def lines(p): return [re.sub(r"\x1b\[[0-9;]*m", "", l) for l in open(p)]
def stamp(l): return datetime.datetime.strptime(l[1:13], "%H:%M:%S.%f")
full, rest = lines(f"{out}/full.log"), lines(f"{out}/restart.log")
ck = [re.search(r"checkpoint after step (\d+): .* \(([\d.]+) ([KMG]?B), ([\d.]+) s\)", l) for l in full]
ck = [m for m in ck if m]
units = 6
scale = {"B": 1e-6, "KB": 1e-3, "MB": 1.0, "GB": 1e3}
for m in ck:
    mb = float(m.group(2)) * scale[m.group(3)]
    print(f"checkpoint after step {m.group(1)}: {m.group(2)} {m.group(3)} ({units} units: {mb / units:.1f} MB per unit), "
          f"written in {m.group(4)} s ({float(m.group(4)) / units:.3f} s per unit)")
start = stamp(rest[0])
placed = stamp(next(l for l in rest if "restarted from" in l))
print(f"restart: read, checked (checksum) and placed every unit's state in {(placed - start).total_seconds():.2f} s "
      f"(from the first log line; spec, meshes and models included)")
def first_iteration(d, step):
    rows = [json.loads(l) for l in open(f"{d}/trace_units.jsonl")]
    rows = [r for r in rows if r["step"] == step and r["iteration"] == 1]
    return (sum(r["refresh_cost"] for r in rows), sum(r["cost"] for r in rows), sum(r["kind"] == "refresh" for r in rows),
            sum(r["factor_rebuilt"] for r in rows))
rf, cf, nf, bf = first_iteration(f"{out}/full", 1)
rr, cr, nr, br = first_iteration(f"{out}/restart", 1)
print(f"step 2, iteration 1, uninterrupted: {nf} of {units} units refresh, {bf} rebuild, refresh CPU {rf:.2f} s, job CPU {cf:.2f} s")
print(f"step 2, iteration 1, restarted:     {nr} of {units} units refresh, {br} rebuild, refresh CPU {rr:.2f} s, job CPU {cr:.2f} s")
first = [json.loads(l) for l in open(f"{out}/full/trace_units.jsonl")]
fresh = [r["refresh_cost"] for r in first if r["step"] == 0 and r["iteration"] == 1]
print(f"one factorization per unit (step 1, iteration 1): {sum(fresh):.2f} s for {len(fresh)} units")
PY
done
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
