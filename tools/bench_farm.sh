#!/usr/bin/env bash
# Micro-phase speedup of 1 vs 2 worker ranks on configs/farm_beam.json: runs the two
# launches alternately REPEAT times and prints each run's figures and the medians.
#   tools/bench_farm.sh [REPEAT=3] [OUT=out/bench_farm]
set -euo pipefail
top=$(cd "$(dirname "$0")/.." && pwd)
repeat=${1:-3}
out=${2:-$top/out/bench_farm}
export OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
bin=$top/build/tools/fe2heart
for r in $(seq 1 "$repeat"); do
  for np in 1 2; do
    mpirun -np "$np" "$bin" run "$top/configs/farm_beam.json" --out "$out/np$np.r$r" --overwrite --log-level warn
    "$bin" trace summary "$out/np$np.r$r" --json > "$out/np$np.r$r/trace_summary.json"
  done
done
/usr/bin/env python3 - "$out" "$repeat" <<'PY'
import json, statistics, sys
out, repeat = sys.argv[1], int(sys.argv[2])
rows = {np: [json.load(open(f"{out}/np{np}.r{r}/trace_summary.json")) for r in range(1, repeat + 1)] for np in (1, 2)}
for np in (1, 2):
    for k, s in enumerate(rows[np], 1):
        print(f"np{np} run {k}: Micro+L+C {s['micro_lc_seconds']:.2f} s, Entire {s['entire_seconds']:.2f} s, "
              f"Macro/Entire {s['macro_over_entire']:.4f}, imbalance {s['imbalance_mean']:.3f}, "
              f"bytes/unit-iteration {s['bytes_per_unit_iteration']:.0f}, migrations {s['migrations']}")
m = {np: statistics.median(s['micro_lc_seconds'] for s in rows[np]) for np in (1, 2)}
print(f"median Micro+L+C: np1 {m[1]:.2f} s, np2 {m[2]:.2f} s, speedup {m[1] / m[2]:.2f}")
PY
