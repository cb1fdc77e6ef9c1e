#!/usr/bin/env python3
"""postprocess/calibrate_paper.py (issue 15 item 4) against what it must
reproduce: with rigid joints and one number (--fixed-pads 0) on the
single-number variant (inputs/paper_extraction_single_calibration.yaml) it
finds the section scale c of that scene (its I values over the steel box
values); the two-number fits converge to both targets (27.0 Hz retracted,
-0.2 m extended tip), and the mass fit on inputs/paper_extraction.yaml (pads
and rope pair as in the scene) reproduces that scene's stored I and density.

  test_calibrate_paper.py BOOMDYN SOURCE_DIR BINARY_DIR
"""
import os
import subprocess
import sys

import yaml

boomdyn, source, binary = sys.argv[1:4]
script = os.path.join(source, "postprocess", "calibrate_paper.py")
scene = os.path.join(source, "inputs", "paper_extraction.yaml")
single = os.path.join(source, "inputs", "paper_extraction_single_calibration.yaml")
work = os.path.join(binary, "test_calibrate_paper")
failures = []
steel = {"boom1": 6.395214e-5, "boom2": 3.720306e-5, "boom3": 1.986431e-5}


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        failures.append(what)


def calibrate(scene_file, *extra):
    r = subprocess.run([sys.executable, script, "--boomdyn", boomdyn, "--scene", scene_file, "--work", work]
                       + list(extra), capture_output=True, text=True, timeout=600)
    if r.returncode != 0:
        print(r.stdout, r.stderr)
        raise SystemExit("calibrate_paper.py failed")
    last = [l for l in r.stdout.splitlines() if l.startswith("calibration:")][-1]
    return {k: (float(v) if k != "fit" else v) for k, v in (t.split("=") for t in last.split()[1:])}


def sections(path):
    with open(path) as f:
        return {b["name"]: b["section"] for b in yaml.safe_load(f)["bodies"]}


c_single = sections(single)["boom1"]["I"] / steel["boom1"]
one = calibrate(single, "--fixed-pads", "0", "--c0", "1.0")
check(abs(one["c"] / c_single - 1) < 1e-5, "single-number fit c = %.7f against the stored %.7f (1e-5)"
      % (one["c"], c_single))
check(abs(one["f_retracted"] / 27.0 - 1) < 1e-7, "single-number fit: 27.0 Hz to 1e-7 (%.9f)" % one["f_retracted"])

stored = sections(scene)
for fit, c0, k0 in (("mass", "0.2", "5e8"), ("pads", "0.73", "1e7")):
    r = calibrate(scene, "--fit", fit, "--c0", c0, "--k0", k0)
    check(abs(r["f_retracted"] / 27.0 - 1) < 1e-6 and abs(r["tip"] / -0.2 - 1) < 1e-6,
          "%s fit reaches 27.0 Hz and -0.2 m to 1e-6 (%.7f Hz, %.7f m) in %d iterations"
          % (fit, r["f_retracted"], r["tip"], r["iterations"]))
    check(r["iterations"] <= 8, "%s fit: at most 8 Newton iterations" % fit)
    if fit == "mass":
        worst = max(abs(stored[b]["I"] / (r["c"] * steel[b]) - 1) for b in steel)
        rho = stored["boom1"]["rho"] / (7850.0 * r["p2"]) - 1
        check(worst < 1e-6 and abs(rho) < 1e-6, "the scene's I and density are the mass fit's (c = %.7f, m = %.7f; "
              "largest relative difference %.1e, %.1e)" % (r["c"], r["p2"], worst, rho))
sys.exit(1 if failures else 0)
