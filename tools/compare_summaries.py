#!/usr/bin/env python3
"""Compares two runs' summary.json: every number must agree bit for bit (or to --rtol),
except timings and host facts, which differ between any two runs.

    tools/compare_summaries.py BEFORE/summary.json AFTER/summary.json [--rtol 0]

Residual histories written under their old keys ("residuals", "volume_residuals",
"cavity_residuals", one list per step) are compared with the per-field layout
("residuals": {"displacement": [...], "pressure": [...], "cavity_pressure": [...]}).
Exit 0 when they agree, 1 with the differing paths listed."""
import argparse
import json
import math
import re
import sys

# Keys whose values are measurements of this machine, not answers.
IGNORED = re.compile(r"(seconds|wall|cpu|elapsed|date|host|hostname|duration|_ms$|^ms_|time_s|"
                     r"throughput|memory_bytes|peak_rss|rss|started|finished|version|git|command)",
                     re.IGNORECASE)
OLD_FIELD_KEYS = {"residuals": "displacement", "volume_residuals": "pressure",
                  "cavity_residuals": "cavity_pressure"}


def per_field_residuals(step):
    """The step's residual histories keyed by field name, whichever layout it has."""
    if isinstance(step.get("residuals"), dict):
        out = dict(step["residuals"])
    else:
        out = {field: step[key] for key, field in OLD_FIELD_KEYS.items() if step.get(key)}
    return out


def normalise(node):
    if isinstance(node, dict):
        if "iterations" in node and ("residuals" in node or "micro_residuals" in node):
            node = dict(node)
            fields = per_field_residuals(node)
            for key in OLD_FIELD_KEYS:
                node.pop(key, None)
            node["residuals"] = fields
        return {k: normalise(v) for k, v in node.items() if not IGNORED.search(k)}
    if isinstance(node, list):
        return [normalise(v) for v in node]
    return node


def compare(a, b, path, rtol, out):
    if isinstance(a, dict) and isinstance(b, dict):
        for k in sorted(set(a) | set(b)):
            if k not in a or k not in b:
                out.append(f"{path}/{k}: only in {'after' if k not in a else 'before'}")
            else:
                compare(a[k], b[k], f"{path}/{k}", rtol, out)
    elif isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            out.append(f"{path}: {len(a)} entries before, {len(b)} after")
        for i, (x, y) in enumerate(zip(a, b)):
            compare(x, y, f"{path}/{i}", rtol, out)
    elif isinstance(a, (int, float)) and isinstance(b, (int, float)) and not isinstance(a, bool):
        if a == b or (math.isnan(a) and math.isnan(b)):
            return
        if rtol > 0 and abs(a - b) <= rtol * max(abs(a), abs(b)):
            return
        out.append(f"{path}: {a!r} before, {b!r} after")
    elif a != b:
        out.append(f"{path}: {a!r} before, {b!r} after")


def numbers(node, path=""):
    """Every number with its path."""
    if isinstance(node, dict):
        for k, v in node.items():
            yield from numbers(v, f"{path}/{k}")
    elif isinstance(node, list):
        for i, v in enumerate(node):
            yield from numbers(v, f"{path}/{i}")
    elif isinstance(node, (int, float)) and not isinstance(node, bool):
        yield path, node


def max_relative_difference(a, b):
    """(largest |x − y| relative to the largest |x| of the same quantity — the path with its
    indices as wildcards, e.g. /history/*/probes/tip/* — and that path), residual histories
    and Newton corrections left out (convergence noise below the tolerance)."""
    before, after = dict(numbers(a)), dict(numbers(b))
    family = lambda path: re.sub(r"/\d+", "/*", path)
    scale = {}
    for path, x in before.items():
        scale[family(path)] = max(scale.get(family(path), 0.0), abs(x))
    worst = (0.0, "")
    for path, x in before.items():
        if path not in after or "residuals" in path or "corrections" in path or after[path] == x:
            continue
        s = scale[family(path)]
        if s > 0:
            worst = max(worst, (abs(after[path] - x) / s, path))
    return worst


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("before")
    parser.add_argument("after")
    parser.add_argument("--rtol", type=float, default=0.0,
                        help="relative tolerance per number (default 0: bit for bit)")
    args = parser.parse_args(argv)
    with open(args.before) as f:
        before = normalise(json.load(f))
    with open(args.after) as f:
        after = normalise(json.load(f))
    diffs = []
    compare(before, after, "", args.rtol, diffs)
    worst = max_relative_difference(before, after)
    if worst[0] > 0:
        print(f"largest relative difference {worst[0]:.2e} at {worst[1]}")
    iters = [h.get("iterations") for h in before.get("history", [])], \
            [h.get("iterations") for h in after.get("history", [])]
    print("Newton iterations per step: " + ("identical" if iters[0] == iters[1] else "DIFFER"))
    for d in diffs[:50]:
        print(d)
    if len(diffs) > 50:
        print(f"... and {len(diffs) - 50} more")
    verdict = "the same answer as" if not diffs else f"{len(diffs)} differences from"
    print(f"{args.after}: {verdict} {args.before}"
          + (f" (rtol {args.rtol:g})" if args.rtol else " (bit for bit)"))
    return 1 if diffs else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
