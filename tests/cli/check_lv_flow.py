#!/usr/bin/python3
"""Checks configs/lv-flow-prescribed.json's run: blood fills through the mitral ring and
leaves through the aortic ring as the circulation's valves say, and the mid-plane picture
is drawn.

  check_lv_flow.py OUT_DIR

Checks (summary.json history, observables per step):
  - the beat fills and ejects: the blood's volume falls by at least 30 % of its largest
    value during the beat and comes back within 10 % of it by the beat's end;
  - no ring passes blood the wrong way: mitral flux ≤ 0 (in), aortic flux ≥ 0 (out), to
    1 % of the peak flow (a shut ring passes nothing: its nodes stick);
  - never both at once beyond 1 % of the peak (the valves alternate);
  - the blood's volume changes by what the rings pass: |fluid_volume_imbalance| below
    5 % of the peak flow at every step;
  - tools/fluid_plane_plot.py draws end of filling and peak ejection.
Exits 1 naming the first failed check.
"""
import json
import os
import subprocess
import sys


def fail(msg):
    print("check_lv_flow.py: " + msg)
    sys.exit(1)


def main():
    out = sys.argv[1]
    h = [s for s in json.load(open(os.path.join(out, "summary.json")))["history"] if s["time"] > 0]
    obs = lambda k: [s["observables"][k] for s in h]
    V, mitral, aortic, imbalance = obs("fluid_volume"), obs("flux:mitral"), obs("flux:aortic"), obs("fluid_volume_imbalance")
    peak = max(max(aortic), -min(mitral))
    V_max, V_min = max(V), min(V)
    print(f"blood volume {V_min / 1e3:.1f}–{V_max / 1e3:.1f} mL, end {V[-1] / 1e3:.1f} mL; peak flow {peak / 1e3:.0f} mL/s; "
          f"largest imbalance {max(map(abs, imbalance)) / 1e3:.2f} mL/s")
    if V_min > 0.7 * V_max:
        fail(f"the blood's volume fell only to {V_min / V_max:.2f} of its largest (expected an ejection below 0.7)")
    if V[-1] < 0.9 * V_max:
        fail(f"the beat ends at {V[-1] / V_max:.2f} of the largest volume (expected refilled above 0.9)")
    for s, m, a, i in zip(h, mitral, aortic, imbalance):
        if m > 0.01 * peak or a < -0.01 * peak:
            fail(f"t = {s['time']:.3f}: a ring passes blood the wrong way (mitral {m:.0f}, aortic {a:.0f} mm³/s)")
        if -m > 0.01 * peak and a > 0.01 * peak:
            fail(f"t = {s['time']:.3f}: both rings pass blood (mitral {m:.0f}, aortic {a:.0f} mm³/s)")
        if abs(i) > 0.05 * peak:
            fail(f"t = {s['time']:.3f}: volume imbalance {i:.0f} mm³/s, above 5 % of the peak flow {peak:.0f}")
    png = os.path.join(out, "fluid_plane.png")
    subprocess.run(["/usr/bin/python3", os.path.join(os.path.dirname(__file__), "../../tools/fluid_plane_plot.py"), out,
                    "--png", png], check=True)
    if not os.path.getsize(png) > 10000:
        fail(f"{png}: no picture")
    print("ok")


if __name__ == "__main__":
    main()
