#!/usr/bin/env bash
# The default FE² beat's costliest phase with larger units (issue 32 §1): the cheap beat
# (configs/lv-beat.json) runs to end-diastole (its inflation steps) and stops with a
# checkpoint; the same heart with units of R x R x R hexahedra (binary16 factors)
# continues from it with fresh units (--fresh-units: they settle at the end-diastolic
# wall first) over STEPS steps of the isovolumic contraction and early ejection, and its
# traces are replayed by farm-sim at the paper's Table I worker counts.
#   tools/bench_seed_scale.sh [R=10] [STEPS=20] [OUT=out/bench_seed_scale] [NP=2] [BUDGET] [REFRESH]
# R = 21 is the paper's unit size (27,780 DOF; the paper: 26,121); `fe2heart validate`
# prints what the 360 units need (R = 10: 13.5 GB on one rank, R = 21: 256 GB), and
# BUDGET (e.g. 8G: farm.factor_memory_budget per worker rank) caps the factors kept;
# REFRESH replaces the units' refresh policy (unit.solver.refresh, e.g. every_iteration).
# OPENBLAS_NUM_THREADS=1 inside the ranks.
set -euo pipefail
top=$(cd "$(dirname "$0")/.." && pwd)
R=${1:-10}
steps=${2:-20}
out=${3:-$top/out/bench_seed_scale}
np=${4:-2}
budget=${5:-}
refresh=${6:-}
export OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
bin=${FE2HEART:-$top/build/tools/fe2heart}
base=$top/configs/lv-beat.json
mkdir -p "$out"

inflation=$(/usr/bin/env python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['time']['inflation_steps'])" "$base")
if [[ ! -f $out/cheap/checkpoint.bin ]]; then
  echo "== the cheap beat to end-diastole ($inflation inflation steps)"
  mpirun -np "$np" "$bin" run "$base" --out "$out/cheap" --overwrite --stop-after-steps "$inflation" --log-level warn
fi

/usr/bin/env python3 - "$base" "$out/seed.json" "$R" "$budget" "$refresh" <<'PY'
import json, sys
base, path, r, budget, refresh = sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4], sys.argv[5]
spec = json.load(open(base))
unit = spec["models"]["myocardium"]["unit"]
unit["resolution"] = [r, r, r]
unit.setdefault("solver", {})["precision"] = "half"
spec["output"] = {"vtu": False}
if budget:
    spec.setdefault("farm", {})["factor_memory_budget"] = budget
if refresh:
    unit["solver"]["refresh"] = refresh
json.dump(spec, open(path, "w"), indent=1, ensure_ascii=False)
PY
"$bin" validate "$out/seed.json"

echo "== $steps steps with units of $R^3 hexahedra from end-diastole"
rm -rf "$out/seed"
start=$(date +%s)
mpirun -np "$np" "$bin" run "$out/seed.json" --out "$out/seed" --restart "$out/cheap" --fresh-units \
  --stop-after-steps "$steps" --log-level warn
echo "wall time: $(( $(date +%s) - start )) s on $np ranks"
"$bin" trace summary "$out/seed"
"$bin" farm-sim "$out/seed" --workers 1536 2048 3072 6144 --units-per-worker 1 4
