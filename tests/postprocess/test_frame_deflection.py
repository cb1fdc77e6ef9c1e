#!/usr/bin/env python3
"""The moving-frame deflection boomdyn writes every step (/steps/frame_deflection,
C++) against an independent evaluation from the last saved state with
postprocess/centerline.py (Python), on a short run of the paper extraction
scene. Usage: test_frame_deflection.py BOOMDYN_EXECUTABLE SOURCE_DIR WORK_DIR"""
import os
import subprocess
import sys

import h5py

boomdyn, source, work = sys.argv[1:4]
sys.path.insert(0, os.path.join(source, "postprocess"))
from centerline import moving_frame_deflection  # noqa: E402

out = os.path.join(work, "frame_deflection.h5")
subprocess.run([boomdyn, os.path.join(source, "inputs", "paper_extraction.yaml"), "-o", out, "-boom_overwrite",
                "-boom_quiet", "-ts_max_time", "0.3", "-boom_elements", "8"], check=True, stdout=subprocess.DEVNULL)
with h5py.File(out) as f:
    names = list(f["layout/body_names"].asstr()[:])
    b = names.index("boom3")
    first, n = int(f["layout/body_first_coordinate"][b]), int(f["layout/body_num_coordinates"][b])
    joints = list(f["layout/sliding_joint_names"].asstr()[:])
    s_axis = f["steps/slack"][-1][joints.index("j3")]
    written = f["steps/frame_deflection"][-1][0]
    assert abs(f["state/time"][-1] - f["steps/time"][-1]) < 1e-12
    independent = moving_frame_deflection(f["state/q"][-1], first, n, 2.0, s_axis, 2.0)
diff = abs(written - independent)
print("frame deflection: written %.12e m, independent %.12e m, difference %.1e m" % (written, independent, diff))
assert diff < 1e-12 * max(1.0, abs(independent)) + 1e-15, "frame deflections differ"
assert abs(independent) > 1e-5, "the tip must actually deflect"
print("1 passed, 0 failed")
