#!/usr/bin/env python3
"""Convergence and work-precision study of any scene (issue 6).

Runs `boomdyn SCENE` over a grid of element counts (-boom_elements), step
sizes (-ts_dt) and spectral radii (-boom_rho_inf), extracts one quantity from
each results file, and computes its error against a reference: the exact
value (--exact) when the scene has one, else the finest run of the grid
(finest mesh and smallest step). Writes a markdown table with the error, the
observed order between successive refinements and the wall time, and a
log-log work-precision plot (error against run time).

  /usr/bin/python3 postprocess/study.py SCENE.yaml --quantity 'sensors/tip/position[-1,1]' \\
      --elements 4 8 16 32 --dt 1e-3 --out docs/studies/cantilever [--exact VALUE] [-- extra boomdyn options]

The quantity is an HDF5 dataset path with a numpy index, e.g.
'sensors/tip/position[-1,1]' (last tip y), 'tracking/tracked_hz[-1]',
'modal/frequencies_hz[0]', 'events/time[2]', 'steps/slack[-1,0]'.
"""
import argparse
import itertools
import os
import re
import subprocess
import sys
import time

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def extract(path, quantity):
    """Value of `dataset[index]` in a results file."""
    m = re.fullmatch(r"([^\[]+)(\[.*\])?", quantity)
    if not m:
        raise SystemExit("quantity must look like 'group/dataset[index]': %r" % quantity)
    with h5py.File(path) as f:
        data = f[m.group(1)][()]
    return float(eval("data" + (m.group(2) or ""), {"data": data}))  # index expression from the user


def run_case(boomdyn, scene, out, elements, dt, rho, extra):
    cmd = [boomdyn, scene, "-o", out, "-boom_overwrite", "-boom_quiet"]
    if elements:
        cmd += ["-boom_elements", str(elements)]
    if dt:
        cmd += ["-ts_dt", repr(dt)]
    if rho is not None:
        cmd += ["-boom_rho_inf", repr(rho)]
    start = time.perf_counter()
    subprocess.run(cmd + extra, check=True, stdout=subprocess.DEVNULL)
    return time.perf_counter() - start


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("scene")
    p.add_argument("--quantity", required=True)
    p.add_argument("--elements", type=int, nargs="*", default=[None], help="element counts (all beams)")
    p.add_argument("--dt", type=float, nargs="*", default=[None], help="time steps (dynamic scenes)")
    p.add_argument("--rho", type=float, nargs="*", default=[None], help="rho_inf values")
    p.add_argument("--exact", type=float, help="exact value of the quantity (else the finest run)")
    p.add_argument("--out", required=True, help="output stem: writes STEM.md and STEM.png")
    p.add_argument("--build", default=os.path.join(ROOT, "build"))
    argv = list(sys.argv[1:] if argv is None else argv)
    extra = argv[argv.index("--") + 1:] if "--" in argv else []  # after '--': more boomdyn options
    a = p.parse_args(argv[: argv.index("--")] if "--" in argv else argv)
    boomdyn = os.path.join(a.build, "boomdyn")
    work = a.out + "_runs"
    os.makedirs(work, exist_ok=True)
    os.makedirs(os.path.dirname(os.path.abspath(a.out)), exist_ok=True)
    rows = []
    for rho, n, dt in itertools.product(a.rho, a.elements, a.dt):
        out = os.path.join(work, "n%s_dt%s_rho%s.h5" % (n, dt, rho))
        wall = run_case(boomdyn, a.scene, out, n, dt, rho, extra)
        rows.append(dict(rho=rho, n=n, dt=dt, value=extract(out, a.quantity), wall=wall))
        print("rho_inf %s, elements %s, dt %s: %s = %.12g (%.2f s)" % (rho, n, dt, a.quantity, rows[-1]["value"], wall), flush=True)
    # Reference: exact, else the finest run of each rho (largest n, smallest dt).
    for rho in a.rho:
        group = [r for r in rows if r["rho"] == rho]
        finest = max(group, key=lambda r: ((r["n"] or 0), -(r["dt"] or 0)))
        ref = a.exact if a.exact is not None else finest["value"]
        for r in group:
            r["error"] = abs(r["value"] - ref) / max(abs(ref), 1e-300)
            r["reference"] = "exact" if a.exact is not None else "finest run"
            if a.exact is None and r is finest:
                r["error"] = float("nan")
    # Observed orders along each refinement direction (halving h or doubling n).
    def order(prev, cur, size):
        if not (prev and prev["error"] > 0 and cur["error"] > 0):
            return float("nan")
        return np.log(prev["error"] / cur["error"]) / np.log(size(prev) / size(cur))
    lines = ["# Study: %s" % os.path.basename(a.scene), "",
             "Quantity `%s`; reference: %s. Command: `postprocess/study.py %s`" % (
                 a.quantity, "exact value %.12g" % a.exact if a.exact is not None else "the finest run",
                 " ".join(argv)), "",
             "| rho_inf | elements | dt [s] | value | relative error | order | wall [s] |", "|---:|---:|---:|---:|---:|---:|---:|"]
    for i, r in enumerate(rows):
        prev = rows[i - 1] if i else None
        o = float("nan")
        if prev and prev["rho"] == r["rho"]:
            if prev["n"] == r["n"] and prev["dt"] and r["dt"]:
                o = order(prev, r, lambda x: x["dt"])
            elif prev["dt"] == r["dt"] and prev["n"] and r["n"]:
                o = order(prev, r, lambda x: 1.0 / x["n"])
        lines.append("| %s | %s | %s | %.12g | %.3e | %s | %.2f |" % (
            r["rho"] if r["rho"] is not None else "scene", r["n"] if r["n"] else "scene", r["dt"] if r["dt"] else "scene",
            r["value"], r["error"], "%.2f" % o if np.isfinite(o) else "", r["wall"]))
    with open(a.out + ".md", "w") as f:
        f.write("\n".join(lines) + "\n")
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for rho in a.rho:
        g = [r for r in rows if r["rho"] == rho and np.isfinite(r["error"]) and r["error"] > 0]
        ax.loglog([r["wall"] for r in g], [r["error"] for r in g], "o-", label="rho_inf = %s" % rho)
    ax.set_xlabel("wall time [s]")
    ax.set_ylabel("relative error of %s" % a.quantity)
    ax.set_title("%s: work-precision" % os.path.basename(a.scene))
    ax.grid(True, which="both", alpha=0.4)
    ax.legend()
    fig.tight_layout()
    fig.savefig(a.out + ".png", dpi=100)
    print("\n".join(lines))
    print("wrote %s.md and %s.png" % (a.out, a.out))


if __name__ == "__main__":
    main()
