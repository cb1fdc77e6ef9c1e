#!/usr/bin/python3
"""Longer sweeps of the stiff and extreme cases (issue 6, item 3) that do not
fit in the test suite (tests/extreme, ctest -L extreme). Runs build/boomdyn on
variants of the scenes in inputs/ and prints one Markdown table per case:
parameter, outcome (completed / the error line), steps, rejected steps,
energy growth max(E - E0) (E: kinetic + strain + potential of gravity and
dead loads), max constraint violation, wall time, and the command.
Results: docs/extreme-cases.md.

    /usr/bin/python3 scripts/extreme_cases.py [--boomdyn build/boomdyn] [--out DIR] [--quick] [CASE ...]

CASE: conditioning, whip, extraction, sigma0, steps (default: all).
"""
import argparse
import os
import re
import subprocess
import sys
import time

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def scene_variant(src, out, replacements):
    text = open(os.path.join(ROOT, "inputs", src)).read()
    for old, new in replacements:
        if old not in text:
            sys.exit(f"{src}: '{old}' not found")
        text = text.replace(old, new)
    with open(out, "w") as f:
        f.write(text)
    return out


def run(boomdyn, scene, out, args, timeout):
    h5 = os.path.join(out, os.path.basename(scene).replace(".yaml", "") + "_" + re.sub(r"[^A-Za-z0-9.]+", "_", " ".join(args)) + ".h5")
    cmd = [boomdyn, scene, "-o", h5, "-boom_overwrite", "-boom_quiet"] + args
    start = time.time()
    try:
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
        text, rc = p.stdout + p.stderr, p.returncode
    except subprocess.TimeoutExpired:
        text, rc = f"timeout after {timeout} s", None
    wall = time.time() - start
    row = {"cmd": " ".join([os.path.relpath(c, ROOT) if c.startswith(ROOT) else c for c in cmd]), "wall": wall, "rc": rc}
    errors = [l for l in text.splitlines() if l.startswith("boomdyn: error")]
    warnings = [l for l in text.splitlines() if l.startswith("warning:") and "rejected" not in l and "rope" not in l]
    row["outcome"] = errors[0] if errors else ("completed" if rc == 0 else text.strip().splitlines()[-1][:200])
    row["warning"] = warnings[0] if warnings else ""
    try:
        with h5py.File(h5, "r") as f:
            e = f["steps/energy"][:, 3]
            row["steps"] = int(f["summary"].attrs["steps"]) if "summary" in f else len(e) - 1
            row["rejected"] = int(f["summary"].attrs["rejected_steps"]) if "summary" in f else -1
            row["growth"] = float(np.max(e - e[0])) if np.all(np.isfinite(e)) else float("nan")
            row["violation"] = float(np.max(f["steps/constraint_violation"][:]))
            row["finite"] = bool(np.all(np.isfinite(e)))
    except (OSError, KeyError):
        row.update(steps=-1, rejected=-1, growth=float("nan"), violation=float("nan"), finite=False)
    return row


def table(title, rows):
    print(f"\n### {title}\n")
    print("| parameter | outcome | steps | rejected | max(E − E0), J | max violation | wall, s |")
    print("| --- | --- | --- | --- | --- | --- | --- |")
    for label, r in rows:
        outcome = r["outcome"].replace("|", "/")
        if r["warning"]:
            outcome += "<br>" + r["warning"][:160].replace("|", "/") + "…"
        print(f"| {label} | {outcome} | {r['steps']} | {r['rejected']} | {r['growth']:.3g} | {r['violation']:.1e} | {r['wall']:.1f} |")
    print("\nCommands:\n")
    for label, r in rows:
        print(f"- {label}: `{r['cmd']}`")
    sys.stdout.flush()


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--boomdyn", default=os.path.join(ROOT, "build", "boomdyn"))
    ap.add_argument("--out", default="/tmp/boomdyn-extreme")
    ap.add_argument("--quick", action="store_true", help="fewer and shorter runs")
    ap.add_argument("cases", nargs="*", default=["conditioning", "whip", "extraction", "sigma0", "steps"])
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    b = a.boomdyn
    cantilever = os.path.join(ROOT, "inputs", "cantilever_dynamic.yaml")

    if "conditioning" in a.cases:
        rows = []
        grid = [(2048, 1e-3), (4096, 1e-3), (8192, 1e-3), (8192, 1e-4)] if a.quick else \
            [(1024, 1e-3), (2048, 1e-3), (3072, 1e-3), (4096, 1e-3), (8192, 1e-3), (2048, 1e-5), (4096, 1e-4), (8192, 1e-4), (8192, 1e-5)]
        for n, h in grid:
            steps = 20
            rows.append((f"{n} elements, h = {h:g} s, {steps} steps",
                         run(b, cantilever, a.out, ["-boom_elements", str(n), "-ts_dt", f"{h:g}", "-ts_max_time", f"{steps * h:g}"], 900)))
        table("Fine meshes: cantilever_dynamic.yaml, 20 steps", rows)

    if "whip" in a.cases:
        whip = os.path.join(a.out, "whip50.yaml")
        with open(whip, "w") as f:
            f.write("name: whip\nanalysis: dynamic\nbodies:\n  - {name: beam, length: 1.0, elements: 16, section: {EA: 1.0e5, EI: 1.0, rhoA: 1.0}}\n"
                    "constraints:\n  - {type: clamp, body: beam, at: start}\nloads:\n  - {type: point_force, body: beam, at: end, force: [0, -50]}\n"
                    "dynamic: {t_end: 2.0, dt: 1.0e-3, rho_inf: 0.8}\noutput:\n  sensors:\n    - {name: tip, body: beam, at: end}\n")
        rows = [(f"rho_inf = {r}", run(b, whip, a.out, ["-boom_rho_inf", str(r)], 600)) for r in (0.5, 0.8, 0.9, 0.95, 1.0)]
        table("Whip: soft 1 m cantilever, dead tip load P L^2/EI = 50 applied at t = 0 (E0 = 0; E may only fall)", rows)

    if "extraction" in a.cases:
        rows = []
        for speed, dist in [(0.25, 1.25), (1.0, 1.25), (5.0, 1.25), (10.0, 1.25), (5.0, 1.74), (5.0, 1.9)]:
            t1 = 2.0 + dist / speed
            # The scene with the linear ramp drive (paper_extraction.yaml has an accel_limited one).
            s = scene_variant("paper_extraction_single_calibration.yaml", os.path.join(a.out, f"extraction_{speed:g}_{dist:g}.yaml"),
                              [("displacement: {type: ramp, t0: 2.0, t1: 7.0, from: 0, to: 1.25}",
                                f"displacement: {{type: ramp, t0: 2.0, t1: {t1:.6g}, from: 0, to: {dist:g}}}"),
                               ("t_end: 7.0", f"t_end: {t1 + 0.5:.6g}")])
            rows.append((f"{speed:g} m/s to {dist:g} m", run(b, s, a.out, ["-boom_tracking_interval", "0"], 900)))
        table("Extraction speed and distance: paper_extraction_single_calibration.yaml (ramp from 2 s; drive work makes E grow)", rows)

    if "sigma0" in a.cases:
        rows = []
        for sigma0 in ((1e5, 1e7) if a.quick else (1e5, 1e6, 1e7)):
            # str.replace: both pads' friction
            s = scene_variant("paper_stick_slip.yaml", os.path.join(a.out, f"stick_slip_{sigma0:g}.yaml"),
                              [("sigma0: 1.0e5", f"sigma0: {sigma0:g}")])
            rows.append((f"sigma0 = {sigma0:g} 1/m", run(b, s, a.out, [], 1800)))
        table("LuGre bristle stiffness: paper_stick_slip.yaml, 14 s (driven elevation: E changes)", rows)

    if "steps" in a.cases:
        rows = []
        pendulum = os.path.join(ROOT, "inputs", "flexible_pendulum.yaml")
        for scene, h, t in [(cantilever, 0.05, 1.0), (cantilever, 0.01, 1.0), (cantilever, 1e-6, 0.01),
                            (pendulum, 0.05, 1.0), (pendulum, 0.01, 1.0), (pendulum, 1e-6, 0.01)]:
            rows.append((f"{os.path.basename(scene)} h = {h:g} s to {t:g} s",
                         run(b, scene, a.out, ["-ts_dt", f"{h:g}", "-ts_max_time", f"{t:g}"], 900)))
        table("Very large and very small steps", rows)


if __name__ == "__main__":
    main()
