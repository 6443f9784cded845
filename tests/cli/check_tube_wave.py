#!/usr/bin/python3
"""The pressure wave of configs/tube-fsi.json (or its short test version) against theory.

  check_tube_wave.py OUT_DIR --radius 1 --wall 0.3

A tube of lumen radius a and outer radius b = a + h, clamped at its ends (plane strain),
under a pressure p: Lamé's radial displacement at radius r is
    u(r) = (1 + ν)/E · p a²/(b² − a²) · [(1 − 2ν) r + b²/r],
so the lumen's area A = πa² grows by dA/dp = 2πa u(a)/p, and a long wave travels at the
Moens–Korteweg speed of that distensibility,
    c₀ = sqrt(A / (ρ dA/dp)) = sqrt(a p / (2 ρ u(a))).
A step in pressure is not a long wave: the wall's inertia makes its short waves slower
(in the 1D model 2ρc²/a = E'h/a² − ρ_s h ω²), so the front travels below c₀ and
spreads. Checked: every probe is reached in order along the tube; the front moves at a
steady speed (each probe-to-probe interval within 12 % of the fitted speed: a travelling
wave, not a diffusing one, whose arrivals would go as z²); the speed between 0.8 c₀ and
1.02 c₀ (measured 0.88 c₀ at Δt = 0.2 ms and 0.87 at 0.06 ms: the gap is the dispersion,
not the step); the wave's height at the first probe within 12 % of Lamé's u there (a
Newmark overshoot of a few % rides on it).
"""
import argparse
import json
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools"))
from wave_front import arrivals  # noqa: E402


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("out")
    parser.add_argument("--radius", type=float, required=True, help="lumen radius a (mm)")
    parser.add_argument("--wall", type=float, required=True, help="wall thickness h (mm)")
    args = parser.parse_args()
    spec = json.load(open(os.path.join(args.out, "spec.json")))
    summary = json.load(open(os.path.join(args.out, "summary.json")))
    material = spec["models"]["wall"]["material"]
    E, nu = material["E"], material["nu"]
    rho = spec["fluid"]["density"]
    p = next(b["value"] for b in spec["fluid"]["boundaries"] if b["kind"] == "pressure" and b["set"] == "inlet")
    a, b = args.radius, args.radius + args.wall

    def lame(r):
        return (1 + nu) / E * p * a * a / (b * b - a * a) * ((1 - 2 * nu) * r + b * b / r)

    c0 = math.sqrt(a * p / (2 * rho * lame(a)))
    names, z, t, height, threshold, arrive = arrivals(summary, spec["probes"], "wall_z", 0.5)
    failures = []
    if any(x is None for x in arrive):
        failures.append(f"probes not reached: {[n for n, x in zip(names, arrive) if x is None]}")
    else:
        if any(t1 <= t0 for t0, t1 in zip(arrive, arrive[1:])):
            failures.append(f"arrivals out of order along the tube: {arrive}")
    if not failures:
        n = len(z)
        zm, tm = sum(z) / n, sum(arrive) / n
        speed = sum((zi - zm) * (ti - tm) for zi, ti in zip(z, arrive)) / sum((ti - tm) ** 2 for ti in arrive)
        print(f"front speed {speed / 1e3:.3f} m/s; Moens–Korteweg with Lamé's distensibility c0 = {c0 / 1e3:.3f} m/s "
              f"(ratio {speed / c0:.3f})")
        for k in range(1, n):
            step = (z[k] - z[k - 1]) / (arrive[k] - arrive[k - 1])
            print(f"  {names[k - 1]} -> {names[k]}: {step / 1e3:.3f} m/s")
            if abs(step / speed - 1) > 0.12:
                failures.append(f"{names[k - 1]} -> {names[k]}: {step:.0f} mm/s, not within 12 % of {speed:.0f}")
        if not 0.8 * c0 <= speed <= 1.02 * c0:
            failures.append(f"front speed {speed:.0f} mm/s outside [0.8, 1.02] c0 = [{0.8 * c0:.0f}, {1.02 * c0:.0f}]")
    r_probe = math.hypot(*spec["probes"][names[0]][:2])
    wave = threshold / 0.5
    print(f"wave height at {names[0]} {wave:.4f} mm; Lamé u({r_probe}) = {lame(r_probe):.4f} mm")
    if abs(wave / lame(r_probe) - 1) > 0.12:
        failures.append(f"wave height {wave:.4f} mm not within 12 % of Lamé's {lame(r_probe):.4f} mm")
    for f in failures:
        print("FAIL:", f)
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
