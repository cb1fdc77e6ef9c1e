#!/usr/bin/env python3
"""Benchmark: dynamic cantilever (2 m steel box, gravity + 10 kN tip load at
t = 0, h = 1e-3, 1 s) for several element counts. Reports wall time, time per
step, Newton iterations per step and the -log_view split between assembly,
LU factorization (numeric + symbolic), triangular solves and the rest.

  /usr/bin/python3 benchmarks/cantilever_scaling.py [--elements 8 32 ...] [--ranks 1] [--out docs/bench.md]
"""
import argparse
import os
import re
import subprocess
import sys
import tempfile

import h5py

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
EVENTS = {"BoomAssembly": "assembly", "MatLUFactorNum": "factor", "MatLUFactorSym": "factor",
          "MatSolve": "solve"}


def log_times(path):
    times = {"assembly": 0.0, "factor": 0.0, "solve": 0.0, "total": 0.0}
    with open(path) as f:
        text = f.read()
    m = re.search(r"^Time \(sec\):\s+(\S+)", text, re.M)
    times["total"] = float(m.group(1)) if m else float("nan")
    for event, key in EVENTS.items():
        m = re.search(r"^%s\s+\d+\s+\S+\s+(\S+)" % event, text, re.M)
        if m:
            times[key] += float(m.group(1))
    return times


def run(n, ranks, tmp):
    out = os.path.join(tmp, "run%d.h5" % n)
    log = os.path.join(tmp, "log%d.txt" % n)
    cmd = [os.path.join(ROOT, "build", "boomdyn"), os.path.join(ROOT, "inputs", "cantilever_dynamic.yaml"),
           "-o", out, "-boom_overwrite", "-boom_quiet", "-boom_elements", str(n), "-boom_state_interval", "0",
           "-ts_dt", "1e-3", "-ts_max_time", "1", "-log_view", ":" + log]
    if ranks > 1:
        cmd = ["mpiexec", "-n", str(ranks), "--oversubscribe", "--allow-run-as-root"] + cmd
    subprocess.run(cmd, check=True)
    with h5py.File(out) as f:
        its = f["steps/newton_iterations"][1:]
        wall = float(f["summary"].attrs["wall_time_s"])
        tip = f["sensors/tip/position"][-1]
    return wall, len(its), its.mean(), log_times(log), tip


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--elements", type=int, nargs="+", default=[8, 32, 128, 512, 2048])
    p.add_argument("--ranks", type=int, default=1)
    p.add_argument("--out", help="append the markdown table to this file")
    a = p.parse_args()
    rows = ["| elements | unknowns | wall [s] | per step [ms] | Newton it/step | assembly [%] | LU factor [%] | "
            "solve [%] | rest [%] | tip y at 1 s [mm] |",
            "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    with tempfile.TemporaryDirectory() as tmp:
        for n in a.elements:
            wall, steps, its, t, tip = run(n, a.ranks, tmp)
            tot = t["total"]
            rest = tot - t["assembly"] - t["factor"] - t["solve"]
            rows.append("| %d | %d | %.2f | %.3f | %.2f | %.0f | %.0f | %.0f | %.0f | %.4f |" % (
                n, 4 * (n + 1) + 3, wall, 1e3 * wall / steps, its, 100 * t["assembly"] / tot,
                100 * t["factor"] / tot, 100 * t["solve"] / tot, 100 * rest / tot, 1e3 * tip[1]))
            print(rows[-1], flush=True)
    table = "\n".join(rows)
    print(table)
    if a.out:
        with open(a.out, "a") as f:
            f.write("\n" + table + "\n")


if __name__ == "__main__":
    sys.exit(main())
