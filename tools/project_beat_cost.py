#!/usr/bin/python3
"""Projects the core-hours of one beat at the paper's size (6144 units of ≈ 26k DOF,
400 steps) from a measured beat's rates and measured unit costs.

    /usr/bin/python3 tools/project_beat_cost.py RUN_DIR SMALL.json LARGE.json [--units 6144] [--steps 400]
        [--macro MACRO_DIR]

RUN_DIR   a beat run with FE² units (its summary.json): the rates per step and per
          unit-iteration, and the micro CPU it spent;
SMALL     `fe2heart bench unit --dofs D` at the beat's own unit size (D ≈ its DOF);
LARGE     `fe2heart bench unit --dofs 26000` (the paper's unit), same flags.

Per unit-iteration, from the bench (a passive neo-Hookean unit of that size):
    t = assembly + g · (iteration − assembly) / g_bench + r · refresh
with the beat's GMRES iterations g and refreshes r per unit-iteration. The beat's units
do more than the bench's (Holzapfel–Ogden cells, viscosity, Land 2017 sub-steps): that
extra, measured = beat's micro CPU per unit-iteration − t(SMALL), is scaled by the number
of elements (LARGE / SMALL) and added. It keeps the beat's Newton iterations per step and
its cells' sub-steps per step (10 ms steps here; the paper's 2 ms steps would need fewer of
both), so the projection is an upper estimate. Every input is printed beside the result.

With --macro MACRO_DIR (a run of the macro at the paper's size, tools/bench_macro.sh), the
macro per Newton iteration is added: RUN_DIR's mix of iterations (factorizing, kept-factor,
converged check: its trace) times MACRO_DIR's medians of each kind (the busiest
coordinator's CPU). With one unit per worker the workers wait while the macro solves, so the
beat's core-hours are (units + coordinators) × iterations × (unit-iteration + macro), and
Macro/Entire = macro / (unit-iteration + macro) (perfect balance: a lower bound)."""
import argparse
import json
import os
import sys


def load(path):
    try:
        with open(path) as f:
            return json.load(f)
    except (OSError, ValueError) as e:
        sys.exit(f"project_beat_cost.py: cannot read {path}: {e}")


def bench_bits(b, name):
    """The double-precision unit's, or the single/half factor's when the bench timed one."""
    src = b.get("single", b)
    need = ("assembly_ms", "iteration_ms", "iteration_gmres_iterations", "refresh_ms")
    missing = [k for k in need if k not in src]
    if missing:
        sys.exit(f"project_beat_cost.py: {name}: no {', '.join(missing)}; expected `fe2heart bench unit` output")
    return {k: src[k] for k in need} | {"dofs": b["dofs"], "elements": b["elements"],
                                        "factor": src.get("factor", b.get("factor"))}


def per_unit_iteration_ms(b, gmres, refreshes):
    per_gmres = (b["iteration_ms"] - b["assembly_ms"]) / max(1.0, b["iteration_gmres_iterations"])
    return b["assembly_ms"] + gmres * per_gmres + refreshes * b["refresh_ms"]


def iterations(run_dir):
    path = os.path.join(run_dir, "trace_iterations.jsonl")
    try:
        with open(path) as f:
            return [json.loads(line) for line in f if line.strip()]
    except (OSError, ValueError) as e:
        sys.exit(f"project_beat_cost.py: cannot read {path}: {e}")


def kind(it):
    if "macro_factorized" not in it:
        return None
    if it["macro_factorized"] > 0:
        return "factorizing"
    return "kept" if it["solve"] > 0 else "none"


def macro_per_iteration(run_dir, macro_dir):
    """RUN_DIR's mix of macro-solve kinds × MACRO_DIR's CPU medians per kind (seconds)."""
    import statistics
    mine, theirs = iterations(run_dir), iterations(macro_dir)
    if any(kind(it) is None for it in mine + theirs):
        sys.exit("project_beat_cost.py: --macro: a trace without macro_factorized (a run of an older fe2heart)")
    cost = {}
    for k in ("factorizing", "kept", "none"):
        xs = [it["macro_cpu_max"] for it in theirs if kind(it) == k]
        cost[k] = statistics.median(xs) if xs else statistics.median(it["macro_cpu_max"] for it in theirs)
    mix = {k: sum(kind(it) == k for it in mine) / len(mine) for k in cost}
    coordinators = max(it["coordinators"] for it in theirs)
    return sum(mix[k] * cost[k] for k in cost), mix, cost, coordinators


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("run_dir")
    ap.add_argument("small")
    ap.add_argument("large")
    ap.add_argument("--units", type=int, default=6144)
    ap.add_argument("--steps", type=int, default=400)
    ap.add_argument("--macro", help="a run of the macro at the paper's size (tools/bench_macro.sh)")
    a = ap.parse_args()
    s = load(os.path.join(a.run_dir, "summary.json"))
    small, large = bench_bits(load(a.small), a.small), bench_bits(load(a.large), a.large)
    units, newton, steps = s["points"], s["newton_iterations"], s["steps"]
    if not units or not newton or "micro_cpu_seconds" not in s:
        sys.exit(f"project_beat_cost.py: {a.run_dir}: not a run with FE² units")
    unit_its = units * newton
    g, r = s["gmres_iterations"] / unit_its, s["refreshes"] / unit_its
    newton_per_step = newton / steps
    measured_ms = 1e3 * s["micro_cpu_seconds"] / unit_its
    extra_ms = max(0.0, measured_ms - per_unit_iteration_ms(small, g, r))
    scale = large["elements"] / small["elements"]
    large_ms = per_unit_iteration_ms(large, g, r) + extra_ms * scale
    core_seconds = a.units * a.steps * newton_per_step * large_ms / 1e3
    print(f"beat {a.run_dir}: {units} units, {steps} steps, {newton_per_step:.2f} Newton iterations per step, "
          f"{g:.2f} GMRES iterations and {r:.4f} refreshes per unit-iteration (measured)")
    print(f"  micro CPU per unit-iteration {measured_ms:.3f} ms (measured); the bench unit of "
          f"{small['dofs']} DOF with these rates {per_unit_iteration_ms(small, g, r):.3f} ms; "
          f"the cells' extra {extra_ms:.3f} ms")
    print(f"unit of {large['dofs']} DOF ({large['factor']}): assembly {large['assembly_ms']:.1f} ms, iteration "
          f"{large['iteration_ms']:.1f} ms ({large['iteration_gmres_iterations']:g} GMRES), refresh "
          f"{large['refresh_ms']:.0f} ms (measured)")
    print(f"  per unit-iteration with the beat's rates {per_unit_iteration_ms(large, g, r):.1f} ms + the cells' extra "
          f"x{scale:.0f} elements {extra_ms * scale:.1f} ms = {large_ms:.1f} ms (projected)")
    print(f"projected: {a.units} units x {a.steps} steps x {newton_per_step:.2f} x {large_ms:.1f} ms = "
          f"{core_seconds:.3g} core-seconds = {core_seconds / 3600:.0f} core-hours per beat")
    if a.macro:
        macro_s, mix, cost, coordinators = macro_per_iteration(a.run_dir, a.macro)
        micro_s = large_ms / 1e3
        its = a.steps * newton_per_step
        total = (a.units + coordinators) * its * (micro_s + macro_s)
        print(f"macro of {a.macro} ({coordinators} coordinator(s), busiest coordinator's CPU, measured): "
              + ", ".join(f"{k} {cost[k]:.3f} s x {mix[k]:.2f} of the beat's iterations" for k in cost)
              + f" = {macro_s:.3f} s per Newton iteration")
        print(f"  one unit per worker: Entire per iteration {micro_s:.3f} + {macro_s:.3f} s, Macro/Entire "
              f"{macro_s / (micro_s + macro_s):.3f}; ({a.units} + {coordinators}) cores x {its:.0f} iterations = "
              f"{total / 3600:.0f} core-hours per beat (projected)")


if __name__ == "__main__":
    main()
