#!/usr/bin/python3
"""Pressure–volume curves of a run: pv_curve.png in the run folder from its summary.json.

For every cavity of the spec, the volume after each step (history[*].cavity_volumes)
against the pressure of the loads on the cavity's surface (history[*].load_pressures),
starting from the undeformed volume at zero pressure. A run that stopped early ends its
history with the failed step, which has no volumes: the curve stops at the last
converged step. Needs Debian's python3-matplotlib.

    /usr/bin/python3 tools/pv_plot.py RUN_DIR [--out FILE]
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
    ap.add_argument("run_dir")
    ap.add_argument("--out", default=None, help="PNG file (default RUN_DIR/pv_curve.png)")
    a = ap.parse_args()
    path = os.path.join(a.run_dir, "summary.json")
    try:
        with open(path) as f:
            s = json.load(f)
    except (OSError, ValueError) as e:
        sys.exit(f"pv_plot: cannot read {path}: {e}")
    cavities = s.get("cavities", {})
    if not cavities:
        sys.exit(f"pv_plot: {path} has no cavities (add \"cavities\" to the spec)")
    fig, ax = plt.subplots(figsize=(5.5, 4.2))
    for name, c in cavities.items():
        loads = c.get("pressure_loads", [])
        V = [c["reference_volume"]]
        p = [0.0]
        for h in s["history"]:
            if name not in h.get("cavity_volumes", {}):
                continue  # the failed step of a run that stopped early
            V.append(h["cavity_volumes"][name])
            p.append(sum(h["load_pressures"][k] for k in loads) if loads else 0.0)
        ax.plot(V, [x / 1000.0 for x in p], "o-", ms=3, label=f"{name} ({c['surface']})")
    ax.set_xlabel("cavity volume (mesh units³)")
    ax.set_ylabel("cavity pressure (kPa)")
    ax.set_title(s.get("title", "")[:70], fontsize=9)
    ax.grid(alpha=0.3)
    ax.legend()
    fig.tight_layout()
    out = a.out or os.path.join(a.run_dir, "pv_curve.png")
    fig.savefig(out, dpi=120)
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
