#!/usr/bin/env bash
# The macro system at the paper's size (configs/lv-macro-paper-size.json, 43,578 unknowns):
# per Newton iteration, the factorization of S̄, a solve with the kept factor and the
# assembly, on 1, 2 and 4 coordinators (every rank a coordinator; with more ranks than
# cores they share them, so the busiest coordinator's CPU is the figure, not wall time).
#   tools/bench_macro.sh [COORDINATORS="1 2 4"] [OUT=out/bench_macro] [SPEC=configs/lv-macro-paper-size.json]
# Then `fe2heart farm-sim RUN --macro-from OUT/c2` puts these macro costs under a run's units.
set -euo pipefail
top=$(cd "$(dirname "$0")/.." && pwd)
coordinators=${1:-"1 2 4"}
out=${2:-$top/out/bench_macro}
spec=${3:-$top/configs/lv-macro-paper-size.json}
export OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
bin=$top/build/tools/fe2heart
for c in $coordinators; do
  mpirun -np "$c" "$bin" run "$spec" --out "$out/c$c" --coordinators "$c" \
    --overwrite --log-level warn
  "$bin" trace summary "$out/c$c" --json > "$out/c$c/trace_summary.json"
done
/usr/bin/env python3 - "$out" $coordinators <<'PY'
import json, sys
out, cs = sys.argv[1], sys.argv[2:]
print(f"{'coordinators':>12} | {'unknowns':>8} | {'factorizing: n':>14} {'CPU s':>7} {'solve s':>7} | "
      f"{'kept factor: n':>14} {'CPU s':>7} {'GMRES':>5} | {'assembly s':>10} | {'Σ CPU busiest':>13} {'Σ CPU all':>9} | {'wall s':>7}")
for c in cs:
    s = json.load(open(f"{out}/c{c}/trace_summary.json"))
    run = json.load(open(f"{out}/c{c}/summary.json"))
    m, f, k = s["macro"], s["macro"]["factorizing"], s["macro"]["kept_factor"]
    print(f"{c:>12} | {run['macro_unknowns']:>8} | {f['iterations']:>14} {f['median_cpu_seconds']:>7.3f} "
          f"{f['median_solve_seconds']:>7.3f} | {k['iterations']:>14} {k['median_cpu_seconds']:>7.3f} "
          f"{k['median_gmres']:>5.0f} | {f['median_assemble_seconds']:>10.3f} | {m['cpu_critical_seconds']:>13.1f} "
          f"{m['cpu_total_seconds']:>9.1f} | {run['wall_seconds']:>7.1f}")
PY
