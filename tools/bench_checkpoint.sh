#!/usr/bin/env bash
# Checkpoint cost at the paper's unit size: six FE² units of 27,780 DOF (two cells,
# 21^3 hexahedra, as `fe2heart bench unit`), two steps, a checkpoint after each.
#   tools/bench_checkpoint.sh [FE2HEART] [OUT]     (default build/tools/fe2heart, /tmp/fe2_bench_ckpt)
#   RESTART_ONLY=1 tools/bench_checkpoint.sh ...   only the restart (OUT/full from an earlier run)
# Prints: checkpoint size (total, per unit), write time, and for a restart from the first
# checkpoint: the time to read and place every unit's state, and the CPU of the first
# iteration's factor rebuilds, beside the same iteration of the uninterrupted run
# (whose units reuse or refresh as their policy says) and one factorization per unit.
set -euo pipefail
top=$(cd "$(dirname "$0")/.." && pwd)
fe2=${1:-$top/build/tools/fe2heart}
out=${2:-/tmp/fe2_bench_ckpt}
export OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
[[ ${RESTART_ONLY:-} ]] || rm -rf "$out"; rm -rf "$out/restart"
mkdir -p "$out"
cat > "$out/spec.json" <<'JSON'
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
  "output": {"vtu": false, "checkpoint_every": 1}
}
JSON
log() { sed 's/\x1b\[[0-9;]*m//g' "$1"; }
[[ ${RESTART_ONLY:-} ]] || mpirun -n 1 "$fe2" run "$out/spec.json" --out "$out/full" --log-level info > "$out/full.log" 2>&1
mkdir -p "$out/restart"
cp "$out/full/checkpoint.bin.previous" "$out/restart/checkpoint.bin"
mpirun -n 1 "$fe2" run "$out/spec.json" --out "$out/restart" --restart "$out/restart/checkpoint.bin" \
  --log-level info > "$out/restart.log" 2>&1
/usr/bin/python3 - "$out" <<'PY'
import json, re, sys, datetime
out = sys.argv[1]
def lines(p): return [re.sub(r"\x1b\[[0-9;]*m", "", l) for l in open(p)]
def stamp(l): return datetime.datetime.strptime(l[1:13], "%H:%M:%S.%f")
full, rest = lines(f"{out}/full.log"), lines(f"{out}/restart.log")
ck = [re.search(r"checkpoint after step (\d+): .* \(([\d.]+ [KMG]?B), ([\d.]+) s\)", l) for l in full]
ck = [m for m in ck if m]
units = 6
for m in ck:
    print(f"checkpoint after step {m.group(1)}: {m.group(2)} ({units} units), written in {m.group(3)} s")
start = stamp(rest[0])
placed = stamp(next(l for l in rest if "restarted from" in l))
print(f"restart: read, checked (checksum) and placed every unit's state in {(placed - start).total_seconds():.2f} s "
      f"(from the first log line; spec, meshes and models included)")
def first_iteration(d, step):
    rows = [json.loads(l) for l in open(f"{d}/trace_units.jsonl")]
    rows = [r for r in rows if r["step"] == step and r["iteration"] == 1]
    return sum(r["refresh_cost"] for r in rows), sum(r["cost"] for r in rows), sum(r["kind"] == "refresh" for r in rows)
rf, cf, nf = first_iteration(f"{out}/full", 1)
rr, cr, nr = first_iteration(f"{out}/restart", 1)
print(f"step 2, iteration 1, uninterrupted: {nf} of {units} units refresh, refresh CPU {rf:.2f} s, job CPU {cf:.2f} s")
print(f"step 2, iteration 1, restarted:     {nr} of {units} units refresh, refresh CPU {rr:.2f} s, job CPU {cr:.2f} s")
first = [json.loads(l) for l in open(f"{out}/full/trace_units.jsonl")]
fresh = [r["refresh_cost"] for r in first if r["step"] == 0 and r["iteration"] == 1]
print(f"one factorization per unit (step 1, iteration 1): {sum(fresh):.2f} s for {len(fresh)} units")
PY
