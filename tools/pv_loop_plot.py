#!/usr/bin/python3
"""Pressure–volume loops of a run with a circulation (`fe2heart circulation`, or `run`).

Reads RUN_DIR/circulation.csv and draws RUN_DIR/pv_loop.png: left, each cavity's
pressure against volume (earlier beats faint, the last beat bold); right, cavity and
arterial pressures against time. And RUN_DIR/pv_time.png: pressures (top) and cavity
volumes (bottom) against time, the valve phases shaded. Needs Debian's python3-matplotlib.

    /usr/bin/python3 tools/pv_loop_plot.py RUN_DIR [--out FILE] [--time-out FILE]
"""
import argparse
import csv
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

MMHG = 133.322387415  # Pa


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("run_dir")
    ap.add_argument("--out", default=None, help="PNG file (default RUN_DIR/pv_loop.png)")
    ap.add_argument("--time-out", default=None, help="PNG file (default RUN_DIR/pv_time.png)")
    a = ap.parse_args()
    path = os.path.join(a.run_dir, "circulation.csv")
    try:
        with open(path) as f:
            rows = list(csv.DictReader(f))
        with open(os.path.join(a.run_dir, "summary.json")) as f:
            summary = json.load(f)
    except (OSError, ValueError) as e:
        sys.exit(f"pv_loop_plot: cannot read {a.run_dir}: {e}")
    # The cavities of the CSV (a `run` summary also lists cavities without a circulation).
    cavities = [k[2:] for k in rows[0] if k.startswith("p_")]
    t = [float(r["t"]) for r in rows]
    # The last beat's first row: the last period's (the rows start at t = 0, end-diastole
    # after an inflation; a run shorter than a period is one beat).
    circ = summary.get("circulation")
    if isinstance(circ, dict) and circ.get("period", 0.0) > 0:  # `fe2heart run`
        period = circ["period"]
        start = next(i for i, x in enumerate(t) if x >= t[-1] - period * (1 + 1e-9))
    else:  # `fe2heart circulation`: whole beats of steps // beats rows
        beats, steps = summary.get("beats", 0), summary.get("steps", len(rows) - 1)
        start = max(0, len(rows) - 1 - (steps // beats if beats else steps))
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(11, 4.3))
    for name in cavities:
        V = [float(r[f"V_{name}"]) / 1000.0 for r in rows]
        p = [float(r[f"p_{name}"]) / MMHG for r in rows]
        line, = ax.plot(V[start:], p[start:], lw=2, label=f"{name} (last beat)")
        if start > 0:
            ax.plot(V[: start + 1], p[: start + 1], lw=0.7, alpha=0.35, color=line.get_color())
        bx.plot(t, p, lw=1.2, color=line.get_color(), label=f"p {name}")
    for key in rows[0]:
        if key.startswith("p:") and (key.endswith(".proximal") or key.endswith("_arteries")):
            bx.plot(t, [float(r[key]) / MMHG if r[key] else float("nan") for r in rows], lw=0.9,
                    ls="--", label=key[2:])
    ax.set_xlabel("volume (mL)")
    ax.set_ylabel("pressure (mmHg)")
    ax.set_title("pressure–volume loop", fontsize=10)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    bx.set_xlabel("time (s)")
    bx.set_ylabel("pressure (mmHg)")
    bx.set_title(summary.get("title", "")[:70], fontsize=9)
    bx.grid(alpha=0.3)
    bx.legend(fontsize=7)
    fig.tight_layout()
    out = a.out or os.path.join(a.run_dir, "pv_loop.png")
    fig.savefig(out, dpi=110)
    print(f"wrote {out}")
    plot_against_time(rows, cavities, t, summary, a.time_out or os.path.join(a.run_dir, "pv_time.png"))


# Phase names of circulation.csv (phase_<cavity>) and the shade of each.
PHASE_SHADES = {"isovolumic contraction": "#f4cccc", "ejection": "#fce5cd",
                "isovolumic relaxation": "#d9ead3", "filling": None}


def plot_against_time(rows, cavities, t, summary, out):
    fig, (px, vx) = plt.subplots(2, 1, figsize=(8, 6), sharex=True)
    for name in cavities:
        line, = px.plot(t, [float(r[f"p_{name}"]) / MMHG for r in rows], lw=1.5, label=f"p {name}")
        vx.plot(t, [float(r[f"V_{name}"]) / 1000.0 for r in rows], lw=1.5, color=line.get_color(),
                label=f"V {name}")
    for key in rows[0]:
        if key.startswith("p:") and (key.endswith(".proximal") or key.endswith("_arteries")):
            px.plot(t, [float(r[key]) / MMHG if r[key] else float("nan") for r in rows], lw=0.9, ls="--",
                    label=key[2:])
    # The first cavity's phases as bands, so a reader sees where the valves open and shut.
    key = f"phase_{cavities[0]}" if cavities else None
    if key in rows[0]:
        start = 0
        for k in range(1, len(rows) + 1):
            if k == len(rows) or rows[k][key] != rows[start][key]:
                shade = PHASE_SHADES.get(rows[start][key])
                if shade and k > start:
                    for ax in (px, vx):
                        ax.axvspan(t[start], t[min(k, len(t) - 1)], color=shade, lw=0)
                start = k
    px.set_ylabel("pressure (mmHg)")
    px.set_title(summary.get("title", "")[:80], fontsize=9)
    vx.set_ylabel("volume (mL)")
    vx.set_xlabel("time (s)")
    for ax in (px, vx):
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7, loc="upper right")
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
