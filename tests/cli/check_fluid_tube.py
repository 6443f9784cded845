#!/usr/bin/python3
"""Checks configs/tube-flow.json's summary.json against Hagen–Poiseuille.

  check_fluid_tube.py SUMMARY.json

The flow starts from rest under a constant pressure drop ΔP and approaches
Q = πR⁴ΔP/(8μL). Checks, reading R, L, ΔP, μ from the run's spec.json:
  - the last step's outlet flux within 1 % of Q (P2/P1 holds the parabolic profile; the
    rest is the curved lumen's geometry and the last bit of the start-up),
  - inlet and outlet fluxes balance to 1e-8 Q at every step (incompressible),
  - the fluid's volume within 0.5 % of πR²L (the lumen's curved quadratic faces),
  - the flux grows over the first steps (the start-up).
Exits 1 naming the first failed check.
"""
import json
import math
import os
import sys


def main():
    summary = json.load(open(sys.argv[1]))
    spec = json.load(open(os.path.join(os.path.dirname(sys.argv[1]), "spec.json")))
    R, L = 1.0, 6.0  # configs/meshes/tube.msh (tools/meshes/tube_mesh.py --radius 1 --length 6)
    fluid = spec["fluid"]
    mu = fluid["viscosity"]
    p = {b["set"]: b["value"] for b in fluid["boundaries"] if b["kind"] == "pressure"}
    dP = p["inlet"] - p["outlet"]
    Q = math.pi * R**4 * dP / (8 * mu * L)
    h = summary["history"]
    failures = []
    last = h[-1]["observables"]
    print(f"Hagen–Poiseuille Q = {Q:.2f} mm³/s; last step: outlet {last['flux:outlet']:.2f}, "
          f"inlet {last['flux:inlet']:.2f}, volume {last['fluid_volume']:.4f} (πR²L {math.pi * R * R * L:.4f})")
    if abs(last["flux:outlet"] / Q - 1) > 0.01:
        failures.append(f"outlet flux {last['flux:outlet']:.2f} not within 1 % of {Q:.2f}")
    for s in h:
        o = s["observables"]
        if abs(o["flux:outlet"] + o["flux:inlet"]) > 1e-8 * Q:
            failures.append(f"t = {s['time']:.3g}: fluxes do not balance ({o['flux:inlet']} in, {o['flux:outlet']} out)")
            break
    if abs(last["fluid_volume"] / (math.pi * R * R * L) - 1) > 0.005:
        failures.append(f"fluid volume {last['fluid_volume']:.4f} not within 0.5 % of πR²L")
    if not (0 < h[0]["observables"]["flux:outlet"] < h[1]["observables"]["flux:outlet"] < h[2]["observables"]["flux:outlet"]):
        failures.append("the outlet flux does not grow over the first steps")
    for f in failures:
        print("FAIL:", f)
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
