#!/usr/bin/env python3
"""Convergence and work-precision study of any scene (issue 6).

Runs `boomdyn SCENE` over a grid of element counts (-boom_elements), step
sizes (-ts_dt) and spectral radii (-boom_rho_inf), extracts one or more
quantities from each results file, and computes their errors against a
reference: the exact value (--exact) when the scene has one, else the finest
run of the grid (finest mesh and smallest step). Writes a markdown table per
quantity with the error, the observed order between successive refinements
and the wall time, the raw values as JSON, and a log-log work-precision plot
(error against run time).

  /usr/bin/python3 postprocess/study.py SCENE.yaml --quantity 'sensors/tip/position[-1,1]' \\
      --elements 4 8 16 32 --dt 1e-3 --out docs/studies/cantilever [--exact VALUE] [-- extra boomdyn options]

A quantity is an HDF5 dataset path with a numpy index, e.g.
'sensors/tip/position[-1,1]' (last tip y), 'tracking/tracked_hz[-1]',
'modal/frequencies_hz[0]', 'events/time[2]', 'steps/slack[-1,0]'. Also:

  LABEL=QUANTITY            a short name for tables and plots, e.g. 'tip_y=sensors/tip/position[-1,1]'
  max(PATH[index]), min(...), mean(...)  the largest / smallest / mean element, e.g. 'max(steps/slack[:,1])'
  PATH{after=T,before=T}[index]  only the rows of times T0 < t < T1 (the group's time dataset; /steps/time
                            for /sensors), e.g. 'mean(steps/frame_deflection{after=6.5}[:,0])'
  events/time{FILTER}[i]    the i-th stick/slip event that matches FILTER, a comma-separated list of
                            joint=NAME (or index into /layout/friction_joint_names), to_slip=0|1,
                            direction=-1|1, after=T, before=T (event times in s), e.g.
                            'events/time{joint=j2,to_slip=1,direction=-1,after=3}[0]'. When no event
                            matches, the value is nan (the run missed that transition).

--quantity takes several quantities (or may be repeated): every run is then
evaluated for all of them. --error absolute gives errors in the quantity's
unit (e.g. seconds for event times) instead of relative ones. A run that
exits with an error is reported as failed (value nan) and the study goes on.
--reuse skips a run whose results file holds a completed run of the same
command line, e.g. to add a quantity or a refinement to a finished study; its
wall and CPU times are then those of STEM.json when an earlier study with the
same --out measured them, else the run's own wall time (/summary/wall_time_s)
and no CPU time.
"""
import argparse
import itertools
import json
import os
import re
import resource
import subprocess
import sys
import time

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
EVENT_FILTER_KEYS = ("joint", "to_slip", "direction", "after", "before")


def split_label(quantity):
    """(label, spec) of 'LABEL=SPEC'; the label is the spec itself when there is none."""
    m = re.fullmatch(r"([A-Za-z_][\w.\-]*)=(.+)", quantity)
    if m and not any(c in m.group(1) for c in "/[{("):
        return m.group(1), m.group(2)
    return quantity, quantity


def _time_of(f, dataset):
    """The times of the rows of `dataset`: /steps/time for /steps and /sensors, GROUP/time for the others."""
    group = dataset.strip("/").split("/")[0]
    name = "steps/time" if group == "sensors" else group + "/time"
    if name not in f:
        raise SystemExit("no times for the rows of %s (%s is missing)" % (dataset, name))
    return f[name][()]


def _row_mask(f, dataset, filters):
    """Rows of `dataset` that match a 'key=value,...' filter (joint, to_slip, direction: /events only)."""
    events = dataset.strip("/").startswith("events/")
    keys = EVENT_FILTER_KEYS if events else ("after", "before")
    n = f[dataset].shape[0] if dataset in f else 0
    mask = np.ones(n, dtype=bool)
    for item in filter(None, (s.strip() for s in filters.split(","))):
        key, sep, value = item.partition("=")
        key, value = key.strip(), value.strip()
        if not sep or key not in keys:
            raise SystemExit("filter %r of %s: expected key=value with key one of %s" % (item, dataset, ", ".join(keys)))
        if n == 0:
            continue
        if key == "joint":
            names = [s.decode() if isinstance(s, bytes) else str(s) for s in f["layout/friction_joint_names"][()]]
            if value in names:
                index = names.index(value)
            elif re.fullmatch(r"\d+", value):
                index = int(value)
            else:
                raise SystemExit("event filter: no frictional joint %r (the file has %s)" % (value, ", ".join(names)))
            mask &= f["events/joint"][()] == index
        elif key in ("to_slip", "direction"):
            mask &= f["events/" + key][()] == int(value)
        elif key == "after":
            mask &= _time_of(f, dataset)[:n] > float(value)
        else:
            mask &= _time_of(f, dataset)[:n] < float(value)
    return mask


REDUCTIONS = {"max": np.max, "min": np.min, "mean": np.mean}


def extract(path, quantity):
    """Value of a quantity (see the module help) in a results file."""
    spec = split_label(quantity)[1]
    reduce = None
    m = re.fullmatch(r"(%s)\((.+)\)" % "|".join(REDUCTIONS), spec)
    if m:
        reduce, spec = REDUCTIONS[m.group(1)], m.group(2)
    m = re.fullmatch(r"([^\[{]+)(\{[^}]*\})?(\[.*\])?", spec)
    if not m:
        raise SystemExit("quantity must look like 'group/dataset[index]': %r" % quantity)
    dataset, filters, index = m.group(1), m.group(2), m.group(3) or ""
    with h5py.File(path, "r") as f:
        if filters is not None:
            if dataset in f:
                data = f[dataset][()][_row_mask(f, dataset, filters[1:-1])]
            elif dataset.strip("/").startswith("events/"):
                data = np.zeros(0)  # a run without events
            else:
                raise SystemExit("no dataset %s in %s" % (dataset, path))
        else:
            data = f[dataset][()]
    try:
        value = eval("data" + index, {"data": data})  # index expression from the user
    except IndexError:
        if filters is not None:
            return float("nan")  # no such event (or no row in the time window) in this run
        raise
    if reduce and np.size(value) == 0:
        return float("nan")
    return float(reduce(value) if reduce else value)


def command(boomdyn, scene, out, elements, dt, rho, extra):
    cmd = [boomdyn, scene, "-o", out, "-boom_overwrite", "-boom_quiet"]
    if elements:
        cmd += ["-boom_elements", str(elements)]
    if dt:
        cmd += ["-ts_dt", repr(dt)]
    if rho is not None:
        cmd += ["-boom_rho_inf", repr(rho)]
    return cmd + extra


def reusable(cmd, out):
    """Wall time of an earlier run of exactly `cmd` that completed into `out`, else None."""
    try:
        with h5py.File(out, "r") as f:
            if f.attrs.get("command_line") != " ".join(cmd) or f["summary"].attrs.get("status") != "completed":
                return None
            return float(f["summary"].attrs["wall_time_s"])
    except (OSError, KeyError):
        return None


def cpu_of_children():
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def run_case(boomdyn, scene, out, elements, dt, rho, extra, reuse=False):
    """Wall time, CPU time (user + system) and exit code of one run; with `reuse`, a completed earlier run of
    the same command is kept (its recorded wall time, CPU time nan)."""
    cmd = command(boomdyn, scene, out, elements, dt, rho, extra)
    if reuse:
        wall = reusable(cmd, out)
        if wall is not None:
            return wall, float("nan"), 0
    start, cpu = time.perf_counter(), cpu_of_children()
    code = subprocess.run(cmd, stdout=subprocess.DEVNULL).returncode
    return time.perf_counter() - start, cpu_of_children() - cpu, code


def errors(rows, rhos, quantity, exact, absolute):
    """Errors of `quantity` in each row against `exact` or the finest run of each rho."""
    for rho in rhos:
        group = [r for r in rows if r["rho"] == rho]
        finest = max(group, key=lambda r: ((r["n"] or 0), -(r["dt"] or 0)))
        ref = exact if exact is not None else finest["values"][quantity]
        for r in group:
            diff = abs(r["values"][quantity] - ref)
            r["errors"][quantity] = diff if absolute else diff / max(abs(ref), 1e-300)
            if exact is None and r is finest:
                r["errors"][quantity] = float("nan")


def orders(rows, quantity):
    """Observed order of each row against the previous one (halving h or doubling n), nan where undefined."""
    def order(prev, cur, size):
        e0, e1 = prev["errors"][quantity], cur["errors"][quantity]
        if not (e0 > 0 and e1 > 0):
            return float("nan")
        return np.log(e0 / e1) / np.log(size(prev) / size(cur))
    result = []
    for i, r in enumerate(rows):
        prev = rows[i - 1] if i else None
        o = float("nan")
        if prev and prev["rho"] == r["rho"]:
            if prev["n"] == r["n"] and prev["dt"] and r["dt"] and prev["dt"] != r["dt"]:
                o = order(prev, r, lambda x: x["dt"])
            elif prev["dt"] == r["dt"] and prev["n"] and r["n"] and prev["n"] != r["n"]:
                o = order(prev, r, lambda x: 1.0 / x["n"])
        result.append(o)
    return result


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("scene")
    p.add_argument("--quantity", required=True, nargs="+", action="extend",
                   help="one or more quantities: [LABEL=]path[{filter}][index], max/min/mean(...); see above")
    p.add_argument("--elements", type=int, nargs="*", default=[None], help="element counts (all beams)")
    p.add_argument("--dt", type=float, nargs="*", default=[None], help="time steps (dynamic scenes)")
    p.add_argument("--rho", type=float, nargs="*", default=[None], help="rho_inf values")
    p.add_argument("--exact", type=float, help="exact value of the quantity (else the finest run); one quantity only")
    p.add_argument("--error", choices=("relative", "absolute"), default="relative",
                   help="relative errors (default) or absolute ones, in the quantity's unit")
    p.add_argument("--work", choices=("wall", "cpu"), default="wall",
                   help="work axis of the plot: wall time (default) or CPU time of the runs (steadier on a shared machine)")
    p.add_argument("--out", required=True, help="output stem: writes STEM.md, STEM.json and STEM.png")
    p.add_argument("--runs", help="folder for the runs' results files (default: STEM_runs)")
    p.add_argument("--reuse", action="store_true",
                   help="keep the results of a completed earlier run of the same command (times from STEM.json, else the run's wall time)")
    p.add_argument("--build", default=os.path.join(ROOT, "build"))
    argv = list(sys.argv[1:] if argv is None else argv)
    extra = argv[argv.index("--") + 1:] if "--" in argv else []  # after '--': more boomdyn options
    a = p.parse_args(argv[: argv.index("--")] if "--" in argv else argv)
    if a.exact is not None and len(a.quantity) > 1:
        p.error("--exact needs a single --quantity")
    labels = [split_label(q)[0] for q in a.quantity]
    if len(set(labels)) != len(labels):
        p.error("two quantities have the same label")
    absolute = a.error == "absolute"
    boomdyn = os.path.join(a.build, "boomdyn")
    work = a.runs or a.out + "_runs"
    os.makedirs(work, exist_ok=True)
    os.makedirs(os.path.dirname(os.path.abspath(a.out)), exist_ok=True)
    earlier = {}  # (rho, n, dt) -> (wall, cpu) of the runs of an earlier study with this stem
    if a.reuse and os.path.exists(a.out + ".json"):
        with open(a.out + ".json") as f:
            old = json.load(f)
        for r in old.get("runs", []):
            earlier[(r["rho"], r["n"], r["dt"])] = (r["wall"], r.get("cpu", float("nan")))
    rows = []
    for rho, n, dt in itertools.product(a.rho, a.elements, a.dt):
        out = os.path.join(work, "n%s_dt%s_rho%s.h5" % (n, dt, rho))
        wall, cpu, code = run_case(boomdyn, a.scene, out, n, dt, rho, extra, a.reuse)
        if a.reuse and not np.isfinite(cpu) and (rho, n, dt) in earlier:
            wall, cpu = earlier[(rho, n, dt)]  # the times this study measured when it made the run
        values = {q: (extract(out, q) if code == 0 else float("nan")) for q in a.quantity}
        rows.append(dict(rho=rho, n=n, dt=dt, values=values, errors={}, wall=wall, cpu=cpu,
                         status="completed" if code == 0 else "failed (exit %d)" % code))
        print("rho_inf %s, elements %s, dt %s: %s (%.2f s)%s" % (
            rho, n, dt, ", ".join("%s = %.12g" % (split_label(q)[0], v) for q, v in values.items()), wall,
            "" if code == 0 else ", FAILED with exit code %d" % code), flush=True)
    lines = ["# Study: %s" % os.path.basename(a.scene), ""]
    for q, label in zip(a.quantity, labels):
        errors(rows, a.rho, q, a.exact, absolute)
        order = orders(rows, q)
        if len(a.quantity) > 1:
            lines += ["## %s" % label, ""]
        lines += ["Quantity `%s`; reference: %s. Command: `postprocess/study.py %s`" % (
                      split_label(q)[1], "exact value %.12g" % a.exact if a.exact is not None else "the finest run",
                      " ".join(argv)), "",
                  "| rho_inf | elements | dt [s] | value | %s | order | wall [s] | CPU [s] |" % (
                      "absolute error" if absolute else "relative error"),
                  "|---:|---:|---:|---:|---:|---:|---:|---:|"]
        for r, o in zip(rows, order):
            lines.append("| %s | %s | %s | %s | %.3e | %s | %.2f | %.2f |" % (
                r["rho"] if r["rho"] is not None else "scene", r["n"] if r["n"] else "scene",
                r["dt"] if r["dt"] else "scene",
                "%.12g" % r["values"][q] if r["status"] == "completed" else r["status"],
                r["errors"][q], "%.2f" % o if np.isfinite(o) else "", r["wall"], r["cpu"]))
        lines.append("")
    with open(a.out + ".md", "w") as f:
        f.write("\n".join(lines))
    with open(a.out + ".json", "w") as f:
        json.dump(dict(scene=a.scene, argv=argv, error=a.error, exact=a.exact, quantities=a.quantity,
                       runs=rows),
                  f, indent=1, default=float)
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for q, label in zip(a.quantity, labels):
        for rho in a.rho:
            g = [r for r in rows if r["rho"] == rho and np.isfinite(r["errors"][q]) and r["errors"][q] > 0]
            name = ("%s, " % label if len(a.quantity) > 1 else "") + "rho_inf = %s" % (rho if rho is not None else "scene")
            ax.loglog([r[a.work] for r in g], [r["errors"][q] for r in g], "o-", label=name)
    ax.set_xlabel("%s time [s]" % ("wall" if a.work == "wall" else "CPU"))
    ax.set_ylabel("%s error%s" % (a.error, " of %s" % a.quantity[0] if len(a.quantity) == 1 else ""))
    ax.set_title("%s: work-precision" % os.path.basename(a.scene))
    ax.grid(True, which="both", alpha=0.4)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(a.out + ".png", dpi=100)
    print("\n".join(lines))
    print("wrote %s.md, %s.json and %s.png" % (a.out, a.out, a.out))


if __name__ == "__main__":
    main()
