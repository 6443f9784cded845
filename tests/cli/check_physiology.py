#!/usr/bin/python3
"""Checks that a coupled beat's summary.json lands in human physiology (issue: the FE²
heart beats like a heart). Over the last beat (the steps after the end-diastolic
inflation, t > 0, or of the last period with --beats N):
    LV: EF 50–65 %, peak pressure 14–17 kPa, end-diastolic pressure 0.7–1.6 kPa,
        aortic (root or systemic arterial) pressure 9–16 kPa, stroke volume 55–100 mL,
        EDV 100–160 mL;
and the beat is periodic: it ends within 2 % of the LV volume and the arterial pressure
it started from at end-diastole (t = 0). A biventricular beat (a cavity "rv") also:
    RV: EF 45–65 %, peak pressure 2.5–4.5 kPa; LV and RV stroke volumes within 5 % of
        each other; the RV volume periodic to 2 % as well.
The aortic pressure is the Windkessel's proximal compartment (lv.proximal) or the closed
loop's systemic arteries.

    check_physiology.py SUMMARY_JSON"""
import json
import sys

LV_RANGES = {"EF": (0.50, 0.65), "peak LV pressure (kPa)": (14.0, 17.0),
             "end-diastolic pressure (kPa)": (0.7, 1.6), "aortic pressure min (kPa)": (9.0, 16.0),
             "aortic pressure max (kPa)": (9.0, 16.0), "stroke volume (mL)": (55.0, 100.0),
             "EDV (mL)": (100.0, 160.0)}
RV_RANGES = {"RV EF": (0.45, 0.65), "peak RV pressure (kPa)": (2.5, 4.5),
             "LV/RV stroke volume mismatch (%)": (0.0, 5.0)}
PERIODIC = 0.02  # largest relative change over the beat


def aortic_compartment(pressures):
    for name in ("lv.proximal", "systemic_arteries"):
        if name in pressures:
            return name
    sys.exit(f"check_physiology.py: no aortic compartment among {sorted(pressures)}")


def arterial_compartment(pressures):
    return "lv.arterial" if "lv.arterial" in pressures else "systemic_arteries"


def figures(s):
    hist = s["history"]
    cavities = s["circulation"]["cavities"]
    lv = cavities["lv"]
    # The last beat's end-diastole: t = 0 after the inflation, or one period before the end.
    t_start = max(0.0, hist[-1]["time"] - s["circulation"]["period"])
    start = next(i for i, h in enumerate(hist) if h["time"] >= t_start - 1e-9)
    beat = hist[start + 1:]
    aortic = [h["compartment_pressures"][aortic_compartment(h["compartment_pressures"])] for h in beat]
    arterial = arterial_compartment(hist[start]["compartment_pressures"])
    f = {"EF": lv["EF"], "peak LV pressure (kPa)": lv["peak_pressure"] / 1e3,
         "end-diastolic pressure (kPa)": hist[start]["compartment_pressures"]["lv"] / 1e3,
         "aortic pressure min (kPa)": min(aortic) / 1e3, "aortic pressure max (kPa)": max(aortic) / 1e3,
         "stroke volume (mL)": lv["SV"] / 1e3, "EDV (mL)": lv["EDV"] / 1e3}
    a0, a1 = (hist[start]["compartment_pressures"][arterial], hist[-1]["compartment_pressures"][arterial])
    periodic = {"arterial pressure": abs(a1 - a0) / a0}
    for name in cavities:
        V0, V1 = hist[start]["cavity_volumes"][name], hist[-1]["cavity_volumes"][name]
        periodic[f"{name.upper()} volume"] = abs(V1 - V0) / V0
    ranges = dict(LV_RANGES)
    if "rv" in cavities:
        rv = cavities["rv"]
        f["RV EF"] = rv["EF"]
        f["peak RV pressure (kPa)"] = rv["peak_pressure"] / 1e3
        f["LV/RV stroke volume mismatch (%)"] = 100 * abs(lv["SV"] - rv["SV"]) / max(lv["SV"], rv["SV"])
        ranges.update(RV_RANGES)
    return f, ranges, periodic


def main():
    s = json.load(open(sys.argv[1]))
    f, ranges, periodic = figures(s)
    ok = True
    for name, (lo, hi) in ranges.items():
        inside = lo <= f[name] <= hi
        ok = ok and inside
        print(f"{name:34s} {f[name]:8.3f}   expected {lo}–{hi}{'' if inside else '   OUT OF RANGE'}")
    for name, change in periodic.items():
        inside = change < PERIODIC
        ok = ok and inside
        print(f"change of the {name} over the beat {100 * change:.2f} %   expected < {100 * PERIODIC:g} %"
              f"{'' if inside else '   NOT PERIODIC'}")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
