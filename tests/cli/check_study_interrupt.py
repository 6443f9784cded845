#!/usr/bin/python3
"""A study stopped by SIGTERM (a batch system's time limit) stops its running variant
with it, records only the variants that ended, and goes on with --resume.

    check_study_interrupt.py FE2HEART STUDY_DATA_DIR OUT

Runs a study of base.json with 400 and 401 steps (each a few seconds) and sends SIGTERM
to the study once the first variant has its result.json. Checks: exit code 143 (128 +
SIGTERM) and the log names --resume; the stopped variant did not run to its end (no
summary.json) and no process of it is left (none has OUT in its command line); it has
no result.json. Then
--resume keeps the first and runs the second, and study.json has both "ok".
Exit 0 on success, 1 with the reasons otherwise.
"""
import json
import os
import shutil
import signal
import subprocess
import sys
import time

from check_study_resume import run, variants


def processes_naming(text):
    """PIDs of processes whose command line contains `text` (from /proc)."""
    found = []
    for pid in filter(str.isdigit, os.listdir("/proc")):
        try:
            cmdline = open(f"/proc/{pid}/cmdline", "rb").read().replace(b"\0", b" ").decode(errors="replace")
            state = open(f"/proc/{pid}/stat").read().rsplit(")", 1)[1].split()[0]
        except OSError:
            continue
        if text in cmdline and state != "Z":
            found.append((int(pid), cmdline))
    return found


def main(fe2heart, data, out):
    failures = []
    shutil.rmtree(out, ignore_errors=True)
    os.makedirs(out)
    study = {"base": os.path.join(data, "base.json"), "variants": [],
             "one_at_a_time": {"/time/steps": [400, 401]}, "quantities": ["displacement"], "np": 1}
    spec = os.path.join(out, "slow.json")
    json.dump(study, open(spec, "w"), indent=2)
    result_dir = os.path.join(out, "study")
    first = os.path.join(result_dir, "variants", "steps=400", "result.json")

    p = subprocess.Popen([fe2heart, "study", spec, "--out", result_dir], stdout=subprocess.PIPE,
                         stderr=subprocess.STDOUT, text=True)
    deadline = time.time() + 60
    while not os.path.exists(first) and p.poll() is None and time.time() < deadline:
        time.sleep(0.05)
    time.sleep(0.3)  # the second variant is running now
    running = processes_naming(os.path.join(result_dir, "variants", "steps=401"))
    p.send_signal(signal.SIGTERM)
    output, _ = p.communicate(timeout=60)
    print(output)
    print(f"exit {p.returncode}; the second variant's processes before the signal: {running}")
    if not running:
        failures.append("the second variant was not running when the study got SIGTERM (test timing)")
    if p.returncode != 128 + signal.SIGTERM:
        failures.append(f"exit code {p.returncode}, expected {128 + signal.SIGTERM}")
    if "stopped by signal 15" not in output or "--resume" not in output:
        failures.append("the study's log does not say it was stopped and how to go on (--resume)")
    time.sleep(0.5)
    left = processes_naming(result_dir)
    if left:
        failures.append(f"processes outlived the study: {left}")
    if not os.path.exists(first):
        failures.append("the variant that ended has no result.json")
    if os.path.exists(os.path.join(result_dir, "variants", "steps=401", "run", "summary.json")):
        failures.append("the stopped variant ran to its end: the signal did not reach it")
    if os.path.exists(os.path.join(result_dir, "variants", "steps=401", "result.json")):
        failures.append("the stopped variant has a result.json")
    if os.path.exists(os.path.join(result_dir, "study.json")):
        failures.append("a stopped study wrote study.json")

    r = run([fe2heart, "study", spec, "--out", result_dir, "--resume"])
    v = variants(result_dir) if r.returncode == 0 else {}
    kept = {n: (x["status"], x["kept_from_earlier_study"]) for n, x in v.items()}
    if kept != {"steps=400": ("ok", True), "steps=401": ("ok", False)}:
        failures.append(f"after --resume: {kept} (exit {r.returncode}); expected steps=400 kept, steps=401 run, both ok")
    return failures


if __name__ == "__main__":
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    problems = main(*sys.argv[1:])
    for f in problems:
        print("FAIL:", f)
    sys.exit(1 if problems else 0)
