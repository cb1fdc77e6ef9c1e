#!/usr/bin/env python3
"""A modal scene of a damped model writes its damped modes (docs/output.md,
/modal/damped_frequencies_hz, undamped_equivalent_hz, damping_ratio,
decay_rates; an overdamped cantilever its two real decay rates per mode), and
frequency tracking in a dynamic run of it writes /tracking/damping_ratio and
tracked_damped_hz; an undamped model writes none of them. The 16-element steel cantilever with damping_ratio
0.02 at its first frequency f_1 has stiffness-proportional damping D = eta K,
so every mode has zeta_n = 0.02 f_n / f_1, |lambda_n| / 2 pi = f_n and
f_d,n = f_n sqrt(1 - zeta_n^2), with f_n from the same file.
Usage: test_damped_modal_output.py BOOMDYN_EXECUTABLE SOURCE_DIR WORK_DIR"""
import os
import subprocess
import sys

import h5py
import numpy as np

boomdyn, source, work = sys.argv[1:4]
sys.path.insert(0, os.path.join(source, "tests"))
import script_checks  # noqa: E402

results = []
check = script_checks.checker(results)

SCENE = """name: damped-cantilever-modal
analysis: modal
bodies:
  - name: boom
    length: 2.0
    elements: 16
    section: {{EA: 8.5176e8, EI: 4.9531e6, rhoA: 31.8396{damping}}}
constraints:
  - {{type: clamp, body: boom, at: start}}
{tail}
"""
MODAL = "modal: {count: 4}"
# At rest (no load, no gravity): every analysis sees the unstressed beam.
TRACKING = "dynamic: {t_end: 0.01, dt: 1.0e-3}\ntracking: {interval: 0.005, count: 3}"


def run(name, damping, tail=MODAL):
    scene = os.path.join(work, name + ".yaml")
    text = SCENE.format(damping=damping, tail=tail)
    if tail is TRACKING:
        text = text.replace("analysis: modal", "analysis: dynamic")
    with open(scene, "w") as f:
        f.write(text)
    out = os.path.join(work, name + ".h5")
    subprocess.run([boomdyn, scene, "-o", out, "-boom_overwrite", "-boom_quiet"], check=True, stdout=subprocess.DEVNULL)
    return out


def main():
    with h5py.File(run("undamped_modal", "")) as f:
        f1 = float(f["modal/frequencies_hz"][0])
        check("damping_ratio" not in f["modal"] and "damped_frequencies_hz" not in f["modal"],
              "an undamped model writes no damped modes")
    with h5py.File(run("damped_modal", ", damping_ratio: 0.02, damping_frequency: %.17g" % f1)) as f:
        m = f["modal"]
        present = all(k in m for k in ("damped_frequencies_hz", "undamped_equivalent_hz", "damping_ratio"))
        check(present, "a damped model writes damped_frequencies_hz, undamped_equivalent_hz, damping_ratio")
        if not present:
            return
        fn = m["frequencies_hz"][()]
        zeta = 0.02 * fn / f1
        e_zeta = np.max(np.abs(m["damping_ratio"][()] - zeta) / zeta)
        e_fd = np.max(np.abs(m["damped_frequencies_hz"][()] - fn * np.sqrt(1 - zeta**2)) / fn)
        e_abs = np.max(np.abs(m["undamped_equivalent_hz"][()] - fn) / fn)
        check(len(m["damping_ratio"]) == 4, "4 damped modes written")
        check(e_zeta < 1e-4, "zeta_n = 0.02 f_n / f_1 for modes 1-4 (worst relative error %.2e)" % e_zeta)
        check(e_fd < 1e-4, "f_d,n = f_n sqrt(1 - zeta_n^2) (worst relative error %.2e)" % e_fd)
        check(e_abs < 1e-4, "|lambda_n| / 2 pi = f_n (worst relative error %.2e)" % e_abs)
    # Heavy damping (issue 40): zeta_1 = 2, every mode overdamped. Two real
    # decay rates per mode, omega_n (zeta_n -+ sqrt(zeta_n^2 - 1)), no damped
    # frequency, the damping ratio above 1 (was: invented MHz modes).
    with h5py.File(run("overdamped_modal", ", damping_ratio: 2.0, damping_frequency: %.17g" % f1)) as f:
        m = f["modal"]
        check("decay_rates" in m and m["decay_rates"].shape == (4, 2), "decay_rates (4, 2) written")
        if "decay_rates" not in m:
            return
        omega = 2 * np.pi * m["frequencies_hz"][()]
        zeta = 2.0 * m["frequencies_hz"][()] / f1
        fast = omega * (zeta + np.sqrt(zeta**2 - 1))
        slow = omega**2 / fast
        rates = m["decay_rates"][()]
        e_rates = max(np.max(np.abs(rates[:, 0] - slow) / slow), np.max(np.abs(rates[:, 1] - fast) / fast))
        e_zeta = np.max(np.abs(m["damping_ratio"][()] - zeta) / zeta)
        check(e_rates < 1e-8, "overdamped: both decay rates of modes 1-4 in closed form (worst relative error %.2e)"
              % e_rates)
        check(e_zeta < 1e-8, "overdamped: zeta_n = 2 f_n / f_1 > 1 (worst relative error %.2e)" % e_zeta)
        check(np.all(m["damped_frequencies_hz"][()] == 0), "overdamped: no damped frequency (0)")
    with h5py.File(run("undamped_tracking", "", TRACKING)) as f:
        check("damping_ratio" not in f["tracking"], "undamped tracking writes no damping ratio")
    with h5py.File(run("damped_tracking", ", damping_ratio: 0.02, damping_frequency: %.17g" % f1, TRACKING)) as f:
        t = f["tracking"]
        present = all(k in t for k in ("damping_ratio", "tracked_damped_hz", "damped_mac"))
        check(present, "damped tracking writes damping_ratio, tracked_damped_hz, damped_mac")
        if not present:
            return
        ft = t["tracked_hz"][()]
        zeta = 0.02 * ft / f1
        e_zeta = np.max(np.abs(t["damping_ratio"][()] - zeta) / zeta)
        e_fd = np.max(np.abs(t["tracked_damped_hz"][()] - ft * np.sqrt(1 - zeta**2)) / ft)
        check(len(ft) == 3, "3 analyses (t = 0, 0.005, 0.01 s; got %d)" % len(ft))
        check(e_zeta < 1e-4, "tracked zeta = 0.02 f / f_1 (worst relative error %.2e)" % e_zeta)
        check(e_fd < 1e-4, "tracked f_d = f sqrt(1 - zeta^2) (worst relative error %.2e)" % e_fd)
        check(np.min(t["damped_mac"][()]) > 0.999, "MAC of the damped against the undamped shape %.6f" %
              np.min(t["damped_mac"][()]))


sys.exit(script_checks.finish(main, results))
