#!/usr/bin/python3
"""A study stopped by SIGTERM (a batch system's time limit) stops its running variant
at a checkpoint, and --resume continues that variant from there.

    check_study_interrupt.py FE2HEART STUDY_DATA_DIR OUT [--np N] [--sbatch SCRIPT]
                             [--early] [--killed]

--np N: ranks per variant (default 1); with N > 1 each variant runs under mpirun, which
  the study stops through the variant's stop file (`run --stop-file`), not with a signal
  (SIGTERM ends the ranks; a SIGUSR1 that mpirun forwards to a rank still between its
  exec and main kills it).
--sbatch SCRIPT (configs/slurm/study.sbatch): the study is started, signalled and
  resumed through that script, run by bash outside Slurm, as a batch job would.
--early: the signal comes as soon as the second variant has started (its ranks still
  starting up), not once it iterates: it must still stop at a checkpoint, not die.
--killed: before --resume, the stopped variant's result.json is made to say it was
  killed (exit 137) after its checkpoint: --resume must continue it all the same.

Runs a study of base.json with 400 and 800 steps (each a few seconds) and sends SIGTERM
to the study during the second. Checks:
- exit code 143 (128 + SIGTERM), the log names --resume, no study.json is written and no
  process of the variant is left (none has OUT in its command line);
- the first variant's result.json says "ok"; the second's says "stopped", and its run
  has checkpoint.bin and a summary.json that is not complete.
Then --resume keeps the first and continues the second from its checkpoint (its run.log
says "restarted from"; its CPU seconds include the stopped part), both "ok", and the
continued run's probe history equals that of the same spec run without a stop, bit for
bit (a restart continues exactly).
Exit 0 on success, 1 with the reasons otherwise.
"""
import argparse
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


def main(fe2heart, data, out, np=1, sbatch=None, early=False, killed=False):
    failures = []
    shutil.rmtree(out, ignore_errors=True)
    os.makedirs(out)
    study = {"base": os.path.join(data, "base.json"), "variants": [],
             "one_at_a_time": {"/time/steps": [400, 800]}, "quantities": ["displacement"], "np": np}
    spec = os.path.join(out, "slow.json")
    json.dump(study, open(spec, "w"), indent=2)
    result_dir = os.path.join(out, "study")
    first = os.path.join(result_dir, "variants", "steps=400", "result.json")
    second = os.path.join(result_dir, "variants", "steps=800")

    if sbatch:  # the script calls `fe2heart` from PATH and always passes --resume
        os.environ["PATH"] = os.path.dirname(os.path.abspath(fe2heart)) + os.pathsep + os.environ["PATH"]
        study_command = ["bash", sbatch, spec, result_dir]
    else:
        study_command = [fe2heart, "study", spec, "--out", result_dir]
    p = subprocess.Popen(study_command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    trace = os.path.join(second, "run", "trace_iterations.jsonl")
    started = os.path.join(second, "run.log")  # opened for the variant as it is spawned

    def second_is_where_we_want_it():
        if early:
            return os.path.exists(started)
        return os.path.exists(first) and os.path.exists(trace) and os.path.getsize(trace) > 0

    deadline = time.time() + 120
    while not second_is_where_we_want_it() and p.poll() is None and time.time() < deadline:
        time.sleep(0.01 if early else 0.05)
    running = processes_naming(second)
    p.send_signal(signal.SIGTERM)
    output, _ = p.communicate(timeout=120)
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
    if os.path.exists(os.path.join(result_dir, "study.json")):
        failures.append("a stopped study wrote study.json")
    records = {}
    for name in ("steps=400", "steps=800"):
        try:
            records[name] = json.load(open(os.path.join(result_dir, "variants", name, "result.json")))
        except OSError as e:
            failures.append(f"{name}: no result.json ({e})")
    if failures:
        return failures
    if records["steps=400"]["status"] != "ok" or records["steps=800"]["status"] != "stopped":
        failures.append(f"statuses {records['steps=400']['status']}, {records['steps=800']['status']}; "
                        "expected ok, stopped")
    stopped_summary = json.load(open(os.path.join(second, "run", "summary.json")))
    if stopped_summary.get("complete") or "stopped" not in stopped_summary:
        failures.append("the stopped variant's summary.json says complete, or not stopped")
    if not os.path.exists(os.path.join(second, "run", "checkpoint.bin")):
        failures.append("the stopped variant has no checkpoint.bin")

    if killed:  # as if the variant had been killed after its checkpoint
        record = os.path.join(second, "result.json")
        rec = json.load(open(record))
        rec.update(status="failed", exit_code=137, reason="killed by signal 9 (Killed)")
        json.dump(rec, open(record, "w"), indent=2)
    r = run(study_command if sbatch else study_command + ["--resume"])
    v = variants(result_dir) if r.returncode == 0 else {}
    how = {n: (x["status"], x["kept_from_earlier_study"], x["continued_from_checkpoint"]) for n, x in v.items()}
    if how != {"steps=400": ("ok", True, False), "steps=800": ("ok", False, True)}:
        failures.append(f"after --resume: {how} (exit {r.returncode}); expected steps=400 kept, steps=800 continued, "
                        "both ok")
        return failures
    if "restarted from" not in open(os.path.join(second, "run.log")).read():
        failures.append("the continued variant's run.log does not say 'restarted from'")
    if not v["steps=800"]["cpu_seconds"] > records["steps=800"]["cpu_seconds"]:
        failures.append(f"the continued variant's CPU {v['steps=800']['cpu_seconds']} does not include the stopped "
                        f"part's {records['steps=800']['cpu_seconds']}")
    direct = os.path.join(out, "direct")
    launcher = ["mpirun", "-n", str(np)] if np > 1 else []
    if run(launcher + [fe2heart, "run", os.path.join(second, "spec.json"), "--out", direct]).returncode != 0:
        return failures + ["the uninterrupted run failed"]
    continued = json.load(open(os.path.join(second, "run", "summary.json")))
    reference = json.load(open(os.path.join(direct, "summary.json")))
    a = [(h["time"], h["probes"]) for h in continued["history"]]
    b = [(h["time"], h["probes"]) for h in reference["history"]]
    print(f"continued: {len(a)} steps, uninterrupted: {len(b)}; last tip {a[-1][1]} vs {b[-1][1]}")
    if a != b:
        failures.append("the continued run's probe history differs from the uninterrupted run's")
    return failures

if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("fe2heart")
    parser.add_argument("data")
    parser.add_argument("out")
    parser.add_argument("--np", type=int, default=1)
    parser.add_argument("--sbatch")
    parser.add_argument("--early", action="store_true")
    parser.add_argument("--killed", action="store_true")
    a = parser.parse_args()
    problems = main(a.fe2heart, a.data, a.out, a.np, a.sbatch, a.early, a.killed)
    for f in problems:
        print("FAIL:", f)
    sys.exit(1 if problems else 0)
