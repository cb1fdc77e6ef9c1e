#!/usr/bin/env python3
"""Runs every paper scene in inputs/ and prints, per scene: final tip position
(global), final tip deflection in boom 3's moving frame (paper Fig. 9: origin
at boom 3's rear end, x-axis through its two joint definition points, i.e.
the rear pad and the contact point of joint j3 on boom 3), max constraint
violation, Newton iterations per step, wall time, and the rope slack: slack
events of the elastic rope pair (type events "slack"), or for the inextensible
rope of the single-calibration variant the steps in which it would push.

  /usr/bin/python3 benchmarks/paper_scenes.py [--out DIR]
"""
import argparse
import os
import subprocess
import sys

import h5py

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "postprocess"))
from centerline import moving_frame_deflection  # noqa: E402

SCENES = ["paper_extraction", "paper_extraction_5kN", "paper_extraction_20kN", "paper_rigid_booms",
          "paper_elevation_35", "paper_elevation_70", "paper_extraction_single_calibration"]


def summarize(path):
    with h5py.File(path) as f:
        names = list(f["layout/body_names"].asstr()[:])
        b = names.index("boom3")
        first = int(f["layout/body_first_coordinate"][b])
        n = int(f["layout/body_num_coordinates"][b])
        joints = list(f["layout/sliding_joint_names"].asstr()[:])
        q = f["state/q"][-1]
        s3 = f["steps/slack"][-1][joints.index("j3")]
        tip = f["sensors/tip/position"][-1]
        its = f["steps/newton_iterations"][1:]
        s = f["summary"].attrs
        kinds = list(f["layout/type_event_kinds"].asstr()[:]) if "layout/type_event_kinds" in f else []
        slack_events = (int(sum(1 for k in f["type_events/kind"][()] if kinds[k] == "slack"))
                        if "slack" in kinds and "type_events/kind" in f else 0)
        elastic = any(n.startswith("elastic_rope/") for n in f["layout/output_names"].asstr()[:]) \
            if "layout/output_names" in f else False
        return dict(tip=tip, frame=moving_frame_deflection(q, first, n, 2.0, s3, 2.0), viol=float(s["max_constraint_violation"]),
                    its=float(its.mean()), wall=float(s["wall_time_s"]), status=s["status"],
                    slack="%d events" % slack_events if elastic else "%d steps" % int(s["slack_rope_steps"]))


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--out", default=os.path.join(ROOT, "out", "paper"))
    p.add_argument("--scenes", nargs="+", default=SCENES, help="scene names (default: all seven)")
    a = p.parse_args()
    os.makedirs(a.out, exist_ok=True)
    print("| scene | tip x, y at 7 s [m] | tip deflection, moving frame [mm] | max violation | Newton it/step | wall [s] | rope slack |")
    print("|---|---|---:|---:|---:|---:|---:|")
    for sc in a.scenes:
        out = os.path.join(a.out, sc + ".h5")
        subprocess.run([os.path.join(ROOT, "build", "boomdyn"), os.path.join(ROOT, "inputs", sc + ".yaml"), "-o", out,
                        "-boom_overwrite", "-boom_quiet"], check=True)
        r = summarize(out)
        print("| %s | %.4f, %.5f | %.3f | %.1e | %.2f | %.1f | %s |" % (sc, r["tip"][0], r["tip"][1], 1e3 * r["frame"], r["viol"],
                                                                  r["its"], r["wall"], r["slack"]), flush=True)


if __name__ == "__main__":
    main()
