#!/usr/bin/python3
"""Render PNG figures from the load-balance traces of an fe2heart run.

Usage:
    /usr/bin/python3 tools/trace_plot.py RUN_DIR [--out OUT_DIR] [--iteration STEP:ITER]

Reads the JSON Lines traces that the coordinator writes into RUN_DIR
(trace_iterations.jsonl, trace_workers.jsonl, trace_units.jsonl) and writes,
into OUT_DIR (default: RUN_DIR), the figures below, printing each path written:

  cumulative_times.png  Top: cumulative Entire, Micro+L+C and Macro wall time
                        (summed over each step's Newton iterations) against the
                        time step, titled with the final ratios Micro+L+C/Entire
                        and Macro/Entire (the paper's Fig. 7).  Bottom: the
                        cumulative per-unit CPU work split into refresh jobs
                        (factorization + characteristic modes, and the rest of
                        those jobs) and reuse jobs.
  gantt.png             Gantt chart of the workers for one Newton iteration
                        (default: the one with the largest max/mean busy CPU
                        imbalance; choose another with --iteration STEP:ITER):
                        per worker rank, busy (busy_wall from t_begin) and idle
                        up to the end of the iteration's micro phase, annotated
                        with units held and jobs run.
  gantt_all.png         Busy bars of every iteration for every worker against
                        wall time since run start, a thin line at each
                        iteration's start and a marker where units migrated.
  imbalance.png         Per iteration: max/mean of worker busy CPU time (line at
                        1.10) and the number of migrations (bars, second axis).

Needs only the Python standard library and matplotlib (Debian: python3-matplotlib).
Exit codes: 0 success, 2 unusable input (missing, empty or malformed trace files,
unknown --iteration).
"""

import argparse
import json
import math
import os
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402
from matplotlib.patches import Patch  # noqa: E402
from matplotlib.ticker import MaxNLocator, ScalarFormatter  # noqa: E402
from matplotlib.transforms import offset_copy  # noqa: E402

IMBALANCE_THRESHOLD = 1.10
DPI = 130

BUSY_COLOURS = ("#1f77b4", "#6baed6")  # alternate per iteration in gantt_all
IDLE_COLOUR = "#fdae6b"
MIGRATION_COLOUR = "#d62728"

REQUIRED_KEYS = {
    "trace_iterations.jsonl": ("step", "iteration", "entire", "micro_lc", "macro", "migrations"),
    "trace_workers.jsonl": ("step", "iteration", "worker", "units", "jobs", "busy", "busy_wall",
                            "t_begin", "t_end"),
    "trace_units.jsonl": ("step", "iteration", "unit", "cost", "refresh_cost", "kind"),
}


class TraceError(Exception):
    """Unusable trace input; reported as a one-line message with exit code 2."""


# --------------------------------------------------------------------------- input

def read_jsonl(run_dir, name):
    """Return the records of RUN_DIR/name, checking that each has the required keys.

    An incomplete final line (a run stopped while writing it) is skipped with a
    warning; any other malformed line is an error.
    """
    path = os.path.join(run_dir, name)
    if not os.path.isfile(path):
        raise TraceError(f"{path}: no such file (is {run_dir} an fe2heart run directory?)")
    try:
        with open(path, encoding="utf-8") as f:
            text = f.read()
    except (OSError, UnicodeDecodeError) as e:
        raise TraceError(f"{path}: cannot read: {e}") from e

    lines = text.split("\n")
    last = max((i for i, line in enumerate(lines) if line.strip()), default=-1)
    records = []
    for i, line in enumerate(lines):
        if not line.strip():
            continue
        try:
            rec = json.loads(line)
            if not isinstance(rec, dict):
                raise ValueError("not a JSON object")
        except ValueError as e:
            if i == last and not text.endswith("\n"):
                print(f"warning: {path}:{i + 1}: skipping incomplete last line", file=sys.stderr)
                continue
            raise TraceError(f"{path}:{i + 1}: malformed JSON line: {e}") from e
        missing = [k for k in REQUIRED_KEYS[name] if k not in rec]
        if missing:
            raise TraceError(f"{path}:{i + 1}: missing key(s) {', '.join(missing)}")
        records.append(rec)
    if not records:
        raise TraceError(f"{path}: empty trace (no records); did the run complete an iteration?")
    return records


def load_run(run_dir):
    """Read the three trace files of a run."""
    if not os.path.isdir(run_dir):
        raise TraceError(f"{run_dir}: not a directory")
    return (read_jsonl(run_dir, "trace_iterations.jsonl"),
            read_jsonl(run_dir, "trace_workers.jsonl"),
            read_jsonl(run_dir, "trace_units.jsonl"))


def key_of(rec):
    return (int(rec["step"]), int(rec["iteration"]))


def group_workers(workers):
    """{(step, iteration): [worker records sorted by rank]}."""
    groups = defaultdict(list)
    for w in workers:
        groups[key_of(w)].append(w)
    for recs in groups.values():
        recs.sort(key=lambda w: int(w["worker"]))
    return dict(sorted(groups.items()))


def busy_imbalance(recs, field="busy"):
    """max/mean of `field` over the workers of one iteration; NaN if the mean is 0."""
    values = [float(w[field]) for w in recs]
    mean = sum(values) / len(values)
    return max(values) / mean if mean > 0 else math.nan


def save(fig, out_dir, name):
    path = os.path.join(out_dir, name)
    fig.savefig(path, dpi=DPI, bbox_inches="tight")
    plt.close(fig)
    print(path)
    return path


def legend_below(ax, handles, labels=None, ncol=4, points=38):
    """A frameless legend a fixed distance (in points) below the axes, whatever their height."""
    anchor = offset_copy(ax.transAxes, fig=ax.figure, y=-points, units="points")
    kwargs = dict(loc="upper center", bbox_to_anchor=(0.5, 0.0), bbox_transform=anchor,
                  ncol=ncol, fontsize=8, frameon=False)
    if labels is None:
        return ax.legend(handles=handles, **kwargs)
    return ax.legend(handles, labels, **kwargs)


def plain_axis(axis):
    """Show absolute values on an axis (no '+1.234e3' offset)."""
    fmt = ScalarFormatter(useOffset=False)
    fmt.set_scientific(False)
    axis.set_major_formatter(fmt)


# --------------------------------------------------------------------------- figures

def plot_cumulative_times(iterations, units, out_dir):
    """Fig. 7: cumulative Entire / Micro+L+C / Macro per step, and refresh vs reuse CPU work."""
    per_step = defaultdict(lambda: [0.0, 0.0, 0.0])
    for r in iterations:
        acc = per_step[int(r["step"])]
        acc[0] += float(r["entire"])
        acc[1] += float(r["micro_lc"])
        acc[2] += float(r["macro"])

    work = defaultdict(lambda: [0.0, 0.0, 0.0])  # factor+modes, other refresh, reuse
    for u in units:
        acc = work[int(u["step"])]
        cost, part = float(u["cost"]), float(u["refresh_cost"])
        if u["kind"] == "refresh":
            acc[0] += part
            acc[1] += max(0.0, cost - part)
        else:
            acc[2] += cost

    steps = sorted(set(per_step) | set(work))
    marker = "o" if len(steps) <= 40 else None

    def cumulative(table, index):
        out, total = [], 0.0
        for s in steps:
            total += table[s][index] if s in table else 0.0
            out.append(total)
        return out

    entire, micro, macro = (cumulative(per_step, i) for i in range(3))
    factor, refresh_rest, reuse = (cumulative(work, i) for i in range(3))

    fig, (ax_t, ax_w) = plt.subplots(2, 1, figsize=(8, 8.5), sharex=True)
    ax_t.plot(steps, entire, marker=marker, color="black", label="Entire")
    ax_t.plot(steps, micro, marker=marker, color="#1f77b4", label="Micro+L+C")
    ax_t.plot(steps, macro, marker=marker, color="#2ca02c", label="Macro")
    ax_t.set_ylabel("cumulative wall time [s]")
    ax_t.legend(loc="upper left")
    ax_t.grid(alpha=0.3)
    if entire[-1] > 0:
        ratios = (f"Micro+L+C/Entire = {micro[-1] / entire[-1]:.3f},  "
                  f"Macro/Entire = {macro[-1] / entire[-1]:.3f}")
    else:
        ratios = "Entire time is zero"
    ax_t.set_title(f"Cumulative times over {len(steps)} time step(s)\n{ratios}")

    layer1 = factor
    layer2 = [a + b for a, b in zip(factor, refresh_rest)]
    layer3 = [a + b for a, b in zip(layer2, reuse)]
    bands = (([0.0] * len(steps), layer1, "#d62728", 0.75, "refresh jobs: factorization + modes"),
             (layer1, layer2, "#ff9896", 0.75, "refresh jobs: solve / rest"),
             (layer2, layer3, "#9467bd", 0.45, "reuse jobs"))
    for low, high, colour, alpha, label in bands:
        if len(steps) == 1:  # an area over a single step would be invisible
            ax_w.bar(steps, [high[0] - low[0]], bottom=low, width=0.4, color=colour,
                     alpha=alpha, label=label)
        else:
            ax_w.fill_between(steps, low, high, color=colour, alpha=alpha, label=label)
    ax_w.plot(steps, layer3, marker=marker, color="#4b2c6e", lw=1, label="total unit CPU work")
    if layer3[-1] > 0:
        ax_w.set_ylim(0, layer3[-1] * 1.08)
    ax_w.set_ylabel("cumulative unit CPU time [s]")
    ax_w.set_xlabel("time step")
    total = layer3[-1]
    if total > 0:
        share = (f"refresh {layer2[-1] / total:.1%} "
                 f"(factorization + modes {layer1[-1] / total:.1%}), reuse {reuse[-1] / total:.1%}")
    else:
        share = "no unit CPU work recorded"
    ax_w.set_title(f"Per-unit CPU work by job kind: {share}", fontsize=10)
    ax_w.legend(loc="upper left", fontsize=9)
    ax_w.grid(alpha=0.3)
    if len(steps) <= 20:
        ax_w.set_xticks(steps)
    else:
        ax_w.xaxis.set_major_locator(MaxNLocator(integer=True))
    if len(steps) == 1:
        ax_w.set_xlim(steps[0] - 1, steps[0] + 1)
    fig.tight_layout()
    return save(fig, out_dir, "cumulative_times.png")


def choose_iteration(groups, requested):
    """The (step, iteration) to draw: `requested`, or the one with the largest busy imbalance."""
    if requested is not None:
        if requested not in groups:
            first, last = next(iter(groups)), next(reversed(groups))
            raise TraceError(f"--iteration {requested[0]}:{requested[1]}: no worker records for it "
                             f"(trace covers {first[0]}:{first[1]} .. {last[0]}:{last[1]})")
        return requested
    best, best_value = next(iter(groups)), -math.inf
    for key, recs in groups.items():
        value = busy_imbalance(recs)
        if not math.isnan(value) and value > best_value:
            best, best_value = key, value
    return best


def row_height_figsize(n_rows, width):
    return (width, min(40.0, max(3.0, 0.45 * n_rows + 1.8)))


def plot_gantt(groups, migrations, key, out_dir):
    """Gantt chart of one Newton iteration: busy then idle per worker rank."""
    recs = groups[key]
    phase_end = max(float(w["t_end"]) for w in recs)
    phase_begin = min(float(w["t_begin"]) for w in recs)
    n = len(recs)

    fig, ax = plt.subplots(figsize=row_height_figsize(n, 10))
    fontsize = 9 if n <= 24 else 7
    for row, w in enumerate(recs):
        begin, busy = float(w["t_begin"]), max(0.0, float(w["busy_wall"]))
        busy_end = begin + busy
        idle = max(0.0, phase_end - busy_end)
        ax.broken_barh([(begin, busy)], (row - 0.35, 0.7), facecolors=BUSY_COLOURS[0])
        ax.broken_barh([(busy_end, idle)], (row - 0.35, 0.7), facecolors=IDLE_COLOUR)
        label = f"{int(w['units'])} units, {int(w['jobs'])} jobs, CPU {float(w['busy']):.3g} s"
        mig_in, mig_out = int(w.get("migrations_in", 0)), int(w.get("migrations_out", 0))
        if mig_in or mig_out:
            label += f", migr +{mig_in}/-{mig_out}"
        ax.text(1.01, row, label, transform=ax.get_yaxis_transform(), va="center",
                fontsize=fontsize)
    ax.axvline(phase_end, color="black", lw=1, ls="--")
    ax.set_yticks(range(n))
    ax.set_yticklabels([f"rank {int(w['worker'])}" for w in recs], fontsize=fontsize)
    ax.set_ylim(n - 0.5, -0.5)
    span = max(phase_end - phase_begin, 1e-9)
    ax.set_xlim(phase_begin - 0.02 * span, phase_end + 0.02 * span)
    plain_axis(ax.xaxis)
    ax.set_xlabel("wall time since run start [s]")
    ax.grid(axis="x", alpha=0.3)
    imb = busy_imbalance(recs)
    imb_text = f"{imb:.2f}" if not math.isnan(imb) else "n/a"
    ax.set_title(f"Step {key[0]}, iteration {key[1]}: micro phase {phase_end - phase_begin:.4g} s, "
                 f"busy CPU max/mean = {imb_text}, migrations = {migrations.get(key, 0)}")
    legend_below(ax, [Patch(color=BUSY_COLOURS[0], label="busy (busy_wall, drawn contiguous)"),
                      Patch(color=IDLE_COLOUR, label="idle until end of micro phase"),
                      Line2D([], [], color="black", ls="--", label="end of micro phase")], ncol=3)
    return save(fig, out_dir, "gantt.png")


def plot_gantt_all(groups, migrations, out_dir):
    """Whole-run Gantt chart: every iteration's busy bars per worker against wall time."""
    ranks = sorted({int(w["worker"]) for recs in groups.values() for w in recs})
    row_of = {r: i for i, r in enumerate(ranks)}
    n = len(ranks)
    bars = {r: ([], []) for r in ranks}  # per rank: bars of even / odd iterations
    starts, step_starts, mig_x, mig_n = [], [], [], []
    previous_step = None
    for index, (key, recs) in enumerate(groups.items()):
        start = min(float(w["t_begin"]) for w in recs)
        starts.append(start)
        if key[0] != previous_step:
            step_starts.append((start, key[0]))
            previous_step = key[0]
        if migrations.get(key, 0) > 0:
            mig_x.append(start)
            mig_n.append(migrations[key])
        for w in recs:
            bars[int(w["worker"])][index % 2].append(
                (float(w["t_begin"]), max(0.0, float(w["busy_wall"]))))

    fig, ax = plt.subplots(figsize=row_height_figsize(n + 1, 14))
    for r in ranks:
        for parity in (0, 1):
            if bars[r][parity]:
                ax.broken_barh(bars[r][parity], (row_of[r] - 0.35, 0.7),
                               facecolors=BUSY_COLOURS[parity], linewidth=0)
    # Fade the guide lines as they get denser, so long runs stay readable.
    ax.vlines(starts, -0.5, n - 0.5, colors="grey", lw=0.5, alpha=min(0.7, 60.0 / len(starts)))
    if 1 < len(step_starts) <= 60:
        ax.vlines([s for s, _ in step_starts], -0.5, n - 0.5, colors="black", lw=1.0)
    top = -0.75
    if mig_x:
        ax.scatter(mig_x, [top] * len(mig_x), marker="v", s=45, color=MIGRATION_COLOUR,
                   zorder=5, clip_on=False)
        if len(mig_x) <= 40:
            for x, m in zip(mig_x, mig_n):
                ax.annotate(str(m), (x, top), xytext=(0, 6), textcoords="offset points",
                            ha="center", fontsize=7, color=MIGRATION_COLOUR)
    ax.set_yticks(range(n))
    ax.set_yticklabels([f"rank {r}" for r in ranks], fontsize=9 if n <= 24 else 7)
    ax.set_ylim(n - 0.5, -1.3)
    end = max(float(w["t_end"]) for recs in groups.values() for w in recs)
    span = max(end - starts[0], 1e-9)
    ax.set_xlim(starts[0] - 0.01 * span, end + 0.01 * span)
    plain_axis(ax.xaxis)
    ax.set_xlabel("wall time since run start [s]")

    if len(step_starts) <= 60:  # label steps along the top
        sec = ax.secondary_xaxis("top")
        sec.set_xticks([s for s, _ in step_starts])
        sec.set_xticklabels([f"step {k}" for _, k in step_starts], fontsize=7, rotation=90)
    total_mig = sum(mig_n)
    ax.set_title(f"Worker busy time over the run: {len(groups)} iterations, {n} worker(s), "
                 f"{total_mig} migration(s) in {len(mig_x)} iteration(s)", pad=40)
    handles = [Patch(color=BUSY_COLOURS[0], label="busy (alternating shade per iteration)"),
               Line2D([], [], color="grey", lw=0.7, label="iteration start")]
    if 1 < len(step_starts) <= 60:
        handles.append(Line2D([], [], color="black", lw=1.0, label="time-step start"))
    handles.append(Line2D([], [], marker="v", ls="", color=MIGRATION_COLOUR,
                          label="iteration with migrations" + (" (count)" if len(mig_x) <= 40 else "")))
    legend_below(ax, handles)
    return save(fig, out_dir, "gantt_all.png")


def plot_imbalance(groups, iterations, out_dir):
    """Per-iteration busy CPU max/mean with the 1.10 threshold, and migrations as bars."""
    migrations = {key_of(r): int(r["migrations"]) for r in iterations}
    keys = sorted(set(groups) | set(migrations))
    x = list(range(len(keys)))
    cpu = [busy_imbalance(groups[k]) if k in groups else math.nan for k in keys]
    wall = [busy_imbalance(groups[k], "busy_wall") if k in groups else math.nan for k in keys]
    migr = [migrations.get(k, 0) for k in keys]
    marker = "o" if len(keys) <= 80 else None

    fig, ax = plt.subplots(figsize=(11, 5))
    ax_m = ax.twinx()
    ax_m.bar(x, migr, width=0.8, color=MIGRATION_COLOUR, alpha=0.35, label="migrations")
    ax_m.set_ylabel("migrations per iteration", color=MIGRATION_COLOUR)
    ax_m.tick_params(axis="y", colors=MIGRATION_COLOUR)
    ax_m.yaxis.set_major_locator(MaxNLocator(integer=True))
    ax_m.set_ylim(0, max(1, max(migr)) * 2.2)  # keep bars in the lower half

    ax.set_zorder(ax_m.get_zorder() + 1)
    ax.patch.set_visible(False)
    ax.plot(x, cpu, marker=marker, ms=4, color="#1f77b4", label="busy CPU max/mean")
    ax.plot(x, wall, marker=None, lw=1, ls=":", color="#1f77b4", alpha=0.6,
            label="busy wall max/mean (for reference)")
    ax.axhline(IMBALANCE_THRESHOLD, color="black", ls="--", lw=1,
               label=f"threshold {IMBALANCE_THRESHOLD:.2f}")
    finite = [v for v in cpu + wall if not math.isnan(v)]
    ax.set_ylim(min([0.95] + finite), max([IMBALANCE_THRESHOLD] + finite) * 1.08)
    ax.set_ylabel("max / mean worker busy time")

    boundaries = [i for i in range(1, len(keys)) if keys[i][0] != keys[i - 1][0]]
    if len(boundaries) <= 60:
        for b in boundaries:
            ax.axvline(b - 0.5, color="grey", lw=0.6, alpha=0.6)
    step_first = [0] + boundaries
    if len(step_first) <= 40:
        ax.set_xticks(step_first)
        ax.set_xticklabels([f"step {keys[i][0]}" for i in step_first],
                           fontsize=8 if len(step_first) <= 20 else 6,
                           rotation=0 if len(step_first) <= 12 else 90)
        ax.set_xlabel("Newton iteration (ticks: first iteration of each time step)")
    else:
        ax.xaxis.set_major_locator(MaxNLocator(integer=True))
        ax.set_xlabel("Newton iteration (global index over the run)")
    ax.set_xlim(-0.7, len(keys) - 0.3)
    ax.grid(axis="y", alpha=0.3)

    above = sum(1 for v in cpu if not math.isnan(v) and v > IMBALANCE_THRESHOLD)
    ax.set_title(f"Load imbalance per iteration: {above} of {len(keys)} iteration(s) above "
                 f"{IMBALANCE_THRESHOLD:.2f}, {sum(migr)} migration(s)")
    h1, l1 = ax.get_legend_handles_labels()
    h2, l2 = ax_m.get_legend_handles_labels()
    legend_below(ax, h1 + h2, l1 + l2)
    return save(fig, out_dir, "imbalance.png")


# --------------------------------------------------------------------------- main

def parse_step_iter(text):
    try:
        step, it = text.split(":")
        return int(step), int(it)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected STEP:ITER (e.g. 3:2), got '{text}'") from None


def main(argv=None):
    parser = argparse.ArgumentParser(
        description="Render PNG figures (cumulative times, Gantt charts, imbalance) "
                    "from the trace_*.jsonl files of an fe2heart run.")
    parser.add_argument("run_dir", metavar="RUN_DIR", help="run output folder with trace_*.jsonl")
    parser.add_argument("--out", metavar="OUT_DIR", help="where to write the PNGs (default: RUN_DIR)")
    parser.add_argument("--iteration", metavar="STEP:ITER", type=parse_step_iter,
                        help="iteration for gantt.png (default: largest busy max/mean)")
    args = parser.parse_args(argv)
    out_dir = args.out or args.run_dir

    try:
        iterations, workers, units = load_run(args.run_dir)
        groups = group_workers(workers)
        key = choose_iteration(groups, args.iteration)
        try:
            os.makedirs(out_dir, exist_ok=True)
        except OSError as e:
            raise TraceError(f"{out_dir}: cannot create output folder: {e}") from e
        migrations = {key_of(r): int(r["migrations"]) for r in iterations}
        plot_cumulative_times(iterations, units, out_dir)
        plot_gantt(groups, migrations, key, out_dir)
        plot_gantt_all(groups, migrations, out_dir)
        plot_imbalance(groups, iterations, out_dir)
    except TraceError as e:
        print(f"trace_plot: error: {e}", file=sys.stderr)
        return 2
    except (TypeError, ValueError) as e:  # e.g. a string where a number belongs
        print(f"trace_plot: error: unexpected value in the traces of {args.run_dir}: {e}",
              file=sys.stderr)
        return 2
    except OSError as e:
        print(f"trace_plot: error: {e}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
