#!/usr/bin/python3
"""The biventricular heart with blood in both cavities (configs/biv-beat-blood*.json).

  check_biv_blood.py SUMMARY.json [--partial]

Checks, at every step: the blood's volume is the two cavities' volume (the wall's lumped
volumes of the same endocardia) to 1e-9; the moved blood mesh is valid (worst shape > 0);
each ring's flux is its valve's flow in the circulation (outflow rings: Q_out, inflow
rings: −Q_in, into the blood) to 1e-6 of the peak flow, after the inflation (while it
inflates the wall the inflow ring's flux and the reported Q_in differ by up to 0.7 %). Over the run: both ventricles
eject through their outflow rings (peak flux > 0 with the valve open). Without --partial
(a whole beat): both ejection fractions and end-diastolic volumes in human ranges.
Exits 1 naming the first failed check.
"""
import json
import sys

RINGS = {"lv": ("mitral", "aortic"), "rv": ("tricuspid", "pulmonary")}


def fail(msg):
    print("check_biv_blood.py: " + msg)
    sys.exit(1)


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    s = json.load(open(sys.argv[1]))
    partial = "--partial" in sys.argv[2:]
    history = s["history"]
    if not history:
        fail("no steps in the history")
    peak = {c: 0.0 for c in RINGS}
    scale = max(max(abs(h["circulation"][c][q]) for c in RINGS for q in ("Q_in", "Q_out")) for h in history)
    for h in history:
        o, v, circ = h["observables"], h["cavity_volumes"], h["circulation"]
        cavities = v["lv"] + v["rv"]
        if abs(o["fluid_volume"] / cavities - 1) > 1e-9:
            fail(f"step {h['step']}: blood {o['fluid_volume']:.6g} mm³, the cavities {cavities:.6g}")
        if not o["fluid_mesh_worst_shape"] > 0:
            fail(f"step {h['step']}: the blood mesh's worst shape {o['fluid_mesh_worst_shape']}")
        for c, (inflow, outflow) in RINGS.items():
            if circ[c]["phase"] == "inflation":
                continue
            # flux:<ring> is out of the blood: the outflow ring passes Q_out, the inflow ring −Q_in.
            for ring, want in ((outflow, circ[c]["Q_out"]), (inflow, -circ[c]["Q_in"])):
                if abs(o[f"flux:{ring}"] - want) > 1e-6 * scale:
                    fail(f"step {h['step']}: flux:{ring} {o[f'flux:{ring}']:.6g}, the circulation's {want:.6g}")
            if circ[c]["outflow_open"]:
                peak[c] = max(peak[c], o[f"flux:{outflow}"])
    for c, q in peak.items():
        if not q > 0:
            fail(f"{c}: no ejection through its {RINGS[c][1]} ring")
    print(f"{len(history)} steps: blood = cavities, rings = valve flows; peak ejection LV {peak['lv'] / 1e3:.0f} mL/s, "
          f"RV {peak['rv'] / 1e3:.0f} mL/s")
    if partial:
        return
    for c in RINGS:
        f = s["circulation"]["cavities"][c]
        print(f"{c}: EDV {f['EDV'] / 1e3:.1f} mL, EF {f['EF']:.3f}")
        if not 0.35 <= f["EF"] <= 0.75:
            fail(f"{c}: EF {f['EF']:.3f}, expected 0.35–0.75")
        if not 60e3 <= f["EDV"] <= 200e3:
            fail(f"{c}: EDV {f['EDV'] / 1e3:.1f} mL, expected 60–200 mL")


if __name__ == "__main__":
    main()
