#!/usr/bin/env python3
"""Frequency along a run (paper Fig. 7): the tracked first bending frequency
from the eigen-analysis (/tracking; every followed mode when the scene
follows several, tracking.follow), the dominant frequency of the tip
vibration from zero crossings (independent of the eigen-analysis), and the
paper's values (27.0 Hz retracted, 10.2 Hz fully extended). Damped models
(the damped eigen-analysis wrote /tracking/damping_ratio) also get the
tracked mode's damped frequency and, on a second axis beside the
frequency, its damping ratio in percent.

  /usr/bin/python3 postprocess/plot_frequency.py RUN.h5 [-o OUT.png] [--paper]
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
from signal_frequency import zero_crossing_frequency  # noqa: E402

PAPER = {"retracted": (0.0, 2.0, 27.0), "extended": 10.2, "t_end": 7.0}


def frequency_data(f):
    """(tracking times, tracked Hz, crossing times, crossing Hz, signal name)."""
    if "tracking" not in f:
        raise SystemExit("no /tracking in this file: run a scene with a 'tracking' block (docs/scenes.md)")
    tt = f["tracking/time"][()]
    fr = f["tracking/tracked_hz"][()]
    t = f["steps/time"][()]
    # The global vertical tip position carries the first global mode; a
    # moving-frame deflection would mostly show higher modes (in the first
    # mode the outer boom moves nearly rigidly).
    sensors = list(f["sensors"].keys())
    name = "tip" if "tip" in sensors else sensors[0]
    y, name = f["sensors/%s/position" % name][:, 1], "vertical position of sensor '%s'" % name
    # A trend window of a few periods of the lowest tracked frequency.
    tc, fc = zero_crossing_frequency(t, y, 3.0 / max(fr.min(), 1e-9))
    return tt, fr, tc, fc, name


def followed_data(f):
    """(followed Hz (m, n), followed index (m, n)) of every followed mode (tracking.follow), or None
    when the run follows one mode (or predates tracking.follow)."""
    if "tracking/followed_hz" not in f or f["tracking/followed_hz"].shape[1] < 2:
        return None
    return f["tracking/followed_hz"][()], f["tracking/followed_index"][()]


def damping_data(f):
    """(tracked damped Hz, damping ratio) of the tracked mode, or None for undamped runs."""
    if "tracking/damping_ratio" not in f:
        return None
    return f["tracking/tracked_damped_hz"][()], f["tracking/damping_ratio"][()]


def make_figure(run, paper=False):
    """The Fig. 7 figure of results file `run`: (matplotlib Figure, tracking times, tracked Hz)."""
    with boomdyn_h5.open_run(run) as f:
        scene = boomdyn_h5.scene_name(f)
        tt, fr, tc, fc, signal = frequency_data(f)
        damped = damping_data(f)
        followed = followed_data(f)
    fig, ax = plt.subplots(figsize=(8, 4.5))
    if followed is None:
        ax.plot(tt, fr, "-", lw=2, label="first bending mode (eigen-analysis, tracked by MAC)")
    else:
        # Every followed mode (tracking.follow), each carried by its own MAC;
        # a log axis when they span more than a decade (pendulum and bending).
        hz, index = followed
        for j in range(hz.shape[1]):
            ax.plot(tt, hz[:, j], "-", lw=2, color="C%d" % (2 * j),
                    label="followed mode %d (eigen-analysis, MAC): %.3g -> %.3g Hz, index %d -> %d"
                    % (j + 1, hz[0, j], hz[-1, j], index[0, j], index[-1, j]))
        if hz.max() > 10 * max(hz.min(), 1e-12):
            ax.set_yscale("log")
    ax.plot(tc, fc, ".", ms=3, alpha=0.6, label="zero crossings of the %s" % signal)
    lines = []
    if followed is not None and damped is not None:
        # Per followed mode its damped mode (followed_damped_*), drawn where
        # the assignment is meaningful (damped MAC >= 0.5; a mode the damped
        # analysis did not find gets the best of the rest, with a small MAC).
        with boomdyn_h5.open_run(run) as f:
            fd = f["tracking/followed_damped_hz"][()]
            zeta = f["tracking/followed_damping_ratio"][()]
            dmac = f["tracking/followed_damped_mac"][()]
        right = ax.twinx()
        for j in range(fd.shape[1]):
            ok = dmac[:, j] >= 0.5
            ax.plot(tt, np.where(ok, fd[:, j], np.nan), "--", lw=1, color="C%d" % (2 * j),
                    label="followed mode %d: damped frequency (damped MAC >= 0.5)" % (j + 1))
            lines += right.plot(tt, np.where(ok, 100.0 * zeta[:, j], np.nan), ":", lw=1.5, color="C%d" % (2 * j + 1),
                                label="followed mode %d: damping ratio (right axis)" % (j + 1))
        right.set_ylabel("damping ratio [%]")
        right.set_ylim(bottom=0.0)
    elif damped is not None:
        fd, zeta = damped
        ax.plot(tt, fd, "--", lw=1, color="C0", label="its damped frequency (damped eigen-analysis)")
        right = ax.twinx()
        lines = right.plot(tt, 100.0 * zeta, "-", lw=1.5, color="C3", label="its damping ratio (right axis)")
        right.set_ylabel("damping ratio [%]", color="C3")
        right.tick_params(axis="y", colors="C3")
        right.set_ylim(bottom=0.0)
    if paper:
        t0, t1, f0 = PAPER["retracted"]
        ax.plot([t0, t1], [f0, f0], "k--", lw=1, label="paper: 27.0 Hz retracted, 10.2 Hz extended")
        ax.plot([PAPER["t_end"]], [PAPER["extended"]], "ks", ms=6)
    ax.set_xlabel("time [s]")
    ax.set_ylabel("frequency [Hz]")
    ax.set_title("%s: %s along the run" % (scene, "first frequency" if followed is None else "followed modes"))
    ax.grid(True, alpha=0.4)
    handles, labels = ax.get_legend_handles_labels()
    ax.legend(handles + lines, labels + [ln.get_label() for ln in lines], fontsize=8)
    fig.tight_layout()
    return fig, tt, fr


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("run")
    p.add_argument("-o", "--out")
    p.add_argument("--paper", action="store_true", help="mark the paper's 27.0 Hz and 10.2 Hz")
    a = p.parse_args(argv)
    out = a.out or os.path.splitext(a.run)[0] + "_frequency.png"
    fig, tt, fr = make_figure(a.run, a.paper)
    fig.savefig(out, dpi=120)
    print("wrote %s" % out)
    print("tracked: %.3f Hz at t = %.2f s, %.3f Hz at t = %.2f s" % (fr[0], tt[0], fr[-1], tt[-1]))
    with boomdyn_h5.open_run(a.run) as f:
        damped = damping_data(f)
    if damped is not None:
        print("damping ratio: %.3f %% at t = %.2f s, %.3f %% at t = %.2f s"
              % (100 * damped[1][0], tt[0], 100 * damped[1][-1], tt[-1]))


if __name__ == "__main__":
    main()
