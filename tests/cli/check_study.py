#!/usr/bin/python3
"""Checks what `fe2heart study` wrote for the studies of tests/data/study/.

    check_study.py STUDY_DIR tiny|failing

tiny (tiny.json: base, coarse, steps=4; reference "base"):
  every variant ran ("ok"), with wall, CPU seconds, core-hours, peak RSS and Newton
  iterations > 0; the reference's error is exactly 0; the coarse mesh's displacement
  error is > 1e-3 and equals the one recomputed here from the two runs' summary.json
  (same step times) to 1e-12; twice the steps gives 0 < error < coarse's; each
  variant's spec.json carries its edit; study.csv has one row per variant;
  study.txt and pareto.png exist.
failing (failing.json): "one_newton" is kept as failed, exit code 3, with the
  Newton failure as its reason and no error; "base" ran; study.csv still has both rows.
Exit 0 on success, 1 with the reasons otherwise.
"""
import csv
import json
import os
import sys


def displacement_error(run, ref):
    """max |u - u_ref| / max |u_ref| over the steps both have (same times) and every probe."""
    def series(d):
        s = json.load(open(os.path.join(d, "summary.json")))
        X = json.load(open(os.path.join(d, "spec.json")))["probes"]
        return {round(h["time"], 12): [h["probes"][p][k] - X[p][k] for p in sorted(X) for k in range(3)]
                for h in s["history"]}
    a, b = series(run), series(ref)
    common = sorted(set(a) & set(b))
    diff = max(abs(x - y) for t in common for x, y in zip(a[t], b[t]))
    scale = max(abs(y) for t in common for y in b[t])
    return diff / scale


def main(study_dir, mode):
    failures = []
    s = json.load(open(os.path.join(study_dir, "study.json")))
    v = {x["name"]: x for x in s["variants"]}
    rows = list(csv.DictReader(open(os.path.join(study_dir, "study.csv"))))
    print(f"{study_dir}: variants {list(v)}; csv rows {[r['name'] for r in rows]}")
    if [r["name"] for r in rows] != [x["name"] for x in s["variants"]]:
        failures.append("study.csv rows differ from study.json's variants")
    for name, x in v.items():
        print(f"  {name}: {x['status']} exit {x['exit_code']} wall {x['wall_seconds']:.3f} cpu {x['cpu_seconds']:.3f} "
              f"error {x['error']} {x.get('reason', '')}")
    if mode == "tiny":
        if list(v) != ["base", "coarse", "steps=4"]:
            failures.append(f"variants {list(v)}, expected base, coarse, steps=4")
            return failures
        for name, x in v.items():
            if x["status"] != "ok":
                failures.append(f"{name}: status {x['status']}, expected ok")
            for key in ("wall_seconds", "cpu_seconds", "core_hours", "peak_rss_mb", "newton_iterations"):
                if not x[key] > 0:
                    failures.append(f"{name}: {key} = {x[key]}, expected > 0")
        if s["reference"]["name"] != "base" or not v["base"]["reference"]:
            failures.append(f"reference {s['reference']}, expected the variant 'base'")
        if v["base"]["error"] != 0:
            failures.append(f"base (the reference) has error {v['base']['error']}, expected 0")
        run = lambda n: os.path.join(study_dir, "variants", n, "run")
        expected = displacement_error(run("coarse"), run("base"))
        got = v["coarse"]["errors"]["displacement"]["error"]
        print(f"  coarse displacement error {got}, recomputed {expected}")
        if not expected > 1e-3 or abs(got - expected) > 1e-12:
            failures.append(f"coarse: displacement error {got}, expected {expected} (> 1e-3)")
        if not 0 < v["steps=4"]["error"] < v["coarse"]["error"]:
            failures.append(f"steps=4: error {v['steps=4']['error']}, expected between 0 and coarse's")
        spec = json.load(open(os.path.join(study_dir, "variants", "coarse", "spec.json")))
        if spec["mesh"]["divisions"] != [1, 1, 1]:
            failures.append(f"variants/coarse/spec.json: mesh.divisions {spec['mesh']['divisions']}, expected [1, 1, 1]")
        for f in ("study.txt", "pareto.png"):
            if not os.path.getsize(os.path.join(study_dir, f)) > 0:
                failures.append(f"{f} is empty")
    elif mode == "failing":
        x = v.get("one_newton", {})
        if x.get("status") != "failed" or x.get("exit_code") != 3 or x.get("error") is not None:
            failures.append(f"one_newton: {x.get('status')}, exit {x.get('exit_code')}, error {x.get('error')}; "
                            "expected failed, 3, none")
        if "Newton did not converge" not in x.get("reason", ""):
            failures.append(f"one_newton: reason '{x.get('reason')}', expected the Newton failure")
        if v.get("base", {}).get("status") != "ok":
            failures.append("base did not run")
        if [r["status"] for r in rows] != ["ok", "failed"]:
            failures.append(f"study.csv statuses {[r['status'] for r in rows]}, expected ok, failed")
    else:
        failures.append(f"unknown mode {mode}")
    return failures


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    problems = main(sys.argv[1], sys.argv[2])
    for p in problems:
        print("FAIL:", p)
    print("PASS" if not problems else f"{len(problems)} failure(s)")
    sys.exit(1 if problems else 0)
