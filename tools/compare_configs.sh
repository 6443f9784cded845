#!/usr/bin/env bash
# Runs configs with two builds of fe2heart and compares their summary.json (a refactoring
# must give the same answer, bit for bit on one rank).
#   tools/compare_configs.sh BEFORE_BIN AFTER_BIN [-n RANKS] [--out DIR] [--keep-before] [config.json ...]
# Without configs: every run spec in configs/ but the long ones (lv-beat-fine, biv-beat;
# name them to include them). The runs go to DIR/before/<name> and DIR/after/<name>
# (default out/compare); a run that failed before must fail alike after. --keep-before
# reuses the runs already in DIR/before (the old build need not exist any more).
set -euo pipefail
top=$(cd "$(dirname "$0")/.." && pwd)
[[ $# -ge 2 ]] || { sed -n '2,7p' "$0" >&2; exit 2; }
before=$(realpath -m "$1") after=$(realpath -m "$2"); shift 2
ranks=1 out="$top/out/compare" configs=() keep=0
while [[ $# -gt 0 ]]; do
  case $1 in
    -n) ranks=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    --keep-before) keep=1; shift ;;
    *) configs+=("$1"); shift ;;
  esac
done
if ((${#configs[@]} == 0)); then
  for c in "$top"/configs/*.json; do
    case $(basename "$c") in
      study-*|circulation-*|unit_*|lv-beat-fine.json|biv-beat.json) ;;
      *) configs+=("$c") ;;
    esac
  done
fi
export OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
failed=0
for c in "${configs[@]}"; do
  name=$(basename "$c" .json)
  for side in before after; do
    bin=$before; [[ $side == after ]] && bin=$after
    [[ $side == before && $keep == 1 && -f $out/before/$name/summary.json ]] && continue
    mkdir -p "$out/$side"
    if ! mpirun -n "$ranks" "$bin" run "$c" --out "$out/$side/$name" --overwrite \
         >"$out/$side/$name.log" 2>&1; then
      echo "$name ($side): the run failed, see $out/$side/$name.log"
    fi
  done
  if [[ -f $out/before/$name/summary.json && -f $out/after/$name/summary.json ]]; then
    /usr/bin/python3 "$top/tools/compare_summaries.py" "$out/before/$name/summary.json" \
      "$out/after/$name/summary.json" || failed=1
  else
    echo "$name: no summary.json on one side"; failed=1
  fi
done
exit $failed
