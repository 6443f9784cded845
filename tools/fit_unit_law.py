#!/usr/bin/python3
"""Fits a Holzapfel–Ogden macro law to the passive homogenized response of an FE² unit.

    /usr/bin/python3 tools/fit_unit_law.py RUN_SPEC [--model NAME] [--fe2heart BIN]

Takes the unit of model NAME (default: the first FE² model) of RUN_SPEC, drops its
cells' active tension and viscosity, and equilibrates it (`fe2heart unit`) under
isochoric macro gradients in the unit's frame (x fibre, y sheet, z normal): uniaxial
stretches along each axis, an equibiaxial fibre–sheet stretch (1.04–1.16) and the six
simple shears (0.05–0.2). The deviatoric Cauchy stresses are fitted by the eight
parameters of Holzapfel & Ogden 2009 (a, b, a_f, b_f, a_s, b_s, a_fs, b_fs; the law
the incompressible macro formulation sees: the pressure is its own unknown there),
Levenberg–Marquardt on log-parameters from the law's published values. Prints the
fitted parameters as the JSON of a `holzapfel_ogden` material and the fit's errors.
The active part is not fitted: a macro law's T_ref is the cells' times their volume
fraction (cells pulling in parallel), which the comparison of the beats tests."""
import argparse
import json
import os
import subprocess
import sys
import tempfile

import numpy as np

NAMES = ["a", "b", "af", "bf", "as", "bs", "afs", "bfs"]
PUBLISHED = [59.0, 8.023, 18472.0, 16.026, 2481.0, 11.12, 216.0, 11.436]  # Pa, Holzapfel & Ogden 2009
F0, S0 = np.array([1.0, 0, 0]), np.array([0, 1.0, 0])


def dev(s):
    return s - np.trace(s) / 3 * np.eye(3)


def holzapfel_ogden(F, p):
    """Deviatoric Cauchy stress of the law at an isochoric F (fibres resist only stretch)."""
    a, b, af, bf, as_, bs, afs, bfs = p
    C = F.T @ F
    I1, I4f, I4s, I8 = np.trace(C), F0 @ C @ F0, S0 @ C @ S0, F0 @ C @ S0
    S = a * np.exp(b * (I1 - 3)) * np.eye(3)
    if I4f > 1:
        S += 2 * af * (I4f - 1) * np.exp(bf * (I4f - 1) ** 2) * np.outer(F0, F0)
    if I4s > 1:
        S += 2 * as_ * (I4s - 1) * np.exp(bs * (I4s - 1) ** 2) * np.outer(S0, S0)
    S += afs * I8 * np.exp(bfs * I8 ** 2) * (np.outer(F0, S0) + np.outer(S0, F0))
    return dev(F @ S @ F.T)


def gradients():
    Fs = []
    for l in (1.04, 1.08, 1.12, 1.16):
        r = l ** -0.5
        Fs += [np.diag([l, r, r]), np.diag([r, l, r]), np.diag([r, r, l]), np.diag([l, l, l ** -2])]
    for g in (0.05, 0.1, 0.2):
        for i, j in ((0, 1), (0, 2), (1, 2), (1, 0), (2, 0), (2, 1)):
            F = np.eye(3)
            F[i, j] = g
            Fs.append(F)
    return Fs


def unit_stress(fe2heart, unit, F, scratch):
    spec = {"title": "fit_unit_law", "unit": unit, "Zbar_path": [(F - np.eye(3)).flatten(order="F").tolist()],
            "newton": {"rtol": 1e-10, "max_iterations": 30}}
    with open(scratch, "w") as f:
        json.dump(spec, f)
    out = subprocess.run([fe2heart, "unit", scratch], capture_output=True, text=True)
    if out.returncode != 0:
        sys.exit(f"fit_unit_law: fe2heart unit failed at F = {F.tolist()}: {out.stderr.strip()}")
    P = np.array(json.loads(out.stdout)["P_bar"]).reshape(3, 3, order="F")
    return dev(P @ F.T / np.linalg.det(F))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("spec")
    ap.add_argument("--model")
    ap.add_argument("--fe2heart", default=os.path.join(os.path.dirname(__file__), "..", "build", "tools", "fe2heart"))
    a = ap.parse_args()
    with open(a.spec) as f:
        run = json.load(f)
    models = run.get("models", {})
    name = a.model or next((k for k, m in models.items() if m.get("kind") == "fe2"), None)
    if name not in models or models[name].get("kind") != "fe2":
        sys.exit(f"fit_unit_law: {a.spec} has no FE² model {name!r}; its models: {', '.join(models)}")
    unit = json.loads(json.dumps(models[name]["unit"]))
    for material in unit.get("materials", {}).values():
        material.pop("active", None)
        material.pop("viscosity", None)
    with tempfile.TemporaryDirectory() as tmp:
        data = [(F, unit_stress(a.fe2heart, unit, F, os.path.join(tmp, "unit.json"))) for F in gradients()]
    scale = max(np.abs(d).max() for _, d in data)

    def residual(q):
        return np.concatenate([((holzapfel_ogden(F, np.exp(q)) - d) / scale).ravel() for F, d in data])

    q = np.log(PUBLISHED)
    for _ in range(100):  # Levenberg–Marquardt, forward-difference Jacobian
        r = residual(q)
        J = np.column_stack([(residual(q + 1e-6 * e) - r) / 1e-6 for e in np.eye(q.size)])
        A = J.T @ J
        step = np.linalg.solve(A + 1e-3 * np.diag(np.diag(A)) + 1e-12 * np.eye(q.size), -J.T @ r)
        lam = 1.0
        while lam > 1e-4 and np.linalg.norm(residual(q + lam * step)) > np.linalg.norm(r):
            lam /= 2
        q = q + lam * step
        if np.linalg.norm(lam * step) < 1e-9:
            break
    p = np.exp(q)
    rms = lambda v: np.linalg.norm(v) / np.sqrt(v.size)
    worst = max(np.abs(holzapfel_ogden(F, p) - d).max() / np.abs(d).max() for F, d in data)
    print(json.dumps({"model": "holzapfel_ogden", **{k: float(f"{v:.4g}") for k, v in zip(NAMES, p)}}))
    print(f"{len(data)} gradients; rms deviator error / largest stress: fitted {rms(residual(q)):.2e}, "
          f"published parameters {rms(residual(np.log(PUBLISHED))):.2e}; worst component, relative to its "
          f"gradient's largest: {worst:.2f}", file=sys.stderr)


if __name__ == "__main__":
    main()
