#!/usr/bin/env python3
"""Stick-slip figure (paper Fig. 5): elevation angle of the first boom and the
slack coordinate(s) of the frictional sliding joints against time, with the
slip intervals shaded and the stick/slip events marked.

  /usr/bin/python3 postprocess/plot_stick_slip.py RUN.h5 [-o OUT.png] [--paper]
"""
import argparse
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import boomdyn_h5  # noqa: E402


def elevation_deg(f):
    """Angle of the first body's axis at s = 0 (slope coordinates of node 0), in degrees."""
    q = f["state/q"][()]
    first = int(f["layout/body_first_coordinate"][0])
    return f["state/time"][()], np.degrees(np.arctan2(q[:, first + 3], q[:, first + 2]))


PAPER_EVENTS = ((5.4, "slides out"), (8.3, "sticks"), (13.5, "slides in"))  # Fig. 5, joint between booms 1 and 2


def make_figure(run, paper=False):
    """The Fig. 5 figure of results file `run` (matplotlib Figure); with `paper`, the paper's event times marked."""
    with boomdyn_h5.open_run(run) as f:
        if "steps/friction_slipping" not in f:
            raise SystemExit("no friction data in this file (a scene with sliding_joint friction is needed)")
        scene = boomdyn_h5.scene_name(f)
        t = f["steps/time"][()]
        joints = [s.decode() if isinstance(s, bytes) else s for s in f["layout/sliding_joint_names"][()]]
        friction = [s.decode() if isinstance(s, bytes) else s for s in f["layout/friction_joint_names"][()]]
        slack = f["steps/slack"][()]
        slipping = f["steps/friction_slipping"][()]
        te, angle = elevation_deg(f)
        events = (f["events/time"][()], f["events/joint"][()], f["events/to_slip"][()]) if "events" in f else None
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(8, 6), sharex=True)
    ax1.plot(te, angle, "k-")
    ax1.set_ylabel("elevation angle [deg]")
    ax1.set_title("%s: elevation and slack coordinates (paper Fig. 5)" % scene)
    for j, name in enumerate(friction):
        col = joints.index(name)
        ax2.plot(t, slack[:, col], label="s of joint %s" % name)
    # Shade the intervals in which the first frictional joint slips.
    s0 = slipping[:, 0].astype(bool)
    for ax in (ax1, ax2):
        ax.fill_between(t, 0, 1, where=s0, color="orange", alpha=0.25, transform=ax.get_xaxis_transform(),
                        label="slip (%s)" % friction[0] if ax is ax2 else None)
        ax.grid(True, alpha=0.4)
    if events is not None:
        for tt, j, to_slip in zip(*events):
            if j == 0:
                ax2.axvline(tt, color="r" if to_slip else "b", lw=0.8, ls="--")
                ax2.annotate("%.1f s" % tt, (tt, ax2.get_ylim()[1]), fontsize=7, rotation=90, va="top")
    if paper:
        for k, (tt, what) in enumerate(PAPER_EVENTS):
            for ax in (ax1, ax2):
                ax.axvline(tt, color="k", lw=1.2, ls=":", label="paper's events (5.4, 8.3, 13.5 s)"
                           if (k == 0 and ax is ax2) else None)
            ax1.annotate("paper: " + what, (tt, ax1.get_ylim()[0]), fontsize=7, rotation=90, va="bottom",
                         ha="right")
    ax2.set_xlabel("time [s]")
    ax2.set_ylabel("arc-length coordinate [m]")
    ax2.legend(fontsize=8, loc="best")
    fig.tight_layout()
    return fig


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("run")
    p.add_argument("-o", "--out")
    p.add_argument("--paper", action="store_true", help="mark the paper's event times (5.4, 8.3, 13.5 s)")
    a = p.parse_args(argv)
    out = a.out or os.path.splitext(a.run)[0] + "_stick_slip.png"
    fig = make_figure(a.run, a.paper)
    fig.savefig(out, dpi=120)
    print("wrote %s" % out)


if __name__ == "__main__":
    main()
