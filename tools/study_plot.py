#!/usr/bin/python3
"""Error against CPU time of a study: pareto.png in the study folder from its study.json.

Each variant that ran is a point (CPU seconds of its processes, its error against the
reference) on log axes, labelled with its name; the Pareto front (no other variant both
cheaper and more accurate) is joined by a line. The reference itself (error 0) sits on the
bottom edge, drawn as a star; failed variants are listed in the title. Needs Debian's
python3-matplotlib.

    /usr/bin/python3 tools/study_plot.py STUDY_DIR [--out FILE]
"""
import argparse
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("study_dir")
    ap.add_argument("--out", default=None, help="PNG file (default STUDY_DIR/pareto.png)")
    a = ap.parse_args()
    path = os.path.join(a.study_dir, "study.json")
    try:
        with open(path) as f:
            s = json.load(f)
    except (OSError, ValueError) as e:
        sys.exit(f"study_plot: cannot read {path}: {e}")
    ran = [v for v in s["variants"] if v["status"] == "ok" and v["error"] is not None]
    failed = [v["name"] for v in s["variants"] if v["status"] != "ok"]
    if not ran:
        sys.exit(f"study_plot: {path}: no variant has an error to plot")
    positive = [v["error"] for v in ran if v["error"] > 0]
    # Zero errors (the reference, or an identical answer) on a floor below the smallest one.
    floor = min(positive) / 10 if positive else 1e-16
    fig, ax = plt.subplots(figsize=(6.4, 4.6))
    for v in ran:
        err = v["error"] if v["error"] > 0 else floor
        marker = "*" if v["error"] == 0 else "o"
        colour = "tab:red" if v["pareto"] else "tab:blue"
        ax.plot(v["cpu_seconds"], err, marker, color=colour, ms=11 if marker == "*" else 6)
        ax.annotate(v["name"] + (" (reference)" if v.get("reference") else ""), (v["cpu_seconds"], err),
                    textcoords="offset points", xytext=(5, 4), fontsize=7)
    front = sorted((v for v in ran if v["pareto"]), key=lambda v: v["cpu_seconds"])
    if len(front) > 1:
        ax.plot([v["cpu_seconds"] for v in front], [v["error"] if v["error"] > 0 else floor for v in front],
                "-", color="tab:red", lw=1, label="Pareto front")
        ax.legend(fontsize=8)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel(f"CPU seconds ({s['np']} rank{'s' if s['np'] != 1 else ''} per variant)")
    ax.set_ylabel("error: max |q - q_ref| / max |q_ref|")
    title = (s.get("title") or os.path.basename(s["study"]))[:70]
    title += f"\nquantities: {', '.join(s['quantities'])}; reference: {s['reference'].get('name', '')}"
    if failed:
        title += f"\nfailed: {', '.join(failed)}"
    ax.set_title(title, fontsize=8)
    ax.grid(alpha=0.3, which="both")
    fig.tight_layout()
    out = a.out or os.path.join(a.study_dir, "pareto.png")
    fig.savefig(out, dpi=120)
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
