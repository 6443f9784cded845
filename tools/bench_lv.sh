#!/bin/bash
# Passive LV inflation (configs/lv-passive-inflation.json's geometry, law and load) at three
# refinements for three discretizations — P1 displacement-only (Holzapfel–Ogden with a
# volumetric penalty κ), stabilized P1/P1 and Taylor–Hood P2/P1 (perturbed Lagrangian with
# the same κ: the same continuous problem) — one rank, macro-law points. Prints a Markdown
# table: points (= units) per element, macro unknowns, Newton iterations, wall time per
# step, cavity volume at 1.2 kPa.
#   tools/bench_lv.sh [BUILD_DIR] [OUT_DIR]
set -euo pipefail
build=${1:-build}
out=${2:-/tmp/fe2heart-bench-lv}
export OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1
here=$(cd "$(dirname "$0")/.." && pwd)
mkdir -p "$out"
echo "| mesh (circ × long × trans) | formulation | elements | points/element | macro unknowns | Newton (6 steps) | s per step | LV volume at 1.2 kPa (mm³) |"
echo "|---|---|---|---|---|---|---|---|"
for div in "8 4 1" "12 6 2" "16 8 3"; do
  for form in p1 p1p1 p2p1; do
    name="$(echo "$div" | tr ' ' x)-$form"
    /usr/bin/python3 - "$here/configs/lv-passive-inflation.json" "$out/$name.json" "$div" "$form" <<'PY'
import json, sys
src, dst, div, form = sys.argv[1], sys.argv[2], [int(x) for x in sys.argv[3].split()], sys.argv[4]
s = json.load(open(src))
kappa = 1e7
s["mesh"]["divisions"] = div
s["mesh"]["order"] = 2 if form == "p2p1" else 1
s["output"] = {"vtu": False}
s.pop("probes", None)
mat = s["models"]["myocardium"]["material"]
if form == "p1":
    s["formulation"] = {"kind": "displacement"}
    mat.update({"volumetric": "penalty", "kappa": kappa})
else:
    s["formulation"] = {"kind": "mixed", "bulk_modulus": kappa}
    if form == "p1p1":
        s["formulation"]["stabilization_modulus"] = 5000.0
json.dump(s, open(dst, "w"), indent=1)
PY
    "$build/tools/fe2heart" run "$out/$name.json" --out "$out/$name" --overwrite > "$out/$name.log" 2>&1 || true
    /usr/bin/python3 - "$out/$name/summary.json" "$div" "$form" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
label = {"p1": "P1 displacement", "p1p1": "P1/P1 stabilized", "p2p1": "P2/P1 Taylor–Hood"}[sys.argv[3]]
if not s.get("converged"):
    print(f"| {sys.argv[2]} | {label} | failed: {s.get('error', '?')[:60]} |||||")
    sys.exit()
steps = s["history"]
per_step = sum(h["wall_seconds"] for h in steps) / len(steps)
print(f"| {sys.argv[2].replace(' ', ' × ')} | {label} | {s['elements']} | {s['points'] // s['elements']} | "
      f"{s['macro_unknowns']} | {s['newton_iterations']} | {per_step:.2f} | {s['cavities']['lv']['volume']:.0f} |")
PY
  done
done
