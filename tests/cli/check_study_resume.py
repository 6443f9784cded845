#!/usr/bin/python3
"""`fe2heart study --resume` keeps what an earlier study finished and runs the rest.

    check_study_resume.py FE2HEART STUDY_DATA_DIR OUT

1. Runs tests/data/study/tiny.json (base, coarse, steps=4) into OUT.
2. Simulates an interrupted, then edited study: removes steps=4's result.json (as if the
   study had stopped while it ran), leaves a marker file in base's run folder, and writes a
   study whose "coarse" sets other divisions and which adds steps=6.
3. Runs that with --resume and checks: base is kept (its marker, its CPU seconds and its
   error 0 unchanged, "kept_from_earlier_study" true); coarse runs again with its new spec
   (error equal to the one recomputed from the two runs, and not the earlier coarse's);
   steps=4 and steps=6 run; no variant is kept that should not be.
4. Runs it once more with --resume: every variant is kept and study.json's errors are
   those of step 3, bit for bit.
5. --resume with --overwrite is refused (exit 2), and without either flag the folder is
   refused, naming --resume.
Exit 0 on success, 1 with the reasons otherwise.
"""
import json
import os
import shutil
import subprocess
import sys

from check_study import displacement_error


def run(cmd):
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    print(f"$ {' '.join(cmd)}  -> exit {p.returncode}\n{p.stdout}")
    return p


def variants(out):
    return {v["name"]: v for v in json.load(open(os.path.join(out, "study.json")))["variants"]}


def main(fe2heart, data, out):
    failures = []
    shutil.rmtree(out, ignore_errors=True)
    tiny = os.path.join(data, "tiny.json")
    if run([fe2heart, "study", tiny, "--out", out]).returncode != 0:
        return ["the first study failed"]
    first = variants(out)

    os.remove(os.path.join(out, "variants", "steps=4", "result.json"))
    marker = os.path.join(out, "variants", "base", "run", "kept.marker")
    open(marker, "w").close()
    study = json.load(open(tiny))
    study["base"] = os.path.join(data, study["base"])  # the edited study lives in OUT
    study["variants"][1]["set"] = {"/mesh/divisions": [2, 1, 1]}
    study["one_at_a_time"] = {"/time/steps": [4, 6]}
    edited = os.path.join(out, "edited.json")
    json.dump(study, open(edited, "w"), indent=2)

    p = run([fe2heart, "study", edited, "--out", out, "--resume"])
    if p.returncode != 0:
        return ["the resumed study failed"]
    second = variants(out)
    expect_kept = {"base": True, "coarse": False, "steps=4": False, "steps=6": False}
    for name, kept in expect_kept.items():
        if name not in second:
            failures.append(f"{name}: missing from the resumed study.json")
        elif second[name]["kept_from_earlier_study"] != kept or second[name]["status"] != "ok":
            failures.append(f"{name}: kept {second[name]['kept_from_earlier_study']}, status {second[name]['status']}; "
                            f"expected kept {kept}, ok")
    if failures:
        return failures
    if not os.path.exists(marker):
        failures.append("base's run folder was replaced although base was kept")
    if second["base"]["cpu_seconds"] != first["base"]["cpu_seconds"] or second["base"]["error"] != 0:
        failures.append(f"base: CPU {second['base']['cpu_seconds']} error {second['base']['error']}; expected the "
                        f"first study's CPU {first['base']['cpu_seconds']} and error 0")
    spec = json.load(open(os.path.join(out, "variants", "coarse", "spec.json")))
    if spec["mesh"]["divisions"] != [2, 1, 1]:
        failures.append(f"coarse ran with divisions {spec['mesh']['divisions']}, expected the edited [2, 1, 1]")
    recomputed = displacement_error(os.path.join(out, "variants", "coarse", "run"),
                                    os.path.join(out, "variants", "base", "run"))
    got = second["coarse"]["errors"]["displacement"]["error"]
    print(f"coarse: displacement error {got}, recomputed {recomputed}, earlier coarse "
          f"{first['coarse']['errors']['displacement']['error']}")
    if abs(got - recomputed) > 1e-12 * max(1.0, recomputed):
        failures.append(f"coarse: error {got}, recomputed from the runs {recomputed}")
    if got == first["coarse"]["errors"]["displacement"]["error"]:
        failures.append("coarse: the same error as before its spec changed; it was not run again")
    for line in ("variant 'coarse' runs: its spec changed",
                 "variant 'steps=4' runs: no earlier result",
                 "[1/4] base: ok, kept from the earlier study"):
        if line not in p.stdout:
            failures.append(f"the resumed study's output lacks '{line}'")

    p = run([fe2heart, "study", edited, "--out", out, "--resume"])
    third = variants(out)
    if p.returncode != 0 or not all(v["kept_from_earlier_study"] for v in third.values()):
        failures.append("a second --resume ran variants again: " +
                        str({n: v["kept_from_earlier_study"] for n, v in third.items()}))
    if {n: v["errors"] for n, v in third.items()} != {n: v["errors"] for n, v in second.items()}:
        failures.append("a second --resume changed the errors")

    p = run([fe2heart, "study", edited, "--out", out, "--resume", "--overwrite"])
    if p.returncode != 2 or "excludes" not in p.stdout:
        failures.append(f"--resume --overwrite: exit {p.returncode}, expected 2 and 'excludes'")
    p = run([fe2heart, "study", edited, "--out", out])
    if p.returncode != 2 or "use --resume" not in p.stdout:
        failures.append(f"no flag on an existing study: exit {p.returncode}, expected 2 naming --resume")
    return failures


def check_main(main, doc, arguments=3):
    """Runs main(*argv) of a check script: prints each failure, exits 1 if any, 0 if none."""
    if len(sys.argv) != arguments + 1:
        sys.exit(doc)
    problems = main(*sys.argv[1:])
    for f in problems:
        print("FAIL:", f)
    sys.exit(1 if problems else 0)


if __name__ == "__main__":
    check_main(main, __doc__)
