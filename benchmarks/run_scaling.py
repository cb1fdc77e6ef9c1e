#!/usr/bin/env python3
"""Whole-run scaling benchmark (issue 6): runs a dynamic scene with a range of
elements per boom (-boom_elements), on one or more ranks and with any extra
boomdyn options, and reports time per step and per element and step, Newton
iterations and Jacobians per step, and where the time goes (-log_view):
residual evaluations, Jacobian evaluations, factorizations (PCSetUp),
triangular solves (PCApply) and the rest of the step.

  /usr/bin/python3 benchmarks/run_scaling.py [--scene benchmarks/scenes/long_boom.yaml] \\
      [--elements 10 100 1000 10000 100000] [--ranks 1] [--steps 100] [--label NAME] [--out FILE.md] \\
      [--csv FILE.csv] [-- boomdyn options, e.g. -boom_jacobian_reuse 0]

--csv appends one row per run to FILE.csv (the header first if the file is new),
in the format benchmarks/plot_performance.py reads (docs/performance.md):
run it for --ranks 1 and --ranks 2 into the same file and plot that file.

Only the time steps are counted (the -log_view event BoomStep): model set-up,
the initial acceleration solve and the output are not part of the per-step
cost (no state snapshots are written: -boom_state_interval 0).
"""
import argparse
import csv
import datetime
import os
import re
import subprocess
import sys
import tempfile

import h5py

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
# Columns of --csv, also those of benchmarks/results/performance.csv. "timed"
# says what per_step_ms divides by the steps: "steps" (the BoomStep event) or
# "whole_run" (the whole process, start-up and output included).
CSV_COLUMNS = ["scene", "elements", "ranks", "options", "steps", "timed", "per_step_ms", "per_element_step_us",
               "newton_per_step", "jacobians_per_step", "residual_pct", "jacobian_pct", "factor_pct", "solve_pct",
               "rest_pct", "tip_y_m", "source"]
EVENTS = {"BoomStep": "step", "SNESFunctionEval": "residual", "SNESJacobianEval": "jacobian", "PCSetUp": "factor",
          "PCApply": "solve"}


def log_events(path):
    with open(path) as f:
        text = f.read()
    out = {}
    for event, key in EVENTS.items():
        m = re.search(r"^%s\s+(\d+)\s+\S+\s+(\S+)" % event, text, re.M)
        out[key] = (int(m.group(1)), float(m.group(2))) if m else (0, 0.0)
    m = re.search(r"^Time \(sec\):\s+(\S+)", text, re.M)
    out["total"] = float(m.group(1)) if m else float("nan")
    return out


def run(scene, n, ranks, steps, extra, tmp):
    out = os.path.join(tmp, "run%d.h5" % n)
    log = os.path.join(tmp, "log%d.txt" % n)
    with open(scene) as f:
        dt = float(re.search(r"^\s*dt:\s*(\S+)", f.read(), re.M).group(1))
    cmd = [os.path.join(ROOT, "build", "boomdyn"), scene, "-o", out, "-boom_overwrite", "-boom_quiet",
           "-boom_elements", str(n), "-boom_state_interval", "0", "-ts_max_time", repr(steps * dt),
           "-log_view", ":" + log] + extra
    if ranks > 1:
        cmd = ["mpiexec", "-n", str(ranks), "--oversubscribe", "--allow-run-as-root"] + cmd
    subprocess.run(cmd, check=True)
    with h5py.File(out) as f:
        its = f["steps/newton_iterations"][1:]
        tip = f["sensors"][list(f["sensors"])[0]]["position"][-1]
    return len(its), its.mean(), log_events(log), tip


def append_csv(path, row):
    new = not os.path.exists(path) or os.path.getsize(path) == 0
    with open(path, "a", newline="") as f:
        w = csv.DictWriter(f, fieldnames=CSV_COLUMNS)
        if new:
            w.writeheader()
        w.writerow(row)


def main():
    argv = sys.argv[1:]
    extra = []
    if "--" in argv:
        i = argv.index("--")
        argv, extra = argv[:i], argv[i + 1:]
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--scene", default=os.path.join(ROOT, "benchmarks", "scenes", "long_boom.yaml"))
    p.add_argument("--elements", type=int, nargs="+", default=[10, 100, 1000, 10000, 100000])
    p.add_argument("--ranks", type=int, default=1)
    p.add_argument("--steps", type=int, default=100)
    p.add_argument("--label", default="")
    p.add_argument("--out", help="append the markdown table to this file")
    p.add_argument("--csv", help="append one row per run to this CSV file (benchmarks/plot_performance.py reads it)")
    a = p.parse_args(argv)
    head = ("| elements | ranks | options | steps | per step [ms] | per element and step [µs] | Newton it/step | "
            "Jacobians/step | residuals [%] | Jacobians [%] | factor [%] | solve [%] | rest [%] | tip y [m] |")
    rows = [head, "|" + "---:|" * 3 + "---:|" * 11]
    rows[1] = "|---:|---:|---|" + "---:|" * 11
    label = a.label or (" ".join(extra) if extra else "default")
    with tempfile.TemporaryDirectory() as tmp:
        for n in a.elements:
            steps, its, ev, tip = run(a.scene, n, a.ranks, a.steps, extra, tmp)
            step = ev["step"][1]
            share = {k: 100 * ev[k][1] / step for k in ("residual", "jacobian", "factor", "solve")}
            rest = 100 - sum(share.values())
            rows.append("| %d | %d | %s | %d | %.3f | %.3f | %.2f | %.2f | %.0f | %.0f | %.0f | %.0f | %.0f | %.6e |" % (
                n, a.ranks, label, steps, 1e3 * step / steps, 1e6 * step / steps / n, its,
                ev["jacobian"][0] / max(steps, 1), share["residual"], share["jacobian"], share["factor"],
                share["solve"], rest, tip[1]))
            print(rows[-1], flush=True)
            if a.csv:
                append_csv(a.csv, dict(
                    scene=os.path.relpath(os.path.abspath(a.scene), ROOT), elements=n, ranks=a.ranks, options=label,
                    steps=steps, timed="steps", per_step_ms="%.4g" % (1e3 * step / steps),
                    per_element_step_us="%.4g" % (1e6 * step / steps / n), newton_per_step="%.3f" % its,
                    jacobians_per_step="%.3f" % (ev["jacobian"][0] / max(steps, 1)),
                    residual_pct="%.0f" % share["residual"], jacobian_pct="%.0f" % share["jacobian"],
                    factor_pct="%.0f" % share["factor"], solve_pct="%.0f" % share["solve"], rest_pct="%.0f" % rest,
                    tip_y_m="%.6e" % tip[1],
                    source="run_scaling.py, %s UTC" % datetime.datetime.utcnow().strftime("%Y-%m-%d %H:%M")))
    table = "\n".join(rows)
    print(table)
    if a.out:
        with open(a.out, "a") as f:
            f.write("\n" + table + "\n")


if __name__ == "__main__":
    sys.exit(main())
