#!/usr/bin/env python3
"""A beat's macro state with fresh units (fe2heart run --restart --fresh-units) and a
window of steps (--stop-after-steps): the benchmark's way to run a costly phase of a
beat with other units from a checkpoint of a cheap beat (issue 32 §1).

  check_fresh_units.py MPIEXEC FE2HEART SCENE OUT

SCENE is tests/mpi/farm_scene_fresh_units.json (inflated to end-diastole in 3 steps, then
12 steps of a beat). Asserts, each a number that could fail:
  1. --stop-after-steps 3 stops at end-diastole with a checkpoint and exit 0.
  2. Restarted there with fresh units of the same spec, the beat keeps the checkpoint's
     history (steps 0-2 bit for bit) and runs within 1 % of the uninterrupted beat's
     cavity volume at every step: the units settle at the restored Z̄ and their cells
     start at rest, which at end-diastole they nearly are (the cross-bridges' diastolic
     history is the difference: 0.42 % measured). The first step, isovolumic, keeps the
     restored end-diastolic volume (to 1e-15).
  3. Stopped in the ejection (step 7) and restarted there with units of another
     resolution: 2 steps converge (the fresh units settle at the ejecting wall's Z̄
     first; thrown at it in one Newton update their cells invert, and the run fails),
     and the units are the new ones (their state is larger in the trace).
  4. Bad input: --fresh-units without --restart, other units without --fresh-units,
     --fresh-units into the checkpoint's own folder, and a changed key outside the unit
     are refused (exit 2) naming the option or key.
"""
import json
import os
import shutil
import subprocess
import sys

mpiexec, fe2heart, scene, out = sys.argv[1:5]
shutil.rmtree(out, ignore_errors=True)
os.makedirs(out)
failures = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        failures.append(what)


def run(spec, folder, *args, np=2):
    cmd = [mpiexec, "-n", str(np), fe2heart, "run", spec, "--out", os.path.join(out, folder),
           "--log-level", "warn", *args]
    p = subprocess.run(cmd, capture_output=True, text=True, timeout=300)
    return p.returncode, p.stdout + p.stderr


def history(folder):
    with open(os.path.join(out, folder, "summary.json")) as f:
        return json.load(f)["history"]


def volumes(folder):
    return [r["cavity_volumes"]["lv"] for r in history(folder)]


with open(scene) as f:
    spec = json.load(f)
spec["models"]["myocardium"]["unit"]["resolution"] = [8, 4, 4]
other_units = os.path.join(out, "other_units.json")
with open(other_units, "w") as f:
    json.dump(spec, f)
spec["models"]["myocardium"]["unit"]["resolution"] = [4, 4, 4]
spec["newton"]["max_iterations"] = 30
other_newton = os.path.join(out, "other_newton.json")
with open(other_newton, "w") as f:
    json.dump(spec, f)

rc, log = run(scene, "reference")
check(rc == 0, f"the uninterrupted beat runs (exit {rc})")
reference = volumes("reference")

# 1. A window: stop at end-diastole.
rc, log = run(scene, "diastole", "--stop-after-steps", "3")
check(rc == 0 and os.path.exists(os.path.join(out, "diastole", "checkpoint.bin")),
      f"--stop-after-steps 3: exit {rc}, a checkpoint")
check(len(history("diastole")) == 3, f"--stop-after-steps 3 ran {len(history('diastole'))} steps")

# 2. Fresh units of the same spec at end-diastole.
rc, log = run(scene, "fresh", "--restart", os.path.join(out, "diastole"), "--fresh-units")
check(rc == 0, f"the fresh-units restart at end-diastole runs (exit {rc})")
fresh = volumes("fresh")
check(len(fresh) == len(reference), f"it ends the beat ({len(fresh)} of {len(reference)} steps)")
check(fresh[:3] == reference[:3], "the checkpoint's history is kept bit for bit")
# The first step after the restart is isovolumic: it keeps the restored end-diastolic
# volume whatever the units do, if the macro state is the checkpoint's.
first = abs(fresh[3] - reference[3]) / reference[3]
check(first < 1e-9, f"the first step keeps the restored end-diastolic volume ({first:.2e})")
worst = max(abs(a - b) / b for a, b in zip(fresh, reference))
print(f"     largest cavity-volume difference to the uninterrupted beat: {worst:.2e}")
check(worst < 0.01, f"within 1 % of the uninterrupted beat at every step ({worst:.2e})")

# 3. In the ejection, with units of another resolution.
rc, log = run(scene, "ejection", "--stop-after-steps", "7")
check(rc == 0, f"--stop-after-steps 7 (ejection): exit {rc}")
rc, log = run(other_units, "ejection_other", "--restart", os.path.join(out, "ejection"), "--fresh-units",
              "--stop-after-steps", "2")
check(rc == 0, f"fresh units of resolution [8, 4, 4] in the ejection: 2 steps converge (exit {rc})")
if rc != 0:
    print(log[-2000:])
else:
    check(len(history("ejection_other")) == 9, f"it stops after step 9 ({len(history('ejection_other'))})")

    def state_bytes(folder, step):
        with open(os.path.join(out, folder, "trace_units.jsonl")) as f:
            rows = [json.loads(line) for line in f]
        return max(r["state_bytes"] for r in rows if r["step"] == step)
    small, large = state_bytes("ejection", 6), state_bytes("ejection_other", 7)
    check(large > 1.5 * small, f"the restarted units are the new ones: state {large} bytes against {small}")

# 4. Bad input.
cases = [
    ((scene, "bad1", "--fresh-units"), "--fresh-units: only with --restart"),
    ((other_units, "bad2", "--restart", os.path.join(out, "diastole")), "/models/myocardium/unit/resolution"),
    ((scene, "diastole", "--restart", os.path.join(out, "diastole"), "--fresh-units"), "another folder"),
    ((other_newton, "bad4", "--restart", os.path.join(out, "diastole"), "--fresh-units"), "/newton/max_iterations"),
]
for args, expected in cases:
    rc, log = run(*args)
    check(rc == 2 and expected in log, f"refused (exit {rc}) naming '{expected}'")

if failures:
    print(f"{len(failures)} check(s) failed")
    sys.exit(1)
print("all checks passed")
