#!/usr/bin/python3
"""Checks a beat with blood in the cavity against the same heart's lumped beat (issue 31
§3: the PV loop within a few percent of the lumped beat's, the same physiology ranges).

    check_blood_beat.py BLOOD_SUMMARY_JSON LUMPED_SUMMARY_JSON [--partial]

Over the beat (t > 0 after the end-diastolic inflation):
  - EDV, ESV and stroke volume within 5 % of the lumped beat's, EF within 3 points (the
    default FE² beat: EDV +0.1 %, ESV +4 %, SV −2.9 %, EF −1.7 points; the blood's
    inertia and the jet into the coarse cap's aortic ring load the ejecting wall more);
  - the peak pressure at the aortic ring within 10 % of the lumped beat's peak LV pressure
    and in 14–17 kPa (the mean blood pressure p_c is reported, not bounded: on a coarse
    base cap it includes the jet's pressure drop into the ring);
  - the arteries' pressure range within 5 % of the lumped beat's at both ends;
  - the blood's volume equals the cavity volume of the wall at every step (1e-9);
  - the beat ends within 2 % of the volume it started from.
Prints what the blood adds: the peak kinetic energy and the energy dissipated, against
the stroke work. Exit 1 naming every figure out of its bound.

With --partial the blood run is a part of the beat (t_end before the period; the beat's
figures need the whole beat): at t = 0 its volume within 1 % of the lumped beat's (the
filling through the mitral ring has reached end-diastole), the aortic ring opening within
one step of the lumped beat's aortic valve, the volume ejected by the run's end 0.7–1.02
of the lumped beat's by then (the blood's inertia and the jet into the ring slow the
early ejection: 0.78 on the default FE² beat at t = 0.1 s, which catches up by the end
of systole, ESV +4 %), the blood's volume the cavity's, no step cut back."""
import json
import sys


def beat(summary):
    return [h for h in summary["history"] if h["time"] > 1e-9]


def end_diastole(summary):
    return next(h for h in summary["history"] if h["time"] >= -1e-9)


def volume_defect(blood):
    """The largest relative difference of the blood's volume and the wall's cavity volume."""
    return max(abs(h["observables"]["fluid_volume"] / h["cavity_volumes"]["lv"] - 1) for h in blood["history"])


def main(blood_path, lumped_path, partial):
    blood, lumped = json.load(open(blood_path)), json.load(open(lumped_path))
    failures = []

    def bound(name, value, lo, hi, unit=""):
        ok = lo <= value <= hi
        print(f"{name:52s} {value:12.5g}{unit}  [{lo:.5g}, {hi:.5g}] {'ok' if ok else 'OUT'}")
        if not ok:
            failures.append(name)

    if partial:
        def at(summary, t):
            return next(h for h in summary["history"] if abs(h["time"] - t) < 1e-9)

        def aortic_opening(summary):
            return next(h["time"] for h in summary["history"] if h["circulation"]["lv"]["outflow_open"])

        t_end = blood["history"][-1]["time"]
        V0, V0_lumped = at(blood, 0.0)["cavity_volumes"]["lv"], at(lumped, 0.0)["cavity_volumes"]["lv"]
        bound("V(t = 0) with blood / lumped", V0 / V0_lumped, 0.99, 1.01)
        bound("aortic opening with blood − lumped (s)", aortic_opening(blood) - aortic_opening(lumped), -0.0101, 0.0101)
        ejected = V0 - blood["history"][-1]["cavity_volumes"]["lv"]
        ejected_lumped = V0_lumped - at(lumped, t_end)["cavity_volumes"]["lv"]
        bound(f"volume ejected by t = {t_end:.3g} s with blood / lumped", ejected / ejected_lumped, 0.7, 1.02)
        bound("peak aortic-ring flux (mm³/s)", max(h["observables"]["flux:aortic"] for h in blood["history"]), 1e3, 1e9)
        bound("max |blood volume / cavity volume − 1|", volume_defect(blood), 0.0, 1e-9)
        bound("cutbacks", sum(h["cutbacks"] for h in blood["history"]), 0, 0)
        if failures:
            sys.exit("check_blood_beat.py --partial: out of bounds: " + "; ".join(failures))
        return

    b, l = blood["circulation"]["cavities"]["lv"], lumped["circulation"]["cavities"]["lv"]
    for key in ("EDV", "ESV", "SV"):
        bound(f"{key} with blood / lumped", b[key] / l[key], 0.95, 1.05)
    bound("EF with blood − lumped (points)", 100 * (b["EF"] - l["EF"]), -3.0, 3.0)

    hist = beat(blood)
    ring_peak = max(h["observables"]["flux_pressure:aortic"] for h in hist)
    bound("peak aortic-ring pressure / lumped peak LV pressure", ring_peak / l["peak_pressure"], 0.90, 1.10)
    bound("peak aortic-ring pressure (kPa)", ring_peak / 1e3, 14.0, 17.0)
    print(f"{'peak mean blood pressure p_c (kPa, reported)':52s} {b['peak_pressure'] / 1e3:12.5g}")

    arteries = [h["compartment_pressures"]["lv.arterial"] for h in hist]
    arteries_lumped = [h["compartment_pressures"]["lv.arterial"] for h in beat(lumped)]
    bound("arteries min with blood / lumped", min(arteries) / min(arteries_lumped), 0.95, 1.05)
    bound("arteries max with blood / lumped", max(arteries) / max(arteries_lumped), 0.95, 1.05)

    bound("max |blood volume / cavity volume − 1|", volume_defect(blood), 0.0, 1e-9)
    V0, V1 = end_diastole(blood)["cavity_volumes"]["lv"], blood["history"][-1]["cavity_volumes"]["lv"]
    bound("volume change over the beat (relative)", abs(V1 - V0) / V0, 0.0, 0.02)

    # Pa·mm³ = 1e-9 J.
    times = [h["time"] for h in blood["history"]]
    dissipated = sum(h["observables"]["fluid_dissipation_rate"] * (t1 - t0)
                     for h, t0, t1 in zip(blood["history"][1:], times, times[1:]) if t1 > 1e-9)
    kinetic = max(h["observables"]["fluid_kinetic_energy"] for h in hist)
    print(f"blood: peak kinetic energy {kinetic * 1e-6:.3g} mJ, dissipated over the beat {dissipated * 1e-6:.3g} mJ; "
          f"stroke work {b['stroke_work'] * 1e-6:.4g} mJ with blood, {l['stroke_work'] * 1e-6:.4g} mJ lumped")
    if failures:
        sys.exit("check_blood_beat.py: out of bounds: " + "; ".join(failures))


if __name__ == "__main__":
    args = [a for a in sys.argv[1:] if a != "--partial"]
    if len(args) != 2:
        sys.exit(__doc__)
    main(args[0], args[1], "--partial" in sys.argv[1:])
