#!/usr/bin/env python3
"""The study driver postprocess/study.py: quantity extraction (dataset index,
LABEL=, max()/min()/mean(), time windows, /events filtered by joint name,
kind, direction and time, nan for a missing event) on a synthetic results file, then whole studies with
boomdyn: the single-quantity command line of docs/studies.md (static
cantilever, mesh orders), several quantities with absolute errors and event
times (short stick-slip run, step series), --runs and --reuse (nothing run
again), and a study whose runs fail.
Usage: test_study.py BOOMDYN_EXECUTABLE SOURCE_DIR WORK_DIR"""
import json
import math
import os
import subprocess
import sys

import h5py
import numpy as np
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import script_checks  # noqa: E402

boomdyn, source, work = sys.argv[1:4]
sys.path.insert(0, os.path.join(source, "postprocess"))
import study  # noqa: E402

script = os.path.join(source, "postprocess", "study.py")
work = os.path.join(work, "study_test")
os.makedirs(work, exist_ok=True)
checks = []


def check(ok, what):
    checks.append((bool(ok), what))


# 1. Extraction on a synthetic file.
synthetic = os.path.join(work, "synthetic.h5")
with h5py.File(synthetic, "w") as f:
    f["layout/friction_joint_names"] = np.array([b"j1", b"j2"], dtype=h5py.string_dtype())
    f["events/time"] = [0.1, 0.1, 2.0, 4.0, 4.0, 9.0]
    f["events/joint"] = np.array([0, 1, 1, 0, 1, 1], dtype=np.int32)
    f["events/to_slip"] = np.array([1, 1, 0, 1, 1, 0], dtype=np.int32)
    f["events/direction"] = np.array([-1, 1, 1, 1, -1, -1], dtype=np.int32)
    f["steps/slack"] = [[1.0, 0.5], [1.2, 0.7], [0.9, 0.6]]
    f["steps/time"] = [0.0, 1.0, 2.0]
    f["sensors/tip/position"] = [[0.0, -1.0], [0.0, -2.0], [0.0, -4.0]]
x = lambda q: study.extract(synthetic, q)  # noqa: E731
check(x("steps/slack[-1,1]") == 0.6, "dataset with a numpy index")
check(x("s=steps/slack[1,0]") == 1.2, "LABEL= prefix")
check(study.split_label("s=steps/slack[1,0]") == ("s", "steps/slack[1,0]"), "label split")
check(study.split_label("events/time{joint=j2}[0]")[0] == "events/time{joint=j2}[0]", "no label in a filter")
check(x("max(steps/slack[:,0])") == 1.2 and x("min(steps/slack[:,1])") == 0.5, "max() and min()")
check(abs(x("mean(steps/slack{after=0.5}[:,0])") - 1.05) < 1e-15, "mean() over a time window")
check(x("sensors/tip/position{before=1.5}[-1,1]") == -2.0, "sensor rows by /steps/time")
check(math.isnan(x("mean(steps/slack{after=5}[:,0])")), "empty time window gives nan")
try:
    x("steps/slack{joint=j1}[0,0]")
    check(False, "joint filter outside /events is an error")
except SystemExit as e:
    check("after, before" in str(e), "joint filter outside /events is an error")
check(x("events/time[2]") == 2.0, "unfiltered event")
check(x("events/time{joint=j2}[1]") == 2.0, "events of a joint by name")
check(x("events/time{joint=0}[-1]") == 4.0, "events of a joint by index")
check(x("events/time{joint=j2,to_slip=1,direction=-1}[0]") == 4.0, "stick -> slip with s increasing")
check(x("events/time{joint=j2,to_slip=0,after=3}[0]") == 9.0, "slip -> stick after a time")
check(x("events/time{joint=j2,before=3}[-1]") == 2.0, "events before a time")
check(math.isnan(x("events/time{joint=j1,to_slip=0}[0]")), "missing event gives nan")
try:
    x("events/time{joint=j9}[0]")
    check(False, "unknown joint is an error")
except SystemExit as e:
    check("j9" in str(e), "unknown joint is an error naming it")

# 2. The single-quantity command line (docs/studies.md): static cantilever, mesh series.
build = os.path.dirname(os.path.abspath(boomdyn))
stem = os.path.join(work, "cantilever")
subprocess.run([sys.executable, script, os.path.join(source, "inputs", "cantilever_static.yaml"),
                "--quantity", "sensors/tip/position[-1,1]", "--elements", "2", "4", "8", "--out", stem,
                "--build", build], check=True, stdout=subprocess.DEVNULL)
md = open(stem + ".md").read()
rows = [line for line in md.splitlines() if line.startswith("| ") and line.split("|")[2].strip().isdigit()]
check(len(rows) == 3 and md.count("| order |") == 1, "one table of three runs")
order = float(rows[1].split("|")[6])
check(order > 3.0, "mesh order of the static tip deflection above 3 (%.2f)" % order)
check(os.path.getsize(stem + ".png") > 1000 and os.path.isdir(stem + "_runs"), "plot and runs folder written")

# 3. Several quantities, absolute errors, event times: 2 s of the stick-slip scene, step series. The
# scene as it was before issue 14 item 6 (undamped, sine elevation starting at 10.55 deg, single-number
# sections), whose step start
# gives a start-up slip and stick within 2 s; the damped scene in inputs/ sticks until 5.4 s.
stick_scene = os.path.join(work, "stick_slip_undamped.yaml")
text = open(os.path.join(source, "inputs", "paper_stick_slip.yaml")).read()
for old, new in ((", eta_axial: 1.04e-4, eta_bending: 1.04e-4", ""), ("    angle: 0\n", "    angle: 10.546201359107435\n"),
                 ("origin: [0.5, 0]", "origin: [0.4915538197046371, 0.09151416466198646]"),
                 ("I: 1.2005318e-05, rho: 2560.7297", "I: 3.6753355e-5, rho: 7850"),
                 ("I: 6.9838877e-06, rho: 2560.7297", "I: 2.1380634e-5, rho: 7850"),
                 ("angle: {type: table, t: [0, 6.2986, 14.0], values: [0, -10.0, 19.2368]}",
                  "angle: {type: sine, amplitude: 15, frequency: 0.044310, phase: 158.3, offset: 5}")):
    assert old in text, "inputs/paper_stick_slip.yaml changed: no %r" % old
    text = text.replace(old, new)
open(stick_scene, "w").write(text)
stem = os.path.join(work, "stick_slip")
runs = os.path.join(work, "stick_slip_files")
subprocess.run([sys.executable, script, stick_scene,
                "--quantity", "slip=events/time{joint=j2,to_slip=1}[0]", "stick=events/time{joint=j2,to_slip=0}[0]",
                "--quantity", "never=events/time{joint=j2,after=1.95}[0]", "s_end=steps/slack[-1,1]",
                "--elements", "4", "--dt", "4e-3", "2e-3", "1e-3", "--error", "absolute", "--out", stem, "--runs", runs,
                "--build", build, "--", "-ts_max_time", "1.9"], check=True, stdout=subprocess.DEVNULL)
result = json.load(open(stem + ".json"))
r = result["runs"]
check(len(r) == 3 and all(run["status"] == "completed" for run in r), "three completed runs")
check(len(os.listdir(runs)) >= 3, "--runs folder holds the results files")
check(all(0 < run["values"]["slip=events/time{joint=j2,to_slip=1}[0]"] < 0.1 for run in r), "start-up slip found")
stick = [run["values"]["stick=events/time{joint=j2,to_slip=0}[0]"] for run in r]
check(all(1.0 < s < 1.9 for s in stick), "start-up stick found (%s)" % stick)
e = [run["errors"]["stick=events/time{joint=j2,to_slip=0}[0]"] for run in r]
check(abs(e[0] - abs(stick[0] - stick[2])) < 1e-12 and math.isnan(e[2]), "absolute errors against the finest run")
check(all(math.isnan(run["values"]["never=events/time{joint=j2,after=1.95}[0]"]) for run in r), "missing event is nan")
md = open(stem + ".md").read()
check(all("## %s" % label in md for label in ("slip", "stick", "never", "s_end")), "one table per quantity")
check("absolute error" in md and os.path.getsize(stem + ".png") > 1000, "absolute-error tables and plot")

# --reuse: the completed runs are kept (not run again) and a quantity can be added.
stamps = {name: os.path.getmtime(os.path.join(runs, name)) for name in os.listdir(runs)}
subprocess.run([sys.executable, script, stick_scene,
                "--quantity", "stick=events/time{joint=j2,to_slip=0}[0]", "s_max=max(steps/slack[:,1])",
                "--elements", "4", "--dt", "4e-3", "2e-3", "1e-3", "--error", "absolute", "--out", stem + "_again",
                "--runs", runs, "--reuse", "--build", build, "--", "-ts_max_time", "1.9"], check=True,
               stdout=subprocess.DEVNULL)
again = json.load(open(stem + "_again.json"))["runs"]
check(stamps == {name: os.path.getmtime(os.path.join(runs, name)) for name in os.listdir(runs)},
      "--reuse runs nothing again")
check([run["values"]["stick=events/time{joint=j2,to_slip=0}[0]"] for run in again] == stick
      and all(run["wall"] > 0 and math.isfinite(run["values"]["s_max=max(steps/slack[:,1])"]) for run in again),
      "--reuse gives the same values, the recorded wall times and the added quantity")
subprocess.run([sys.executable, script, stick_scene,
                "--quantity", "stick=events/time{joint=j2,to_slip=0}[0]", "--elements", "4", "--dt", "4e-3", "2e-3",
                "1e-3", "--error", "absolute", "--out", stem, "--runs", runs, "--reuse", "--build", build, "--",
                "-ts_max_time", "1.9"], check=True, stdout=subprocess.DEVNULL)
check([(run["wall"], run["cpu"]) for run in json.load(open(stem + ".json"))["runs"]]
      == [(run["wall"], run["cpu"]) for run in r] and all(run["cpu"] > 0 for run in r),
      "--reuse with the same --out keeps the measured wall and CPU times")

# 4. Runs that fail (an unknown body) are reported, not fatal.
stem = os.path.join(work, "failing")
done = subprocess.run([sys.executable, script, os.path.join(source, "inputs", "cantilever_static.yaml"),
                       "--quantity", "sensors/tip/position[-1,1]", "--elements", "2", "4", "--out", stem,
                       "--build", build, "--", "-boom_elements_nosuchbody", "3"],
                      stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
check(done.returncode == 0 and open(stem + ".md").read().count("failed (exit") == 2, "failed runs reported")

sys.exit(script_checks.report(checks))
