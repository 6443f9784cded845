#!/usr/bin/python3
"""Checks that a coupled LV beat's summary.json lands in human physiology (issue: the
FE² heart beats like a heart). Over the beat (the steps after the end-diastolic
inflation, t > 0):
    EF 50–65 %, peak LV pressure 14–17 kPa, end-diastolic pressure 0.7–1.6 kPa,
    aortic (root) pressure 9–16 kPa, stroke volume 55–100 mL,
and the beat is periodic: it ends within 2 % of the LV volume and the arterial
pressure it started from at end-diastole (t = 0).

    check_physiology.py SUMMARY_JSON"""
import json
import sys

RANGES = {"EF": (0.50, 0.65), "peak LV pressure (kPa)": (14.0, 17.0),
          "end-diastolic pressure (kPa)": (0.7, 1.6), "aortic pressure min (kPa)": (9.0, 16.0),
          "aortic pressure max (kPa)": (9.0, 16.0), "stroke volume (mL)": (55.0, 100.0),
          "EDV (mL)": (100.0, 160.0)}


def figures(s):
    hist = s["history"]
    lv = s["circulation"]["cavities"]["lv"]
    start = next(i for i, h in enumerate(hist) if h["time"] >= -1e-12)  # t = 0: end-diastole
    beat = hist[start + 1:]
    aortic = [h["compartment_pressures"]["lv.proximal"] for h in beat]
    V0, V1 = hist[start]["cavity_volumes"]["lv"], hist[-1]["cavity_volumes"]["lv"]
    a0, a1 = (hist[start]["compartment_pressures"]["lv.arterial"], hist[-1]["compartment_pressures"]["lv.arterial"])
    f = {"EF": lv["EF"], "peak LV pressure (kPa)": lv["peak_pressure"] / 1e3,
         "end-diastolic pressure (kPa)": hist[start]["compartment_pressures"]["lv"] / 1e3,
         "aortic pressure min (kPa)": min(aortic) / 1e3, "aortic pressure max (kPa)": max(aortic) / 1e3,
         "stroke volume (mL)": lv["SV"] / 1e3, "EDV (mL)": lv["EDV"] / 1e3}
    periodic = {"volume": abs(V1 - V0) / V0, "arterial pressure": abs(a1 - a0) / a0}
    return f, periodic


def main():
    s = json.load(open(sys.argv[1]))
    f, periodic = figures(s)
    ok = True
    for name, (lo, hi) in RANGES.items():
        inside = lo <= f[name] <= hi
        ok = ok and inside
        print(f"{name:32s} {f[name]:8.3f}   expected {lo}–{hi}{'' if inside else '   OUT OF RANGE'}")
    for name, change in periodic.items():
        inside = change < 0.02
        ok = ok and inside
        print(f"change of the {name} over the beat {100 * change:.2f} %   expected < 2 %{'' if inside else '   NOT PERIODIC'}")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
