#!/usr/bin/env python3
"""postprocess/calibrate_paper.py (issue 15 item 4) against what it must
reproduce: with rigid joints and one number (--fixed-pads 0) it finds the
section scale c of the stored single-number calibration (the I values in
inputs/paper_extraction.yaml over the steel box values); the two-number
fits converge to both targets (27.0 Hz retracted, -0.2 m extended tip).

  test_calibrate_paper.py BOOMDYN SOURCE_DIR BINARY_DIR
"""
import os
import subprocess
import sys

import yaml

boomdyn, source, binary = sys.argv[1:4]
script = os.path.join(source, "postprocess", "calibrate_paper.py")
scene = os.path.join(source, "inputs", "paper_extraction.yaml")
work = os.path.join(binary, "test_calibrate_paper")
failures = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        failures.append(what)


def calibrate(*extra):
    r = subprocess.run([sys.executable, script, "--boomdyn", boomdyn, "--scene", scene, "--work", work] + list(extra),
                       capture_output=True, text=True, timeout=600)
    if r.returncode != 0:
        print(r.stdout, r.stderr)
        raise SystemExit("calibrate_paper.py failed")
    last = [l for l in r.stdout.splitlines() if l.startswith("calibration:")][-1]
    return {k: (float(v) if k != "fit" else v) for k, v in (t.split("=") for t in last.split()[1:])}


with open(scene) as f:
    base = yaml.safe_load(f)
stored = {b["name"]: b["section"]["I"] for b in base["bodies"]}
steel = {"boom1": 6.395214e-5, "boom2": 3.720306e-5, "boom3": 1.986431e-5}
c_stored = stored["boom1"] / steel["boom1"]

one = calibrate("--fixed-pads", "0", "--c0", "1.0")
check(abs(one["c"] / c_stored - 1) < 1e-5, "single-number fit c = %.7f against the stored %.7f (1e-5)" % (one["c"], c_stored))
check(abs(one["f_retracted"] / 27.0 - 1) < 1e-7, "single-number fit: 27.0 Hz to 1e-7 (%.9f)" % one["f_retracted"])

for fit, c0, k0 in (("mass", "0.2", "5e8"), ("pads", "0.73", "1e7")):
    r = calibrate("--fit", fit, "--c0", c0, "--k0", k0)
    check(abs(r["f_retracted"] / 27.0 - 1) < 1e-6 and abs(r["tip"] / -0.2 - 1) < 1e-6,
          "%s fit reaches 27.0 Hz and -0.2 m to 1e-6 (%.7f Hz, %.7f m) in %d iterations"
          % (fit, r["f_retracted"], r["tip"], r["iterations"]))
    check(r["iterations"] <= 8, "%s fit: at most 8 Newton iterations" % fit)

sys.exit(1 if failures else 0)
