#!/usr/bin/env bash
# Threads inside a rank against ranks (issue #32 §3): a spec on 1 rank × 1 thread,
# 1 rank × 2 threads and 2 ranks × 1 thread (one coordinator, cost-based placement),
# the three launches alternated REPEAT times. Prints each run's wall time, Micro+L+C,
# the units' CPU, the peak resident memory of every rank, and the medians; checks that
# the answers are bit for bit the same (tools/compare_summaries.py).
#   tools/bench_threads.sh [REPEAT=3] [OUT=out/bench_threads] [SPEC=configs/lv-beat.json]
set -euo pipefail
top=$(cd "$(dirname "$0")/.." && pwd)
repeat=${1:-3}
out=${2:-$top/out/bench_threads}
spec=${3:-$top/configs/lv-beat.json}
bin=${FE2HEART:-$top/build/tools/fe2heart}
export OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
mkdir -p "$out"
layouts=("1 1" "1 2" "2 1")
for r in $(seq 1 "$repeat"); do
  for layout in "${layouts[@]}"; do
    read -r np threads <<<"$layout"
    dir=$out/np${np}x${threads}.r$r
    mkdir -p "$dir"
    t0=$(date +%s.%N)
    # Open MPI binds a rank to one core: a rank of T threads needs T (--map-by slot:PE=T).
    bind=()
    ((threads > 1)) && bind=(--map-by "slot:PE=$threads")
    # Each rank's peak RSS (kB) into rss.<rank>.
    mpirun -np "$np" "${bind[@]}" sh -c '/usr/bin/time -f "%M" -o "$0/rss.$OMPI_COMM_WORLD_RANK" "$@"' "$dir" \
      "$bin" run "$spec" --out "$dir" --overwrite --log-level warn --coordinators 1 \
      --threads-per-rank "$threads"
    t1=$(date +%s.%N)
    echo "$t0 $t1" | awk '{print $2 - $1}' > "$dir/wall_seconds"
    "$bin" trace summary "$dir" --json > "$dir/trace_summary.json"
  done
done
/usr/bin/env python3 - "$out" "$repeat" "$top" <<'PY'
import glob, json, statistics, subprocess, sys
out, repeat, top = sys.argv[1], int(sys.argv[2]), sys.argv[3]
layouts = [(1, 1), (1, 2), (2, 1)]
def figures(d):
    s = json.load(open(f"{d}/trace_summary.json"))
    cpu = 0.0
    for line in open(f"{d}/trace_workers.jsonl"):
        cpu += json.loads(line).get("busy", 0.0)
    rss = [int(open(f).read().split()[-1]) / 1024 for f in sorted(glob.glob(f"{d}/rss.*"))]
    return dict(wall=float(open(f"{d}/wall_seconds").read()), micro=s["micro_lc_seconds"],
                cpu=cpu, rss=rss)
rows = {l: [figures(f"{out}/np{l[0]}x{l[1]}.r{r}") for r in range(1, repeat + 1)] for l in layouts}
for (np, t), runs in rows.items():
    for k, f in enumerate(runs, 1):
        print(f"{np} rank(s) x {t} thread(s), run {k}: wall {f['wall']:.1f} s, Micro+L+C {f['micro']:.1f} s, "
              f"units' CPU {f['cpu']:.1f} s, peak RSS per rank {', '.join(f'{m:.0f}' for m in f['rss'])} MiB")
print("medians (OPENBLAS_NUM_THREADS=1):")
base = statistics.median(f["wall"] for f in rows[(1, 1)])
for (np, t), runs in rows.items():
    wall = statistics.median(f["wall"] for f in runs)
    micro = statistics.median(f["micro"] for f in runs)
    cpu = statistics.median(f["cpu"] for f in runs)
    rss = statistics.median(sum(f["rss"]) for f in runs)
    cores = np * t
    print(f"  {np} x {t}: wall {wall:.1f} s (speedup {base / wall:.2f}), Micro+L+C {micro:.1f} s, "
          f"units' CPU {cpu:.1f} s, peak RSS {rss:.0f} MiB in all, {rss / cores:.0f} MiB per core")
ref = f"{out}/np1x1.r1/summary.json"
for (np, t) in layouts[1:]:
    same = subprocess.run([sys.executable, f"{top}/tools/compare_summaries.py", ref,
                           f"{out}/np{np}x{t}.r1/summary.json"], capture_output=True).returncode == 0
    print(f"  {np} x {t} answer bit for bit that of 1 x 1: {'yes' if same else 'NO'}")
PY
