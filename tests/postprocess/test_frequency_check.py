#!/usr/bin/env python3
"""Independent check of the tracked first frequency: the dominant frequency
of the simulated tip vibration (zero crossings, postprocess/signal_frequency.py)
must follow the eigen-analysis along the paper extraction scene, here its
first 3.5 s (2 s at rest at 27 Hz, then 0.375 m of extraction per stage).
Also renders the Fig. 7 plot and checks it is a non-empty picture; the
scene is damped (Kelvin-Voigt, eta on every boom), so the tracking also has
the damping ratio of the tracked mode, which must follow zeta = eta omega / 2
(stiffness-proportional damping; the geometric stiffness of the loads, the
pads and the ropes are damped otherwise, so within 3 %), and the plot shows it
on a second axis. The retracted 27.0 Hz is calibrated in the static
equilibrium (postprocess/calibrate_paper.py); the run starts undeformed under
the step load, where the tracked frequency is 27.025 Hz: within 0.1 %.
Usage: test_frequency_check.py BOOMDYN_EXECUTABLE SOURCE_DIR WORK_DIR"""
import os
import subprocess
import sys

import re

import h5py
import matplotlib.image
import numpy as np

boomdyn, source, work = sys.argv[1:4]
sys.path.insert(0, os.path.join(source, "postprocess"))
from signal_frequency import zero_crossing_frequency  # noqa: E402
import plot_frequency  # noqa: E402

out = os.path.join(work, "frequency_check.h5")
subprocess.run([boomdyn, os.path.join(source, "inputs", "paper_extraction.yaml"), "-o", out, "-boom_overwrite",
                "-boom_quiet", "-ts_max_time", "3.5"], check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
with h5py.File(out) as f:
    tt, fr = f["tracking/time"][()], f["tracking/tracked_hz"][()]
    t, y = f["steps/time"][()], f["sensors/tip/position"][:, 1]
    scene_text = f["scene/text"][()]
    zeta = f["tracking/damping_ratio"][()] if "tracking/damping_ratio" in f else None
tc, fc = zero_crossing_frequency(t, y, 3.0 / fr.min())
keep = (tc > 0.3) & (tc < 3.3)  # away from the ends of the moving average
rel = np.abs(fc[keep] - np.interp(tc[keep], tt, fr)) / np.interp(tc[keep], tt, fr)
print("zero crossings: %d periods, median relative difference %.2e, 90th percentile %.2e; tracked %.3f -> %.3f Hz"
      % (keep.sum(), np.median(rel), np.percentile(rel, 90), fr[0], fr[-1]))
passed = failed = 0
for ok, what in [(keep.sum() > 50, "enough periods"), (np.median(rel) < 0.01, "median within 1 %"),
                 (np.percentile(rel, 90) < 0.03, "90 % within 3 %"), (abs(fr[0] / 27.0 - 1) < 1e-3, "27.0 Hz retracted within 0.1 %"),
                 (fr[-1] < 0.9 * fr[0], "frequency falls during extraction")]:
    print(("ok   " if ok else "FAIL ") + what)
    passed, failed = passed + ok, failed + (not ok)
scene_text = scene_text.decode() if isinstance(scene_text, bytes) else str(scene_text)
etas = {float(v) for v in re.findall(r"eta_bending: ([0-9.eE+-]+)", scene_text)}
checks = [(zeta is not None, "damped scene: /tracking/damping_ratio written")]
if zeta is not None and len(etas) == 1:
    expected = np.pi * etas.pop() * fr  # zeta = eta omega / 2
    worst = float(np.max(np.abs(zeta - expected) / expected))
    print("damping ratio %.4f %% -> %.4f %%, eta omega / 2 %.4f %% -> %.4f %%, worst relative difference %.2e"
          % (100 * zeta[0], 100 * zeta[-1], 100 * expected[0], 100 * expected[-1], worst))
    checks.append((worst < 0.03, "damping ratio follows eta omega / 2 within 3 %"))
    fig, _, _ = plot_frequency.make_figure(out, paper=True)
    checks.append((len(fig.axes) == 2 and "damping" in fig.axes[1].get_ylabel(), "damping ratio on a second axis"))
for ok, what in checks:
    print(("ok   " if ok else "FAIL ") + what)
    passed, failed = passed + ok, failed + (not ok)
png = os.path.join(work, "frequency_check.png")
subprocess.run([sys.executable, os.path.join(source, "postprocess", "plot_frequency.py"), out, "-o", png, "--paper"],
               check=True, stdout=subprocess.DEVNULL)
img = matplotlib.image.imread(png)
ok = img.size > 0 and float(img.std()) > 0
print(("ok   " if ok else "FAIL ") + "Fig. 7 plot is a non-empty picture")
passed, failed = passed + ok, failed + (not ok)
# plot_run.py on the same (real) run: the joint, rope, frame and frequency figures.
plots = os.path.join(work, "frequency_check_plots")
subprocess.run([sys.executable, os.path.join(source, "postprocess", "plot_run.py"), out, "-o", plots], check=True,
               stdout=subprocess.DEVNULL)
for name in ("frame_deflection", "slack_coordinates", "rope_tension", "contact_forces", "frequency", "tip_vertical_position"):
    p = os.path.join(plots, name + ".png")
    ok = os.path.exists(p) and float(matplotlib.image.imread(p).std()) > 0
    print(("ok   " if ok else "FAIL ") + "plot_run.py wrote a non-empty %s.png" % name)
    passed, failed = passed + ok, failed + (not ok)
print("%d passed, %d failed" % (passed, failed))
sys.exit(1 if failed else 0)
