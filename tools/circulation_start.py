#!/usr/bin/python3
"""Prints the closed-loop circulation's state at the end of a run as the spec's initial
values (`circulation.systemic/pulmonary.p_ar_init, p_ven_init`, `left_atrium/right_atrium
.V_init`), so that a beat started from them begins on the run's last cycle: run a scene
with `--beats N` until it is periodic, paste these keys into its spec, and one beat is a
periodic beat (configs/biv-beat-fe2.json was started so).

    /usr/bin/python3 tools/circulation_start.py RUN_DIR

Reads RUN_DIR/spec.json and the last row of RUN_DIR/circulation.csv. An atrium's volume
is V0 + p / E(t) with E(t) = E_min + (E_max − E_min) e(t), the cosine activation of
common/circulation/TimeVaryingElastance.cpp (keep in step) at the run's last time,
which is a whole number of periods: the next beat's t = 0. Unset keys take the defaults
of `fe2heart spec-doc` (Regazzoni 2022) that this script repeats for the atria."""
import csv
import json
import math
import os
import sys

MMHG = 133.322
# Regazzoni 2022 atria, in Pa and mm³ (circulation_keys.h: left_atrium(), right_atrium()).
ATRIUM_DEFAULTS = {
    "left_atrium": {"E_min": 0.09 * MMHG / 1e3, "E_max": 0.16 * MMHG / 1e3, "V0": 4000.0},
    "right_atrium": {"E_min": 0.07 * MMHG / 1e3, "E_max": 0.13 * MMHG / 1e3, "V0": 4000.0},
}


def activation(t, period, onset, contraction, relaxation):
    s = math.fmod(t - onset, period)
    if s < 0.0:
        s += period
    if s < contraction:
        return 0.5 * (1.0 - math.cos(math.pi * s / contraction))
    s -= contraction
    if s < relaxation:
        return 0.5 * (1.0 + math.cos(math.pi * s / relaxation))
    return 0.0


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    run = sys.argv[1]
    spec = json.load(open(os.path.join(run, "spec.json")))
    circ = spec.get("circulation", {})
    if circ.get("kind") != "closed_loop":
        sys.exit(f"circulation_start.py: {run}/spec.json: circulation.kind {circ.get('kind')!r}, expected closed_loop")
    period = circ["period"]
    last = list(csv.DictReader(open(os.path.join(run, "circulation.csv"))))[-1]
    t = float(last["t"])
    out = {}
    for vessels in ("systemic", "pulmonary"):
        out[vessels] = {"p_ar_init": round(float(last[f"p:{vessels}_arteries"]), 1),
                        "p_ven_init": round(float(last[f"p:{vessels}_veins"]), 1)}
    for atrium, defaults in ATRIUM_DEFAULTS.items():
        a = {**defaults, "onset": 0.8 * period, "contraction": 0.17 * period, "relaxation": 0.17 * period,
             **circ.get(atrium, {})}
        e = activation(t, period, a["onset"], a["contraction"], a["relaxation"])
        E = a["E_min"] + (a["E_max"] - a["E_min"]) * e
        out[atrium] = {"V_init": round(a["V0"] + float(last[f"p:{atrium}"]) / E, 1)}
    print(f"# the state of {run} at t = {t:g} s = {t / period:.4g} periods")
    print(json.dumps(out, indent=1))


if __name__ == "__main__":
    main()
