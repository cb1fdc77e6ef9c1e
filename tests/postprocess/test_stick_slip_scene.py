#!/usr/bin/env python3
"""The paper's stick-slip scene (inputs/paper_stick_slip.yaml, Fig. 5): boom 2
must stick, slide out of boom 1 as the elevation falls, stick again, and slide
back in as the elevation rises, with the transitions near the paper's times
(5.4 s, 8.3 s, 13.5 s; windows of a few seconds, because neither the paper's
elevation profile nor its LuGre parameters are known). Also renders the
Fig. 5 plot and checks it is a non-empty picture.
Usage: test_stick_slip_scene.py BOOMDYN_EXECUTABLE SOURCE_DIR WORK_DIR"""
import os
import subprocess
import sys

import h5py
import matplotlib.image
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import script_checks  # noqa: E402

boomdyn, source, work = sys.argv[1:4]
out = os.path.join(work, "stick_slip_scene.h5")
subprocess.run([boomdyn, os.path.join(source, "inputs", "paper_stick_slip.yaml"), "-o", out, "-boom_overwrite",
                "-boom_quiet"], check=True, stdout=subprocess.DEVNULL)
with h5py.File(out) as f:
    joints = [s.decode() if isinstance(s, bytes) else s for s in f["layout/friction_joint_names"][()]]
    j2 = joints.index("j2")
    ev = [(t, bool(s), d) for t, j, s, d in zip(f["events/time"][()], f["events/joint"][()], f["events/to_slip"][()],
                                                 f["events/direction"][()]) if j == j2]
    slack = f["steps/slack"][()]
    names = [s.decode() if isinstance(s, bytes) else s for s in f["layout/sliding_joint_names"][()]]
    s2 = slack[:, names.index("j2")]
print("events of j2:", ", ".join("%.3f s %s (%s)" % (t, "stick->slip" if s else "slip->stick",
                                                     "s increasing" if d < 0 else "s decreasing") for t, s, d in ev))
print("s of j2: %.4f m at start, %.4f m at the end" % (s2[0], s2[-1]))
late = [e for e in ev if e[0] > 3.0]  # after the start-up transient of the sudden gravity load
checks = []
out_slide = [e for e in late if e[1] and e[2] < 0]   # stick -> slip, s on boom 1 increasing: sliding out
stop = [e for e in late if not e[1] and out_slide and e[0] > out_slide[0][0]]
in_slide = [e for e in late if e[1] and e[2] > 0 and stop and e[0] > stop[0][0]]
checks.append((bool(out_slide) and 3.5 < out_slide[0][0] < 6.5, "slides out near 5.4 s"))
checks.append((bool(stop) and 8.0 < stop[0][0] < 11.5, "sticks again near 8.3 s"))
checks.append((bool(in_slide) and 12.0 < in_slide[0][0] < 14.0, "slides in near 13.5 s"))
checks.append((s2.max() - s2[0] > 0.3, "boom 2 actually slid out (more than 0.3 m)"))
png = os.path.join(work, "stick_slip_scene.png")
subprocess.run([sys.executable, os.path.join(source, "postprocess", "plot_stick_slip.py"), out, "-o", png], check=True,
               stdout=subprocess.DEVNULL)
img = matplotlib.image.imread(png)
checks.append((img.size > 0 and float(img.std()) > 0, "Fig. 5 plot is a non-empty picture"))
sys.exit(script_checks.report(checks))
