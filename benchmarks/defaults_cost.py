#!/usr/bin/python3
"""What turning each default off does to one scene: cost and moved results.

    /usr/bin/python3 benchmarks/defaults_cost.py [--boomdyn build/boomdyn] [--scene inputs/paper_extraction.yaml]

Runs the scene once with the defaults and once per switch below (one rank,
one after the other) and prints a Markdown table (docs/defaults.md): CPU
time of the run (user + system, which a loaded machine inflates less than
the wall time), LU factorizations and residual
evaluations (PETSc's -log_view counts of MatLUFactorNum and
SNESFunctionEval), and how far the run's tip trajectory (sensor 'tip') and
tracked frequency move against the defaults' run, relative to their largest
values.
"""
import argparse
import os
import re
import resource
import subprocess
import tempfile

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
VARIANTS = [
    ("defaults", []),
    ("full Newton", ["-boom_jacobian_reuse", "0"]),
    ("no acceleration predictor", ["-boom_acceleration_predictor", "0"]),
    ("no filtered start", ["-boom_filtered_start", "0"]),
    ("no KLU refactorization", ["-mat_boomklu_refactor", "0"]),
    ("full eigen-solve tracking", ["-boom_tracking_full"]),
]


def run(boomdyn, scene, options, out):
    log = out + ".log"
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run([boomdyn, scene, "-o", out, "-boom_overwrite", "-boom_quiet", "-log_view", ":" + log] + options,
                   check=True, cwd=os.path.dirname(out))
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime
    text = open(log).read()

    def count(event):
        m = re.search(r"^%s\s+(\d+)" % event, text, re.M)
        return int(m.group(1)) if m else 0
    with h5py.File(out, "r") as f:
        tip = sensor(f, "tip")
        hz = f["tracking/tracked_hz"][()] if "tracking" in f else None
    return {"cpu": cpu, "lu": count("MatLUFactorNum"), "res": count("SNESFunctionEval"), "tip": tip, "hz": hz}


def sensor(f, name):
    """Positions (n, 2) of the sensor, or None."""
    key = "sensors/%s/position" % name
    return f[key][()] if key in f else None


def moved(a, b):
    if a is None or b is None or a.shape != b.shape:
        return float("nan")
    return float(np.max(np.abs(a - b)) / max(np.max(np.abs(b)), 1e-300))


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--boomdyn", default=os.path.join(ROOT, "build", "boomdyn"))
    p.add_argument("--scene", default=os.path.join(ROOT, "inputs", "paper_extraction.yaml"))
    a = p.parse_args()
    results = {}
    with tempfile.TemporaryDirectory() as d:
        for label, options in VARIANTS:
            results[label] = run(os.path.abspath(a.boomdyn), os.path.abspath(a.scene), options,
                                 os.path.join(d, label.replace(" ", "_") + ".h5"))
    base = results["defaults"]
    print("| run | options | CPU time | LU factorizations | residual evaluations | tip moves | tracked frequency moves |")
    print("|---|---|---|---|---|---|---|")
    for label, options in VARIANTS:
        r = results[label]
        print("| %s | %s | %.2f s | %d | %d | %s | %s |" % (
            label, "`%s`" % " ".join(options) if options else "", r["cpu"], r["lu"], r["res"],
            "" if r is base else "%.1e" % moved(r["tip"], base["tip"]),
            "" if r is base else "%.1e" % moved(r["hz"], base["hz"])))


if __name__ == "__main__":
    main()
