#!/usr/bin/env python3
"""The two plots of docs/performance.md, from a CSV in the format that
benchmarks/run_scaling.py --csv writes (benchmarks/results/performance.csv
holds the figures the page quotes, each row with its source):

  /usr/bin/python3 benchmarks/plot_performance.py [--csv benchmarks/results/performance.csv] [--out docs/img]

writes OUT/performance_elements.png (time per step against elements, log-log:
one line per scene, rank count and kind of timing) and
OUT/performance_ranks.png (time per step against ranks, for every scene and
mesh measured on more than one rank count, with the ideal 1/ranks line).

From a fresh measurement:

  /usr/bin/python3 benchmarks/run_scaling.py --elements 1000 10000 100000 --steps 50 --ranks 1 --csv my.csv
  /usr/bin/python3 benchmarks/run_scaling.py --elements 1000 10000 100000 --steps 50 --ranks 2 --csv my.csv
  /usr/bin/python3 benchmarks/plot_performance.py --csv my.csv --out my_plots

The column "timed" says what a row's per_step_ms divides by the steps:
"steps" is the time steps alone (the -log_view event BoomStep, what
run_scaling.py measures); "whole_run" is the whole process (start-up, output
and any frequency tracking included). Whole-run rows appear in the elements
plot only as lines over several meshes, so that a single whole-run point does
not sit among the per-step series.
"""
import argparse
import csv
import os
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")  # files only, no display needed
import matplotlib.pyplot as plt  # noqa: E402  (after the backend)

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
TIMED = {"steps": "time steps", "whole_run": "whole run ÷ steps"}


def read_rows(path):
    """Rows of the CSV with elements, ranks and per_step_ms as numbers."""
    rows = []
    with open(path, newline="") as f:
        for i, r in enumerate(csv.DictReader(f), start=2):
            try:
                rows.append(dict(r, elements=int(r["elements"]), ranks=int(r["ranks"]),
                                 per_step_ms=float(r["per_step_ms"]), timed=r.get("timed") or "steps"))
            except (KeyError, TypeError, ValueError) as e:
                sys.exit("%s, line %d: needs numbers in elements, ranks and per_step_ms (%s)" % (path, i, e))
    if not rows:
        sys.exit("%s: no rows" % path)
    return rows


def scene_name(scene):
    return os.path.splitext(os.path.basename(scene))[0]


def median_by(rows, key):
    """One value per key: the median of repeated rows (several runs of one case)."""
    groups = defaultdict(list)
    for r in rows:
        groups[r[key]].append(r["per_step_ms"])
    out = []
    for k in sorted(groups):
        v = sorted(groups[k])
        n = len(v)
        out.append((k, v[n // 2] if n % 2 else 0.5 * (v[n // 2 - 1] + v[n // 2])))
    return out


def save(fig, ax, path, xlabel, title):
    """Log time axis, labels, legend; writes the figure (700 x 480 pixels)."""
    ax.set_yscale("log")
    ax.set_xlabel(xlabel)
    ax.set_ylabel("time per step [ms]")
    ax.set_title(title)
    ax.grid(True, which="both", alpha=0.3)
    if ax.get_legend_handles_labels()[0]:
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


def plot_elements(rows, path):
    series = defaultdict(list)
    for r in rows:
        series[(r["scene"], r["ranks"], r["timed"])].append(r)
    fig, ax = plt.subplots(figsize=(7, 4.8))
    guide = None
    for (scene, ranks, timed), group in sorted(series.items()):
        points = median_by(group, "elements")
        if timed != "steps" and len(points) < 2:
            continue
        x, y = zip(*points)
        style = "-" if timed == "steps" else "--"
        marker = "o" if ranks == 1 else "s"
        ax.plot(x, y, style, marker=marker, fillstyle="full" if timed == "steps" else "none",
                label="%s, %d rank%s, %s" % (scene_name(scene), ranks, "" if ranks == 1 else "s", TIMED.get(timed, timed)))
        if timed == "steps" and ranks == 1 and (guide is None or x[-1] > guide[0]):
            guide = (x[-1], y[-1])
    if guide:
        xs = [min(r["elements"] for r in rows), guide[0]]
        ax.plot(xs, [guide[1] * x / guide[0] for x in xs], ":", color="grey", label="∝ elements")
    ax.set_xscale("log")
    save(fig, ax, path, "elements (all booms)", "Cost per time step against mesh size")


def plot_ranks(rows, path):
    series = defaultdict(list)
    for r in rows:
        series[(r["scene"], r["elements"], r["timed"])].append(r)
    fig, ax = plt.subplots(figsize=(7, 4.8))
    all_ranks = set()
    drawn = 0
    for (scene, elements, timed), group in sorted(series.items()):
        points = median_by(group, "ranks")
        if len(points) < 2:
            continue
        x, y = zip(*points)
        all_ranks.update(x)
        options = {r["options"] for r in group} - {"", "default"}
        name = scene_name(scene) + (" " + options.pop() if len(options) == 1 else "")
        line, = ax.plot(x, y, "-o", label="%s, %d elements, %s" % (name, elements, TIMED.get(timed, timed)))
        ax.plot(x, [y[0] * x[0] / r for r in x], ":", color=line.get_color())
        for r, t in zip(x[1:], y[1:]):
            ax.annotate("%.2f× one rank" % (y[0] / t), (r, t), textcoords="offset points", xytext=(6, 4), fontsize=8)
        drawn += 1
    if not drawn:
        ax.text(0.5, 0.5, "no case measured on more than one rank count", ha="center", transform=ax.transAxes)
    ticks = sorted(all_ranks) or [1, 2]
    ax.set_xticks(ticks)
    ax.set_xlim(ticks[0] - 0.2, ticks[-1] + 0.2 * (ticks[-1] - ticks[0] + 1))  # room for the labels
    save(fig, ax, path, "ranks (MPI processes, one per core)", "Cost per time step against ranks (dotted: ideal, 1/ranks)")


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--csv", default=os.path.join(ROOT, "benchmarks", "results", "performance.csv"))
    p.add_argument("--out", default=os.path.join(ROOT, "docs", "img"))
    a = p.parse_args()
    rows = read_rows(a.csv)
    os.makedirs(a.out, exist_ok=True)
    for name, plot in (("performance_elements.png", plot_elements), ("performance_ranks.png", plot_ranks)):
        path = os.path.join(a.out, name)
        plot(rows, path)
        print(path)


if __name__ == "__main__":
    sys.exit(main())
