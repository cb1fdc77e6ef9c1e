#!/usr/bin/env python3
"""Payload swing, hoist rope tension and tracked frequencies of a hoisting
run (inputs/hoist_*.yaml; docs/paper-scenes.md "Hoisting a payload").

One figure, three panels over time:
  1. the swing angle of the hanging rope part from the vertical (degrees,
     from the sheave sensor to the hook sensor, counter-clockwise positive);
  2. the rope tension (kN) with its static value (t = 0) and its peak, and
     the dynamic factor from /summary (docs/output.md "Design numbers");
  3. the tracked frequencies (every followed mode: the payload pendulum and
     the first bending mode in the hoist scenes) and the other frequencies of each analysis, with the
     swing frequency from the zero crossings of the swing angle (one point
     per half swing), an estimate independent of the eigen-analysis.

Usage: plot_hoist.py RUN.h5 [-o OUT.png] [--rope hoist] [--sheave tip] [--hook hook]
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


def swing_angle(f, sheave, hook):
    """(time, angle in degrees) of the line sheave -> hook from the downward vertical."""
    t = f["steps/time"][()]
    s = f[f"sensors/{sheave}/position"][()]
    h = f[f"sensors/{hook}/position"][()]
    return t, np.degrees(np.arctan2(h[:, 0] - s[:, 0], s[:, 1] - h[:, 1]))


def rope_tension(f, rope):
    """(time, tension in N) of an elastic rope (or an inextensible one) from /steps/outputs."""
    names = [n.decode() if isinstance(n, bytes) else str(n) for n in f["layout/output_names"][()]]
    for group in ("elastic_rope", "rope"):
        key = f"{group}/{rope}/tension"
        if key in names:
            return f["steps/time"][()], f["steps/outputs"][:, names.index(key)], group
    raise SystemExit(f"plot_hoist: no rope '{rope}' in /layout/output_names")


def swing_crossings(t, angle, band=1e-3):
    """Times at which the swing angle crosses zero (the rope hangs plumb in
    equilibrium), linearly interpolated between steps. Sign changes within
    +-band x the largest swing (round-off while the payload hangs at rest)
    do not count: a crossing is a change between two excursions beyond it."""
    a = np.asarray(angle, dtype=float)
    thr = band * np.max(np.abs(a)) if len(a) else 0.0
    side = np.where(np.abs(a) > thr, np.sign(a), 0.0)
    out, last = [], 0
    for i in np.nonzero(side)[0]:
        if last and side[i] != side[last]:
            # The last raw sign change between the two excursions.
            j = i - 1
            while j > last and np.sign(a[j]) == side[i]:
                j -= 1
            out.append(t[j] - a[j] * (t[j + 1] - t[j]) / (a[j + 1] - a[j]))
        last = i
    return np.array(out)


def half_swing_frequency(t, angle):
    """(times, Hz): the swing frequency from successive zero crossings, one
    value per half swing, at the half swing's middle."""
    tc = swing_crossings(t, angle)
    if len(tc) < 2:
        return np.array([]), np.array([])
    return 0.5 * (tc[1:] + tc[:-1]), 0.5 / np.diff(tc)


def design_numbers(f, group, rope):
    """The rope's design numbers from /summary (an empty dict for older files)."""
    prefix = f"design.{group}.{rope}."
    return {k[len(prefix):]: v for k, v in boomdyn_h5.attributes(f, "/summary").items() if k.startswith(prefix)}


def plot_hoist(run, out=None, rope="hoist", sheave="tip", hook="hook", max_hz=60.0):
    """Writes the figure; returns the numbers it shows (for tests and reports)."""
    out = out or os.path.splitext(run)[0] + "_hoist.png"
    with boomdyn_h5.open_run(run) as f:
        t, angle = swing_angle(f, sheave, hook)
        tt, tension, group = rope_tension(f, rope)
        design = design_numbers(f, group, rope)
        tracking = f["tracking"] if "tracking" in f else None
        tr_t = tracking["time"][()] if tracking is not None else np.array([])
        tracked = tracking["tracked_hz"][()] if tracking is not None else np.array([])
        modes = tracking["frequencies_hz"][()] if tracking is not None else np.zeros((0, 0))
        # Every followed mode (tracking.follow: pendulum and first bending mode), one column each.
        followed = tracking["followed_hz"][()] if tracking is not None and "followed_hz" in tracking else None
        name = boomdyn_h5.scene_name(f)
    zc_t, zc_hz = half_swing_frequency(t, angle)

    fig, ax = plt.subplots(3, 1, figsize=(9, 10), sharex=True)
    ax[0].plot(t, angle, "k-", lw=1)
    ax[0].set_ylabel("swing angle (deg)")
    ax[0].set_title(f"{name}: payload swing, rope '{rope}', tracked frequencies")
    ax[1].plot(tt, tension / 1e3, "b-", lw=1, label="tension")
    if design:
        ax[1].axhline(design["static_tension_N"] / 1e3, color="gray", ls="--",
                      label=f"static (t = 0) {design['static_tension_N'] / 1e3:.2f} kN")
        ax[1].plot([design["peak_tension_time_s"]], [design["peak_tension_N"] / 1e3], "rv",
                   label=f"peak {design['peak_tension_N'] / 1e3:.2f} kN, dynamic factor {design['dynamic_factor']:.3f}")
    ax[1].set_ylabel("rope tension (kN)")
    ax[1].legend(loc="best", fontsize=8)
    if len(tr_t):
        for k in range(modes.shape[1]):
            keep = modes[:, k] <= max_hz
            ax[2].plot(tr_t[keep], modes[keep, k], ".", ms=2, color="0.7", label="modes of each analysis" if k == 0 else None)
        if followed is None or followed.shape[1] < 2:
            ax[2].plot(tr_t, tracked, "b-", lw=1.2, label="tracked (MAC)")
        else:
            for j in range(followed.shape[1]):
                ax[2].plot(tr_t, followed[:, j], "-", lw=1.2, color="C%d" % j,
                           label="followed mode %d (MAC): %.3g -> %.3g Hz" % (j + 1, followed[0, j], followed[-1, j]))
    if len(zc_t):
        ax[2].plot(zc_t, zc_hz, "ro", ms=3, label="swing, zero crossings")
    ax[2].set_yscale("log")
    ax[2].set_ylabel("frequency (Hz)")
    ax[2].set_xlabel("time (s)")
    ax[2].legend(loc="best", fontsize=8)
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    plt.close(fig)
    return {"figure": out, "max_swing_deg": float(np.max(np.abs(angle))), "peak_tension_N": float(np.max(tension)),
            "static_tension_N": float(tension[0]), "design": design, "tracked_time": tr_t, "tracked_hz": tracked,
            "followed_hz": followed,
            "swing_time": zc_t, "swing_hz": zc_hz, "swing_crossings": swing_crossings(t, angle)}


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("run", help="results file (.h5)")
    p.add_argument("-o", "--out", help="PNG file (default: RUN stem + '_hoist.png')")
    p.add_argument("--rope", default="hoist", help="rope name (default hoist)")
    p.add_argument("--sheave", default="tip", help="sensor at the sheave (default tip)")
    p.add_argument("--hook", default="hook", help="sensor at the hook (default hook)")
    a = p.parse_args(argv)
    r = plot_hoist(a.run, a.out, a.rope, a.sheave, a.hook)
    d = r["design"]
    print(f"{r['figure']}: max swing {r['max_swing_deg']:.2f} deg, tension {r['static_tension_N']:.0f} N at t = 0, "
          f"peak {r['peak_tension_N']:.0f} N" + (f" (dynamic factor {d['dynamic_factor']:.4f})" if d else ""))
    return 0


if __name__ == "__main__":
    sys.exit(main())
