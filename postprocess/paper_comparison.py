#!/usr/bin/env python3
"""Runs every scene of Fujita & Sugiyama (2012) in inputs/, draws the paper's
Figs. 5-14 from the results and writes the side-by-side comparison
docs/paper-comparison.md (figures in docs/figures/).

  /usr/bin/python3 postprocess/paper_comparison.py [--out docs] [--build build] [--work DIR] [--jobs 2] [--no-run]

The runs (boomdyn -o WORK/<scene>.h5 -boom_overwrite -boom_quiet) go to
--work (default BUILD/paper_comparison), two at a time; --no-run reuses the
results files already there. Needs numpy, h5py, matplotlib (Debian's
/usr/bin/python3); PyYAML (python3-yaml) only for the analytic elevation
rate in Fig. 12, which is otherwise drawn from the simulated motion alone.
"""
import argparse
import concurrent.futures
import os
import subprocess
import sys
import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
import boomdyn_h5  # noqa: E402
import centerline  # noqa: E402
import plot_frequency  # noqa: E402
import plot_stick_slip  # noqa: E402
import snapshots  # noqa: E402
from signal_frequency import moving_average, zero_crossing_frequency  # noqa: E402

# Longest runs first, so that two workers finish about together.
SCENES = ["paper_extraction", "paper_stick_slip", "paper_extraction_20kN", "paper_elevation_35",
          "paper_elevation_70", "paper_extraction_5kN", "paper_extraction_single_calibration", "paper_rigid_booms"]
# The scenes of the figures; paper_extraction_single_calibration is the variant with the single-number
# calibration (rigid joints, inextensible rope, steel density), compared in its own section.
EXTRACTION_SCENES = ("paper_extraction", "paper_extraction_5kN", "paper_extraction_20kN", "paper_rigid_booms",
                     "paper_elevation_35", "paper_elevation_70")
DPI = 100
FIGSIZE = (8, 4.2)
TREND_WINDOW = 0.3  # s, moving average taken as the slow part of a deflection (3 periods at 10 Hz)
FRAME_LABEL = "tip deflection in boom 3's moving frame [mm]"
PAPER = {"f_retracted": 27.0, "f_extended": 10.2, "stick_slip": plot_stick_slip.PAPER_EVENTS}


# ----------------------------------------------------------------------------- running

def run_scenes(boomdyn, work, scenes=SCENES, jobs=2, log=print):
    """Runs the scenes with boomdyn, `jobs` at a time; returns {scene: (h5 path, wall seconds)}."""
    os.makedirs(work, exist_ok=True)

    def one(scene):
        out = os.path.join(work, scene + ".h5")
        cmd = [boomdyn, os.path.join(ROOT, "inputs", scene + ".yaml"), "-o", out, "-boom_overwrite", "-boom_quiet"]
        start = time.time()
        p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        wall = time.time() - start
        if p.returncode != 0:
            raise RuntimeError("%s failed (exit %d):\n%s" % (" ".join(cmd), p.returncode, p.stdout[-3000:]))
        log("ran %-22s %5.1f s" % (scene, wall))
        return scene, out, wall

    results = {}
    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, jobs)) as pool:
        for scene, out, wall in pool.map(one, scenes):
            results[scene] = (out, wall)
    return results


# ----------------------------------------------------------------------------- reading

class Run:
    """The parts of one results file the figures need."""

    def __init__(self, path):
        self.path = path
        with boomdyn_h5.open_run(path) as f:
            self.scene = boomdyn_h5.scene_name(f)
            self.version = str(boomdyn_h5.attributes(f).get("boomdyn_version", "?"))
            self.summary = boomdyn_h5.load_summary(f)
            self.layout = boomdyn_h5.load_layout(f)
            self.lengths = boomdyn_h5.body_lengths(f)
            self.scene_dict = boomdyn_h5.load_scene(f)
            self.t = f["steps/time"][()]
            self.tip = f["sensors/tip/position"][()] if "sensors/tip/position" in f else None
            self.frame = f["steps/frame_deflection"][:, 0] if "steps/frame_deflection" in f else None
            self.joints = list(f["layout/sliding_joint_names"].asstr()[()]) if "layout/sliding_joint_names" in f else []
            self.slack = f["steps/slack"][()] if "steps/slack" in f else None
            states = boomdyn_h5.load_states(f)
            self.state_t, self.q = states["time"], states["q"]
            self.tracking = ({k: f["tracking/" + k][()] for k in ("time", "tracked_hz", "mac", "damping_ratio")
                              if "tracking/" + k in f}
                             if "tracking" in f else None)
            self.friction = (list(f["layout/friction_joint_names"].asstr()[()])
                             if "layout/friction_joint_names" in f else [])
            self.events = ({k: f["events/" + k][()] for k in ("time", "joint", "to_slip", "direction")}
                           if "events" in f else None)
            # Per-type outputs (/steps/outputs: rope tensions, pad forces) and type events (slack/taut, lift-off).
            names = list(f["layout/output_names"].asstr()[()]) if "layout/output_names" in f else []
            self.outputs = ({n: f["steps/outputs"][:, i] for i, n in enumerate(names)}
                            if names and "steps/outputs" in f else {})
            self.type_events = []
            if "type_events" in f and "layout/type_event_components" in f:
                comps = list(f["layout/type_event_components"].asstr()[()])
                kinds = list(f["layout/type_event_kinds"].asstr()[()])
                self.type_events = [(float(t), comps[c], kinds[k]) for t, c, k in
                                    zip(f["type_events/time"][()], f["type_events/component"][()],
                                        f["type_events/kind"][()])]

    def body(self, name):
        b = self.layout.body(name)
        return b.first, b.count, self.lengths[name]

    def slack_of(self, joint):
        return self.slack[:, self.joints.index(joint)]

    def step_index(self, t):
        return int(np.argmin(np.abs(self.t - t)))

    def state_index(self, t):
        return int(np.argmin(np.abs(self.state_t - t)))

    def constraint(self, **match):
        """The scene's first constraint whose keys match (None without PyYAML)."""
        if self.scene_dict is None:
            return None
        return next((c for c in self.scene_dict.get("constraints", [])
                     if all(c.get(k) == v for k, v in match.items())), None)

    def extraction_interval(self):
        """(t0, t1) of the extraction drive: from the scene, else the paper scenes' 2 s and 7 s."""
        c = self.constraint(type="extraction_drive")
        d = c.get("displacement") if c else None
        if isinstance(d, dict) and d.get("type") == "accel_limited":
            # arrives at t0 + distance/speed + speed/accel (+ accel/jerk), docs/scenes.md
            t0, speed, accel = float(d.get("t0", 0)), float(d["speed"]), float(d["accel"])
            dist = abs(float(d["to"]) - float(d.get("from", 0)))
            return t0, t0 + dist / speed + speed / accel + (accel / float(d["jerk"]) if "jerk" in d else 0.0)
        if isinstance(d, dict) and "t0" in d and "t1" in d:
            return float(d["t0"]), float(d["t1"])
        return 2.0, 7.0

    def cruise_interval(self):
        """(start, end) of the drive's constant-speed phase: the extraction interval less the acceleration and
        deceleration of an accel_limited move (the vibration windows during the extraction lie inside it, since a
        quadratic detrend across the start or stop of the drive counts the change of the deflection's trend as
        vibration)."""
        t0, t1 = self.extraction_interval()
        c = self.constraint(type="extraction_drive")
        d = c.get("displacement") if c else None
        if isinstance(d, dict) and d.get("type") == "accel_limited":
            ramp = float(d["speed"]) / float(d["accel"]) + (float(d["accel"]) / float(d["jerk"]) if "jerk" in d else 0)
            return t0 + ramp, t1 - ramp
        return t0, t1

    def elevation(self):
        """(state times, elevation angle in rad) of the first body's axis at s = 0 (slope of its node 0)."""
        first = self.layout.bodies[0].first
        return self.state_t, np.arctan2(self.q[:, first + 3], self.q[:, first + 2])


# ----------------------------------------------------------------------------- numbers

def window(t, a, b):
    return (t >= a - 1e-9) & (t <= b + 1e-9)


def window_mean(t, y, a, b):
    m = window(t, a, b)
    return float(np.mean(y[m])) if m.sum() > 0 else float("nan")


def amplitude(t, y, a, b):
    """Vibration amplitude in [a, b]: half the peak-to-peak of y minus its quadratic fit over the window."""
    m = window(t, a, b)
    if m.sum() < 10:
        return float("nan")
    tt = t[m] - t[m].mean()
    r = y[m] - np.polyval(np.polyfit(tt, y[m], 2), tt)
    return 0.5 * float(np.ptp(r))


def dominant_frequency(t, y, a, b, fmin=0.0, fmax=np.inf):
    """Frequency [Hz] of the largest spectral peak of y over [a, b] (quadratic trend removed, Hann window)
    between fmin and fmax; nan when the window is too short."""
    m = window(t, a, b)
    if m.sum() < 16:
        return float("nan")
    tt = t[m] - t[m].mean()
    r = (y[m] - np.polyval(np.polyfit(tt, y[m], 2), tt)) * np.hanning(m.sum())
    f = np.fft.rfftfreq(m.sum(), np.median(np.diff(t[m])))
    spectrum = np.abs(np.fft.rfft(r))
    band = (f >= fmin) & (f <= fmax)
    return float(f[band][np.argmax(spectrum[band])]) if band.any() else float("nan")


def time_function_rate(spec, t):
    """d/dt of a scene time function (docs/scenes.md) at times t, in the function's unit per second."""
    t = np.asarray(t, dtype=float)
    if spec is None or isinstance(spec, (int, float)) or spec.get("type") == "constant":
        return np.zeros_like(t)
    kind = spec["type"]
    if kind in ("ramp", "smooth_step"):
        t0, t1, a, b = (float(spec[k]) for k in ("t0", "t1", "from", "to"))
        s = np.clip((t - t0) / (t1 - t0), 0.0, 1.0)
        inside = (t > t0) & (t < t1)
        shape = np.ones_like(s) if kind == "ramp" else 30 * s**2 - 60 * s**3 + 30 * s**4
        return np.where(inside, (b - a) / (t1 - t0) * shape, 0.0)
    if kind == "sine":
        amp, freq = float(spec["amplitude"]), float(spec["frequency"])
        phase, t0 = np.radians(float(spec.get("phase", 0))), float(spec.get("t0", 0))
        w = 2 * np.pi * freq
        return np.where(t >= t0, amp * w * np.cos(w * (t - t0) + phase), 0.0)
    if kind == "table":
        tk, vk = np.asarray(spec["t"], float), np.asarray(spec["values"], float)
        slopes = np.diff(vk) / np.diff(tk)
        k = np.searchsorted(tk, t, side="right") - 1
        inside = (k >= 0) & (k < len(slopes))
        return np.where(inside, slopes[np.clip(k, 0, len(slopes) - 1)], 0.0)
    raise ValueError("unknown time function type %r" % kind)


def frequency_numbers(run):
    tr = run.tracking
    tt, fr = tr["time"], tr["tracked_hz"]
    t0, t1 = run.extraction_interval()
    tc, fc = zero_crossing_frequency(run.t, run.tip[:, 1], 3.0 / fr.min())
    at = lambda x: float(np.interp(x, tt, fr))  # noqa: E731
    start = (tc > 0.3) & (tc < t0 - 0.1)
    end = (tc > t1 - 0.6) & (tc < t1 - 0.2)
    med = lambda m, x: float(np.median(x[m])) if m.any() else float("nan")  # noqa: E731
    return {"f0": at(0.0), "f_t0": at(t0), "f_end": at(tt[-1]), "t_end": float(tt[-1]),
            "zc_start": med(start, fc), "zc_end": med(end, fc),
            "tr_start": med(start, np.interp(tc, tt, fr)), "tr_end": med(end, np.interp(tc, tt, fr)),
            "window_end": (t1 - 0.6, t1 - 0.2),
            "mac_min": float(tr["mac"][1:].min()) if len(tr["mac"]) > 1 else 1.0,
            # Damped models: damping ratio of the tracked mode (damped eigen-analysis) at the start and the end.
            "zeta0": float(tr["damping_ratio"][0]) if "damping_ratio" in tr else float("nan"),
            "zeta_end": float(tr["damping_ratio"][-1]) if "damping_ratio" in tr else float("nan")}


def deflection_numbers(run):
    """Moving-frame tip deflection (m): means and vibration amplitudes before and at the end of the extraction."""
    t, d = run.t, run.frame
    t0, t1 = run.extraction_interval()
    c0, c1 = run.cruise_interval()
    t_end = float(t[-1])
    return {"rest_mean": window_mean(t, d, t0 - 0.5, t0), "end_mean": window_mean(t, d, t_end - 0.1, t_end),
            "final": float(d[-1]), "amp_early": amplitude(t, d, 0.2, 0.7), "amp_rest": amplitude(t, d, t0 - 0.5, t0),
            "amp_end": amplitude(t, d, c1 - 0.5, c1), "t_end": t_end, "cruise": (c0, c1),
            # Largest spectral peaks at rest (1 s window) and over the last 0.5 s; above 50 Hz at rest.
            "f_rest": dominant_frequency(t, d, t0 - 1.0, t0), "f_rest_high": dominant_frequency(t, d, t0 - 1.0, t0, 50.0),
            "f_end": dominant_frequency(t, d, c1 - 0.5, c1),
            # During the extraction: right after its start (the drive's velocity jump) and the largest
            # amplitude over 0.5 s windows (growth factors against the last 0.5 s at rest).
            "amp_start_ext": amplitude(t, d, c0, c0 + 0.5), "amp_max_ext": max_window_amplitude(t, d, c0, c1)}


def max_window_amplitude(t, y, a, b, width=0.5):
    """Largest vibration amplitude over consecutive windows of `width` s in [a, b]."""
    edges = np.arange(a, b - 0.5 * width, width)
    return max(amplitude(t, y, e, e + width) for e in edges) if len(edges) else float("nan")


def stick_slip_numbers(run):
    j = run.friction.index("j2") if "j2" in run.friction else 0
    ev = run.events
    rows = [(float(t), bool(s), int(d)) for t, jj, s, d in zip(ev["time"], ev["joint"], ev["to_slip"], ev["direction"])
            if jj == j] if ev is not None else []
    s = run.slack_of(run.friction[j])
    late = [e for e in rows if e[0] > 3.0]  # after the start-up transient
    out_slide = next((e for e in late if e[1] and e[2] < 0), None)
    stop = next((e for e in late if not e[1] and out_slide and e[0] > out_slide[0]), None)
    in_slide = next((e for e in late if e[1] and e[2] > 0 and stop and e[0] > stop[0]), None)
    startup = [e for e in rows if e[0] <= 3.0]
    i0 = run.step_index(out_slide[0]) if out_slide else 0
    moved = np.nonzero(s[i0:] > s[i0] + 5e-3)[0]
    plateau = np.nonzero(s >= s.max() - 1e-3)[0]
    return {"joint": run.friction[j], "events": rows, "startup": startup,
            "out": out_slide[0] if out_slide else float("nan"), "stop": stop[0] if stop else float("nan"),
            "in": in_slide[0] if in_slide else float("nan"),
            "visible_start": float(run.t[i0 + moved[0]]) if len(moved) else float("nan"),
            "visible_end": float(run.t[plateau[0]]) if len(plateau) else float("nan"),
            "s_rest": float(s[i0]), "s_max": float(s.max()), "s_final": float(s[-1])}


def parts_numbers(run):
    """Rope tensions, pad forces and their events (issue 15): {"ropes": {name: {...}}, "pads": {joint: {...}}}."""
    t0, _ = run.extraction_interval()
    rest, moving = run.t <= t0, run.t > t0
    span = lambda v, m: (float(v[m].min()), float(v[m].max())) if m.any() else (float("nan"),) * 2  # noqa: E731
    ropes, pads = {}, {}
    for name, v in run.outputs.items():
        parts = name.split("/")
        if parts[0] == "elastic_rope" and parts[-1] == "tension":
            ev = [e for e in run.type_events if e[1] == parts[1] and e[2] in ("slack", "taut")]
            ropes[parts[1]] = {"rest": span(v, rest), "moving": span(v, moving),
                               "slack_steps": int(np.sum(v <= 0.0)), "events": len(ev),
                               "first": ev[0] if ev else None}
        if parts[0] == "pad" and parts[-1] == "force":
            ev = [e for e in run.type_events if e[1] == parts[1] and e[2] == "lift_off"]
            pads[parts[1]] = {"rest": span(v, rest), "moving": span(v, moving),
                              "lift_offs": len(ev), "last_lift_off": ev[-1][0] if ev else float("nan")}
    return {"ropes": ropes, "pads": pads}


def frame_geometry(run, t=None):
    """Boom 3's moving frame at the state nearest t (default: the last): origin (boom 3's rear end), the j3
    contact point, the unit axis, the tip, the deflection (computed here and as written by boomdyn)."""
    i = len(run.state_t) - 1 if t is None else run.state_index(t)
    k = run.step_index(run.state_t[i])
    q = run.q[i]
    first, count, length = run.body("boom3")
    s3 = float(run.slack_of("j3")[k])
    origin = centerline.position(q, first, count, length, 0.0)
    contact = centerline.position(q, first, count, length, s3)
    tip = centerline.position(q, first, count, length, length)
    ex = (contact - origin) / np.linalg.norm(contact - origin)
    n = np.array([-ex[1], ex[0]])
    delta = centerline.moving_frame_deflection(q, first, count, length, s3, length)
    return {"index": i, "time": float(run.state_t[i]), "s3": s3, "origin": origin, "contact": contact, "tip": tip,
            "ex": ex, "n": n, "delta": delta, "written": float(run.frame[k]) if run.frame is not None else None}


# ----------------------------------------------------------------------------- figures

def _finish(fig, out):
    fig.tight_layout()
    fig.savefig(out, dpi=DPI)
    plt.close(fig)
    return out


def _extraction_span(ax, run, label=True):
    t0, t1 = run.extraction_interval()
    if run.t[-1] > t0:
        ax.axvspan(t0, min(t1, run.t[-1]), color="0.85", alpha=0.5, lw=0,
                   label="boom extraction (0.25 m/s per stage)" if label else None)


def fig05(run, out):
    fig = plot_stick_slip.make_figure(run.path, paper=True)
    fig.savefig(out, dpi=DPI)
    plt.close(fig)
    return out


def fig06(run, out):
    fig, ax = plt.subplots(figsize=FIGSIZE)
    _extraction_span(ax, run)
    ax.plot(run.t, run.tip[:, 1], lw=0.8, label="tip of boom 3, global y")
    ax.set_xlabel("time [s]")
    ax.set_ylabel("tip vertical position (global) [m]")
    ax.set_title("%s: vertical position of the tip (paper Fig. 6)" % run.scene)
    ax.grid(True, alpha=0.4)
    ax.legend(fontsize=8, loc="lower left")
    return _finish(fig, out)


def fig07(run, out):
    fig, _, _ = plot_frequency.make_figure(run.path, paper=True)
    fig.axes[0].set_title("%s: first bending frequency along the run (paper Fig. 7)" % run.scene)
    return _finish(fig, out)


def fig08(run, out):
    fig, ax = plt.subplots(figsize=FIGSIZE)
    _extraction_span(ax, run)
    ax.plot(run.t, 1e3 * run.frame, lw=0.8, label="deflection (/steps/frame_deflection)")
    ax.plot(run.t, 1e3 * moving_average(run.t, run.frame, TREND_WINDOW), "k--", lw=1,
            label="moving average over %.1f s" % TREND_WINDOW)
    ax.set_xlabel("time [s]")
    ax.set_ylabel(FRAME_LABEL)
    ax.set_title("%s: tip deflection in boom 3's moving frame (paper Fig. 8)" % run.scene)
    ax.grid(True, alpha=0.4)
    ax.legend(fontsize=8, loc="lower left")
    return _finish(fig, out)


def fig09(run, out, t=None):
    """Sketch of the moving frame: booms at one instant (vertical scale exaggerated), axis, deflection."""
    g = frame_geometry(run, t)
    q = run.q[g["index"]]
    mm = 1e3
    fig, ax = plt.subplots(figsize=(8, 4.6))
    widths = snapshots.line_widths(len(run.layout.bodies))
    for b, w in zip(run.layout.bodies, widths):
        p = centerline.polyline(q, b.first, b.count, run.lengths[b.name])
        ax.plot(p[:, 0], mm * p[:, 1], "-", lw=w, solid_capstyle="butt", label=b.name)
    o, c, tip, ex, n = g["origin"], g["contact"], g["tip"], g["ex"], g["n"]
    foot = o + np.dot(tip - o, ex) * ex
    axis_end = foot + 0.3 * ex
    ax.plot([o[0] - 0.3 * ex[0], axis_end[0]], [mm * (o[1] - 0.3 * ex[1]), mm * axis_end[1]], "k-.", lw=1,
            label="moving frame axis x3 (through origin and j3)")
    ax.annotate("", xy=(axis_end[0], mm * axis_end[1]), xytext=(foot[0], mm * foot[1]),
                arrowprops=dict(arrowstyle="->", color="k"))
    ax.text(axis_end[0], mm * axis_end[1], "  x3", va="center", fontsize=9)
    span = np.ptp(ax.get_ylim())
    y3_tip = o + n * 0.25 * span / mm
    ax.annotate("", xy=(y3_tip[0], mm * y3_tip[1]), xytext=(o[0], mm * o[1]),
                arrowprops=dict(arrowstyle="->", color="k"))
    ax.text(y3_tip[0], mm * y3_tip[1], " y3", va="bottom", fontsize=9)
    ax.plot([o[0]], [mm * o[1]], "ko", ms=6)
    ax.annotate("origin: boom 3 rear end (pad j4)", (o[0], mm * o[1]), xytext=(-12, 4),
                textcoords="offset points", fontsize=8, ha="right")
    ax.plot([c[0]], [mm * c[1]], "rs", ms=6)
    ax.annotate("j3: boom 2's front pad on boom 3\n(s = %.3f m on boom 3)" % g["s3"], (c[0], mm * c[1]),
                xytext=(-10, -8), textcoords="offset points", fontsize=8, color="r", ha="right", va="top")
    ax.annotate("", xy=(tip[0], mm * tip[1]), xytext=(foot[0], mm * foot[1]),
                arrowprops=dict(arrowstyle="<->", color="m", lw=1.5))
    ax.text(tip[0] - 0.05, mm * 0.5 * (tip[1] + foot[1]), "δ = %.2f mm" % (mm * g["delta"]), color="m", fontsize=9,
            va="center", ha="right")
    ax.set_xlim(min(-0.3, o[0] - 0.5), max(axis_end[0], tip[0]) + 0.7)
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [mm] (vertical scale exaggerated)")
    ax.set_title("%s: boom 3's moving frame at t = %.2f s (paper Fig. 9)" % (run.scene, g["time"]))
    ax.grid(True, alpha=0.4)
    ax.legend(fontsize=8, loc="lower left")
    return _finish(fig, out)


def fig10(runs, out):
    """runs: [(tip load in kN, Run)], ascending."""
    fig, (ax, ax2) = plt.subplots(2, 1, figsize=(8, 6.4), sharex=True)
    _extraction_span(ax, runs[0][1])
    _extraction_span(ax2, runs[0][1], label=False)
    for kn, run in runs:
        line, = ax.plot(run.t, 1e3 * run.frame, lw=0.8, label="F = %g kN (%s)" % (kn, run.scene))
        ax2.plot(run.t, 1e3 * moving_average(run.t, run.frame, TREND_WINDOW) / kn, color=line.get_color(),
                 label="F = %g kN" % kn)
    ax.set_ylabel(FRAME_LABEL.replace(" [mm]", "\n[mm]"))
    ax.set_title("Effect of the tip load (paper Fig. 10): %s" % ", ".join(r.scene for _, r in runs), fontsize=10)
    ax2.set_ylabel("moving average (%.1f s)\nper kN of tip load [mm/kN]" % TREND_WINDOW)
    ax2.set_xlabel("time [s]")
    for a in (ax, ax2):
        a.grid(True, alpha=0.4)
        a.legend(fontsize=8, loc="lower left")
    return _finish(fig, out)


def fig11(flexible, rigid, out):
    fig, (ax, ax2) = plt.subplots(2, 1, figsize=(8, 6.4), sharex=True)
    _extraction_span(ax, rigid)
    _extraction_span(ax2, rigid, label=False)
    for run, label in ((flexible, "all booms flexible (%s)" % flexible.scene),
                       (rigid, "booms 1-2 rigid (%s)" % rigid.scene)):
        ax.plot(run.t, 1e3 * run.frame, lw=0.8, label=label)
        ax2.plot(run.t, 1e3 * (run.frame - moving_average(run.t, run.frame, TREND_WINDOW)), lw=0.6, label=label)
    ax.set_ylabel(FRAME_LABEL.replace(" [mm]", "\n[mm]"))
    ax.set_title("Booms 1 and 2 rigid vs flexible (paper Fig. 11): %s, %s" % (rigid.scene, flexible.scene),
                 fontsize=10)
    ax2.set_ylabel("vibration: deflection minus its\n%.1f s moving average [mm]" % TREND_WINDOW)
    ax2.set_xlabel("time [s]")
    for a in (ax, ax2):
        a.grid(True, alpha=0.4)
        a.legend(fontsize=8, loc="lower left")
    return _finish(fig, out)


def elevation_rates(run):
    """(state times, numerical rate [rad/s] from the base node's slope, analytic rate [rad/s] or None)."""
    te, th = run.elevation()
    numeric = np.gradient(np.unwrap(th), te)
    c = run.constraint(type="clamp")
    analytic = None
    if c is not None:
        analytic = np.radians(time_function_rate(c.get("angle", 0), te))
    return te, numeric, analytic, th


def fig12(runs, out):
    """runs: [(target angle in degrees, Run)]."""
    fig, (ax, ax2) = plt.subplots(2, 1, figsize=(8, 6.4), sharex=True)
    for deg, run in runs:
        te, numeric, analytic, th = elevation_rates(run)
        line, = ax.plot(te, numeric, lw=1.5, label="θ = 0 → %g° (%s): d/dt of the base node's slope angle"
                        % (deg, run.scene))
        if analytic is not None:
            ax.plot(te, analytic, "k:", lw=1.2, label="scene's angle profile, differentiated" if deg == runs[0][0]
                    else None)
        ax2.plot(te, np.degrees(th), color=line.get_color(), label="θ = 0 → %g°" % deg)
    ax.set_ylim(top=1.35 * ax.get_ylim()[1])  # room for the legend
    ax.set_ylabel("angular velocity of the\nelevation angle [rad/s]")
    ax.set_title("Elevation of boom 1 (paper Fig. 12): %s" % ", ".join(r.scene for _, r in runs), fontsize=10)
    ax2.set_ylabel("elevation angle θ [deg]")
    ax2.set_xlabel("time [s]")
    for a in (ax, ax2):
        a.grid(True, alpha=0.4)
        a.legend(fontsize=7, loc="upper left")
    return _finish(fig, out)


def fig13(runs, out):
    """runs: [(final elevation in degrees, Run)]."""
    fig, ax = plt.subplots(figsize=FIGSIZE)
    _extraction_span(ax, runs[0][1])
    for deg, run in runs:
        ax.plot(run.t, 1e3 * run.frame, lw=0.8, label="θ = %g° (%s)" % (deg, run.scene))
    ax.set_xlabel("time [s]")
    ax.set_ylabel(FRAME_LABEL)
    ax.set_title("Effect of the elevation angle (paper Fig. 13): %s" % ", ".join(r.scene for _, r in runs),
                 fontsize=10)
    ax.grid(True, alpha=0.4)
    ax.legend(fontsize=8, loc="lower left")
    return _finish(fig, out)


FIG14_TIMES = [0, 2, 3, 4, 5, 6, 7]


def fig14(run, out, times=FIG14_TIMES):
    times = [t for t in times if t <= run.state_t[-1] + 1e-9] or [run.state_t[-1]]
    return snapshots.plot_snapshots(snapshots.Shapes(run.path), out, times, dpi=DPI,
                                    title="%s: motion of the boom, true scale (paper Fig. 14)" % run.scene)


# ----------------------------------------------------------------------------- the report

def mm(x):
    """Millimetres: two decimals, or two significant digits below 0.1 mm (the damped vibrations)."""
    if not np.isfinite(x):
        return "n/a"
    return "%.2f mm" % (1e3 * x) if abs(1e3 * x) >= 0.1 else "%.2g mm" % (1e3 * x)


def growth(amp, d):
    """Growth factor of a vibration amplitude against the last 0.5 s at rest of deflection numbers d; "—" when
    nothing was left at rest (below 1e-6 of the amplitude over 0.2-0.7 s: the ratio would be round-off)."""
    return "%.2f" % ratio(amp, d["amp_rest"]) if d["amp_rest"] > 1e-6 * d["amp_early"] else "— (0 at rest)"


def f3(x):
    return "%.3f" % x if np.isfinite(x) else "n/a"


def ratio(a, b):
    return a / b if b != 0 and np.isfinite(a) and np.isfinite(b) else float("nan")


def collect(runs):
    """Every number the report quotes, from the results files."""
    base = runs["paper_extraction"]
    n = {"freq": frequency_numbers(base), "stick": stick_slip_numbers(runs["paper_stick_slip"])}
    for key in EXTRACTION_SCENES:
        n[key] = deflection_numbers(runs[key])
        n[key]["parts"] = parts_numbers(runs[key])
    single = runs["paper_extraction_single_calibration"]
    n["single"] = deflection_numbers(single)
    n["single"]["freq"] = frequency_numbers(single)
    ts, ys = single.t, single.tip[:, 1]
    n["single"]["tip_end_mean"] = window_mean(ts, ys, ts[-1] - 0.1, ts[-1])
    t0, t1 = base.extraction_interval()
    c0, c1 = base.cruise_interval()
    y = base.tip[:, 1]
    n["tip"] = {"rest_mean": window_mean(base.t, y, t0 - 0.5, t0), "end_mean": window_mean(base.t, y, t1 - 0.1, t1),
                "final": float(y[-1]), "min": float(y.min()), "t_min": float(base.t[np.argmin(y)]),
                "amp_early": amplitude(base.t, y, 0.2, 0.7), "amp_rest": amplitude(base.t, y, t0 - 0.5, t0),
                "amp_end": amplitude(base.t, y, c1 - 0.5, c1), "amp_start_ext": amplitude(base.t, y, c0, c0 + 0.5),
                "amp_max_ext": max_window_amplitude(base.t, y, c0, c1)}
    n["frame9"] = frame_geometry(base)
    loads = np.array([5.0, 10.0, 20.0])
    ends = np.array([n[k]["end_mean"] for k in ("paper_extraction_5kN", "paper_extraction", "paper_extraction_20kN")])
    slope, intercept = np.polyfit(loads, ends, 1)
    n["load_fit"] = {"slope": slope, "intercept": intercept,
                     "residual": float(np.max(np.abs(np.polyval([slope, intercept], loads) - ends)))}
    for key in ("paper_elevation_35", "paper_elevation_70"):
        te, numeric, analytic, th = elevation_rates(runs[key])
        n[key]["rate_peak"] = float(numeric.max())
        n[key]["rate_t_peak"] = float(te[np.argmax(numeric)])
        n[key]["rate_analytic_peak"] = float(analytic.max()) if analytic is not None else float("nan")
        n[key]["rate_diff"] = float(np.max(np.abs(numeric - analytic))) if analytic is not None else float("nan")
        n[key]["theta_end"] = float(np.degrees(th[-1]))
        moving = np.nonzero(np.abs(numeric) > 1e-3)[0]
        n[key]["rate_span"] = (float(te[moving[0]]), float(te[moving[-1]])) if len(moving) else (np.nan, np.nan)
    r70 = runs["paper_elevation_70"]
    n["fig14"] = [(float(r70.state_t[i]), r70.tip[r70.step_index(r70.state_t[i])])
                  for i in sorted(set(r70.state_index(t) for t in FIG14_TIMES))]
    return n


def write_report(path, runs, figures, n):
    """docs/paper-comparison.md: one section per figure, paper and boomdyn side by side."""
    fig_dir = os.path.relpath(os.path.dirname(figures["fig05"]), os.path.dirname(os.path.abspath(path)))
    link = lambda key, alt: "![%s](%s/%s)" % (alt, fig_dir, os.path.basename(figures[key]))  # noqa: E731
    fr, ss, tip = n["freq"], n["stick"], n["tip"]
    base, d5, d20 = n["paper_extraction"], n["paper_extraction_5kN"], n["paper_extraction_20kN"]
    rig, e35, e70 = n["paper_rigid_booms"], n["paper_elevation_35"], n["paper_elevation_70"]
    g9 = n["frame9"]
    fit = n["load_fit"]
    version = runs["paper_extraction"].version
    L = []
    add = L.append
    add("# boomdyn against Fujita & Sugiyama (2012), Figs. 5-14\n")
    add("Generated by `postprocess/paper_comparison.py` (do not edit by hand; rerun it):\n")
    add("    /usr/bin/python3 postprocess/paper_comparison.py [--out docs] [--build build]\n")
    add("It runs the eight paper scenes of `inputs/` (docs/paper-scenes.md) with `%s`, draws every figure from "
        "the HDF5 results and computes every number below from them. The paper's numbers are quoted from its "
        "text (H. Fujita, H. Sugiyama, Theor. Appl. Mech. Lett. 2, 063005 (2012); docs/model.md §6); where the "
        "paper gives only a plot, the value read off the plot (as in docs/paper-scenes.md and docs/model.md §6) is "
        "marked \"approx.\".\n" % version)
    add("| scene | input | status | steps | max constraint violation | rope slack events (elastic ropes) or "
        "slack-rope steps (inextensible rope) | pad lift-offs |")
    add("|---|---|---|---:|---:|---:|---:|")
    for key in SCENES:
        s, r = runs[key].summary, runs[key]
        elastic = any(k.startswith("elastic_rope/") for k in r.outputs)
        slack = (str(sum(1 for e in r.type_events if e[2] == "slack")) if elastic
                 else "%s steps" % s.get("slack_rope_steps", "-") if r.constraint(type="rope") else "-")
        pads = any(k.startswith("pad/") for k in r.outputs)
        add("| %s | `inputs/%s.yaml` | %s | %d | %.1e | %s | %s |" % (
            r.scene, key, s.get("status", "?"), int(s.get("steps", 0)),
            float(s.get("max_constraint_violation", float("nan"))), slack,
            sum(1 for e in r.type_events if e[2] == "lift_off") if pads else "-"))
    add("")
    add("All scenes: 16 ANCF elements per flexible boom, h = 1 ms, generalized-α with ρ∞ = 0.8 (wall times: "
        "docs/paper-scenes.md; the whole script takes about a minute on two idle cores).\n")
    add("## What differs from the paper in every scene\n")
    add("- **Structural damping of a chosen size.** The paper's residual vibration from the suddenly applied tip "
        "load dies out within about 2 s (Figs. 8, 11); its damping is not given. Every flexible boom has "
        "Kelvin–Voigt damping η = 1.04e-4 s on the axial and the bending strain rate (docs/model.md §1.1), chosen "
        "by the rule *first-mode amplitude below 5 %% of its start at 2 s*: exp(−ζ₁ω₁ · 2 s) = 0.05, "
        "ζ₁ω₁ = ln 20 / 2 = 1.50 s⁻¹, at 27.0 Hz ζ₁ = 0.88 %%, η = 2ζ₁/ω₁. The damped eigen-analysis along "
        "the run gives ζ₁ = %.3f %% at t = 0 and %.3f %% fully extended (ζ = ηω/2 falls with the frequency). "
        "`paper_stick_slip` has the same η, with an elevation profile refitted for the damped model (Fig. 5). The "
        "undamped results are kept as a variant at the end (\"Without structural damping\")."
        % (100 * fr["zeta0"], 100 * fr["zeta_end"]))
    add("- **Start from the undeformed state.** Every run starts undeformed and at rest, with gravity and the "
        "full tip load applied at t = 0 (a step load), not from static equilibrium.")
    add("- **The telescoping mechanism as real parts** (issue 15; docs/paper-scenes.md): the extraction scenes "
        "have slide pads at the four joints (k_pad = 5e8 N/m, no clearance, pad damping 2e4 N s/m) and an "
        "extension + retraction pair of elastic, tension-only wire ropes (EA = 1.2e7 N, pretension 1 kN, rope "
        "damping 500 N s/m each) instead of rigid joints and one inextensible rope. `paper_stick_slip` keeps "
        "rigid joints (booms 1-2 only, no rope).")
    add("- **Sections calibrated to two numbers.** The paper's section data (Marjamäki & Mäkinen 2003) are not "
        "available. Documented steel boxes are used, with every I scaled by c = 0.1877 and the density by "
        "m = 0.3262 (2561 kg/m³; E and A stay steel's), fitted with the pads and ropes in the model so that the "
        "retracted first frequency is the paper's 27.0 Hz **and** the fully extended tip position is Fig. 6's "
        "approx. −0.2 m (`postprocess/calibrate_paper.py --fit mass`). These two numbers are matched by "
        "construction; every other number below is a prediction. The single-number calibration used before "
        "is kept as a variant scene (section \"Single-number calibration (variant)\").")
    add("- **Load and scene details the paper leaves open**: the 10 kN is a dead vertical force at boom 3's tip "
        "(no payload mass); the extraction drive is an acceleration-limited move (1 m/s² up to 0.264 m/s per "
        "stage, 2 s to 7 s, 0.25 m/s on average) instead of a velocity jump, so that the ropes do not chatter "
        "slack and taut; the elevation profiles (Figs. 5, 12) and the LuGre σ0, σ1, v_s, α are chosen, "
        "documented values (docs/paper-scenes.md).\n")

    # Fig. 5
    add("## Fig. 5: stick-slip of boom 2 in boom 1\n")
    add(link("fig05", "Fig. 5 reproduced"))
    add("")
    add("Scene `paper_stick_slip` (booms 1-2, LuGre at both pads, μ_s = 0.15, μ_c = 0.1, Kelvin–Voigt damping "
        "η = 1.04e-4 s; elevation piecewise linear through (0 s, 0°), (6.2986 s, −10°), (14 s, 19.2368°); two-number sections). The "
        "paper: *\"boom 2 keeps the stick state until at t = 5.4 s ... boom 2 gets stick again at t = 8.3 s "
        "until boom 2 starts sliding into boom 1 again at t = 13.5 s\"*.\n")
    add("The elevation profile is refitted for the damped model (docs/paper-scenes.md, \"Stick-slip\"): "
        "**fitted** are the slide-out at 5.4 s (the time of the −10° minimum) and the slide-in at 13.5 s (the "
        "angle at 14 s); the start (horizontal, below the stick limit atan μ_s = 8.53°), the −10° minimum (the "
        "paper's plot) and the knots at 0 and 14 s are fixed choices. **Predictions** are the stick time and the "
        "slide.\n")
    add("| joint %s (boom 2's rear pad on boom 1) | paper | boomdyn |" % ss["joint"])
    add("|---|---:|---:|")
    add("| start-up slip (sudden gravity load at t = 0) | — | %s |" % (
        ", ".join("%.3f s %s" % (t, "stick→slip" if s else "slip→stick") for t, s, _ in ss["startup"]) or "none"))
    add("| stick → slip, sliding out | 5.4 s | %.3f s (fitted) |" % ss["out"])
    add("| s moved 5 mm past its value at that event | — | %.2f s |" % ss["visible_start"])
    add("| s within 1 mm of its maximum (visible end of the slide) | — | %.2f s |" % ss["visible_end"])
    add("| slip → stick | 8.3 s | **%.3f s (prediction)** |" % ss["stop"])
    add("| stick → slip, sliding in | 13.5 s | %.3f s (fitted) |" % ss["in"])
    add("| slide out (max s − s at the breakaway) | approx. 0.5 m | **%.3f m (prediction)** (s: %.4f → %.4f m, "
        "%.4f m at the end) |" % (ss["s_max"] - ss["s_rest"], ss["s_rest"], ss["s_max"], ss["s_final"]))
    add("")
    T = ss["stop"] - ss["out"]
    dmu = (0.15 - 0.1) * np.cos(np.radians(8.53))
    add("**Agrees:** the sequence stick → slide out → stick → slide in and its directions; boom 2 sticks from "
        "the start (no start-up slip: the damping removes the vibration that, undamped, made the pad forces "
        "swing through zero) and breaks away when the elevation passes −atan μ_s, as the quasi-static "
        "condition says. **Predicted:** it sticks again at %.2f s (paper 8.3 s, %+.2f s) after a slide of "
        "%.2f m (paper approx. 0.5 m). **Why the slide is longer than the paper's, with numbers:** a slide that "
        "starts at the static limit and stops T = %.2f s later covers, for a rigid block with Coulomb friction "
        "(μ_s, μ_c), at least g(μ_s − μ_c)cos θ T²/6 = %.2f m if the elevation rises linearly from the "
        "breakaway on, and g(μ_s − μ_c)cos θ T²/4 = %.2f m if it turns smoothly at the breakaway; the paper's "
        "0.5 m in 2.9 s would need the elevation to turn back up faster than linearly right at the breakaway "
        "(or a friction that stays near μ_s while sliding, i.e. a much larger Stribeck velocity than v_s = "
        "1 mm/s). The stick time hardly depends on the profile: 8.05-8.19 s over every profile tried "
        "(minimum −9.5° to −10° at 6.0-6.3 s, 14.8° to 20° at 14 s), so it cannot be fitted to 8.3 s with "
        "this friction law. The slide-in needs a steeper slope than the slide-out, because the overlap has "
        "shrunk from 1.5 m to %.2f m: below 1 m of overlap the two pad forces add up to (2/o − 1) times boom 2's "
        "weight component, and the static limit becomes tan θ = μ_s(2/o − 1) = %.3f (θ = %.1f°).\n" % (
            ss["stop"], ss["stop"] - 8.3, ss["s_max"] - ss["s_rest"], T, 9.81 * dmu * T**2 / 6,
            9.81 * dmu * T**2 / 4, 2.0 - ss["s_max"],
            0.15 * max(1.0, 2.0 / (2.0 - ss["s_max"]) - 1.0),
            np.degrees(np.arctan(0.15 * max(1.0, 2.0 / (2.0 - ss["s_max"]) - 1.0)))))

    # Fig. 6
    add("## Fig. 6: vertical position of the tip (global)\n")
    add(link("fig06", "Fig. 6 reproduced"))
    add("")
    add("Scene `paper_extraction` (boom 1 horizontal, 10 kN at the tip, 2 s at rest, extraction at 0.25 m/s "
        "per stage on average to 7 s). The paper: *\"the deflection increases as the booms are extended. Furthermore, the "
        "frequency of the tip vibration becomes lower as the booms are extended.\"*\n")
    add("| quantity | paper | boomdyn |")
    add("|---|---:|---:|")
    add("| tip y, mean over the last 0.5 s at rest (retracted) | — | %.4f m |" % tip["rest_mean"])
    add("| tip y, mean over the last 0.1 s (fully extended) | approx. −0.2 m (Fig. 6) | %.4f m |"
        % tip["end_mean"])
    add("| tip y at 7 s; lowest tip y | — | %.4f m; %.4f m at %.2f s |" % (tip["final"], tip["min"], tip["t_min"]))
    add("| vibration amplitude of tip y, last 0.5 s at rest / last 0.5 s at full speed | — | %s / %s |"
        % (mm(tip["amp_rest"]), mm(tip["amp_end"])))
    add("| frequency of the tip vibration (zero crossings), at rest / %.1f-%.1f s | falls | %.2f Hz / %.2f Hz |"
        % (fr["window_end"] + (fr["zc_start"], fr["zc_end"])))
    add("")
    c0, c1 = runs["paper_extraction"].cruise_interval()
    add("Vibration amplitude here and below: half the peak-to-peak of the signal minus its quadratic fit over "
        "the window. The windows during the extraction lie in the drive's constant-speed phase, %.3f-%.3f s "
        "(\"first 0.5 s\", \"largest over 0.5 s\" and \"last 0.5 s at full speed\"): across the drive's start and "
        "stop the deflection's trend changes faster than a parabola, and the fit would count that as vibration "
        "(0.10 mm over the run's last 0.5 s in boom 3's frame, against 0.003 mm in 0.25 s windows).\n"
        % (c0, c1))
    add("**Matched by construction:** the fully extended tip position is one of the two calibration numbers "
        "(the static position of the extended boom is −0.2000 m; the run ends at %.4f m, mean over the last "
        "0.1 s, %.0f mm from it). **Agrees (prediction):** the tip sinks as the boom extends, and the vibration "
        "slows down. With the structural damping the first-mode vibration started by the step load at t = 0 "
        "decays as in the paper: %s over 0.2-0.7 s, %s over the last 0.5 s at rest (%.1f %%). During the "
        "extraction the tip vibration is %s over its first 0.5 s, at most %s over any 0.5 s (growth factor %.2f "
        "against the last 0.5 s at rest) and %s over the last 0.5 s at full speed.\n"
        % (tip["end_mean"], 1e3 * abs(tip["end_mean"] + 0.2), mm(tip["amp_early"]), mm(tip["amp_rest"]),
           100 * ratio(tip["amp_rest"], tip["amp_early"]), mm(tip["amp_start_ext"]), mm(tip["amp_max_ext"]),
           ratio(tip["amp_max_ext"], tip["amp_rest"]), mm(tip["amp_end"])))

    # Fig. 7
    add("Rope tensions and pad forces along this run: section \"The ropes and the slide pads\" below; the "
        "calibration: docs/paper-scenes.md, \"Two-number calibration\".\n")
    add("## Fig. 7: change of frequency in time\n")
    add(link("fig07", "Fig. 7 reproduced"))
    add("")
    add("The paper: *\"The frequency at the initial configuration is 27.0 Hz, while the frequency decreases to "
        "10.2 Hz when the boom is fully extended at the final configuration.\"* boomdyn: the first bending mode "
        "of the constrained system linearized about the current state every 10 ms (SLEPc), followed by MAC "
        "(smallest MAC between successive analyses: %.5f); independently, the zero crossings of the tip's "
        "vertical vibration.\n" % fr["mac_min"])
    add("| quantity | paper | boomdyn (eigen-analysis) | boomdyn (zero crossings) |")
    add("|---|---:|---:|---:|")
    add("| retracted (t = 0) | %.1f Hz | %.3f Hz (calibrated in statics + modal) | |"
        % (PAPER["f_retracted"], fr["f0"]))
    add("| median over 0.3-%.1f s (at rest) | | %.3f Hz | %.2f Hz |"
        % (runs["paper_extraction"].extraction_interval()[0] - 0.1, fr["tr_start"], fr["zc_start"]))
    add("| start of the extraction (t = %.0f s) | 27.0 Hz | %.3f Hz | |"
        % (runs["paper_extraction"].extraction_interval()[0], fr["f_t0"]))
    add("| fully extended (t = %.0f s) | %.1f Hz | **%.3f Hz (prediction)** | |"
        % (fr["t_end"], PAPER["f_extended"], fr["f_end"]))
    add("| median over %.1f-%.1f s (the last zero crossings) | | %.2f Hz | %.2f Hz |"
        % (fr["window_end"] + (fr["tr_end"], fr["zc_end"])))
    add("| ratio retracted / extended | %.2f | %.2f | |" % (PAPER["f_retracted"] / PAPER["f_extended"],
                                                           fr["f0"] / fr["f_end"]))
    add("")
    add("**Agrees (prediction):** the extended frequency is predicted within %.1f %% (%.2f against 10.2 Hz) by "
        "the two-number calibration (27.0 Hz retracted and −0.2 m extended tip, both from static + modal "
        "analyses), and the independent zero-crossing estimate lies on the tracked curve. **Matched by "
        "construction:** 27.0 Hz at the start (the run's %.3f Hz differs from the calibration's 27.000 Hz "
        "because the run starts undeformed under the step load while the calibration is about the static "
        "equilibrium). The single-number calibration predicted %.3f Hz (section \"Single-number calibration "
        "(variant)\").\n" % (100 * abs(fr["f_end"] / 10.2 - 1), fr["f_end"], fr["f0"], n["single"]["freq"]["f_end"]))

    # Fig. 8
    add("## Fig. 8: tip deflection in boom 3's moving frame\n")
    add(link("fig08", "Fig. 8 reproduced"))
    add("")
    add("The paper: *\"the boom is deflected with small elastic vibration and the amplitude of the elastic "
        "vibration decreases with time within 2 s and then the amplitude of vibration starts increasing until "
        "the maximum length is reached.\"* Its Fig. 8 reaches approx. −0.02 to −0.03 m at 7 s.\n")
    add("| quantity | paper | boomdyn |")
    add("|---|---:|---:|")
    add("| mean deflection, last 0.5 s at rest | — | %s |" % mm(base["rest_mean"]))
    add("| mean deflection, last 0.1 s (fully extended) | approx. −0.02 to −0.03 m (Fig. 8) | %s (prediction) |"
        % mm(base["end_mean"]))
    add("| deflection at 7 s | — | %s |" % mm(base["final"]))
    add("| vibration amplitude 0.2-0.7 s / last 0.5 s at rest / last 0.5 s at full speed | decreases, then increases | "
        "%s / %s / %s |" % (mm(base["amp_early"]), mm(base["amp_rest"]), mm(base["amp_end"])))
    add("| vibration amplitude, first 0.5 s of the extraction / largest over 0.5 s of the extraction | — | "
        "%s / %s |" % (mm(base["amp_start_ext"]), mm(base["amp_max_ext"])))
    add("| growth factors: largest / last 0.5 s at rest; last 0.5 s at full speed / last 0.5 s at rest | grows | %.2f; %.2f |"
        % (ratio(base["amp_max_ext"], base["amp_rest"]), ratio(base["amp_end"], base["amp_rest"])))
    add("")
    regrows = ratio(base["amp_end"], base["amp_rest"]) > 1.5
    rate0, rate_end = 2 * np.pi * fr["f0"] * fr["zeta0"], 2 * np.pi * fr["f_end"] * fr["zeta_end"]
    add("**Agrees:** the deflection grows strongly during the extraction (the overhang of boom 3 beyond the "
        "j3 pad grows from 0.25 m to 1.5 m), and the vibration from the step load decays within 2 s: %s over "
        "0.2-0.7 s, %s over the last 0.5 s at rest (higher modes of the step start too: largest peak above 50 Hz "
        "at rest %.0f Hz). %s The magnitude, a prediction of the two-number calibration, is %s against the paper's "
        "approx. −20 to −30 mm (the single-number calibration gave %s).\n"
        % (mm(base["amp_early"]), mm(base["amp_rest"]), base["f_rest_high"],
           ("**Agrees:** the vibration grows again during the extraction, by a factor %.1f to %s over the last "
            "0.5 s at full speed." % (ratio(base["amp_end"], base["amp_rest"]), mm(base["amp_end"])) if regrows else
            "**Differs, and why:** the vibration does not grow again during the extraction as the paper's does: "
            "the drive's start at t = %.0f s excites %s over the first 0.5 s of the extraction, and the "
            "amplitude over the last 0.5 s at full speed is %s (dominant frequency %.0f Hz), a factor %.2f of the last 0.5 s "
            "at rest. With Kelvin–Voigt damping the first mode's decay rate ζω = ηω²/2 falls from %.2f s⁻¹ at "
            "%.1f Hz to %.2f s⁻¹ at %.1f Hz, so for the vibration to grow the sliding motion would have to feed "
            "the first mode faster than its energy decays (2ζω, at least %.2f s⁻¹ at full extension); in this "
            "model it does not. The paper's growth needs either a feeding that this model does not have (its "
            "sliding joints are frictionless pads on the centre lines, its drive a prescribed, smooth "
            "displacement) or "
            "a damping that falls faster with the frequency than ηω²/2 (e.g. a constant ζ)."
            % (runs["paper_extraction"].extraction_interval()[0], mm(base["amp_start_ext"]), mm(base["amp_end"]),
               base["f_end"], ratio(base["amp_end"], base["amp_rest"]), rate0, fr["f0"], rate_end, fr["f_end"],
               2 * rate_end)),
           mm(base["end_mean"]), mm(n["single"]["end_mean"])))

    # Fig. 9
    add("## Fig. 9: boom 3's moving frame\n")
    add(link("fig09", "Fig. 9 reproduced"))
    add("")
    add("The paper: the moving frame of boom 3 has its origin at boom 3's left (rear) end and its x-axis "
        "through the two joint definition points on boom 3 (the rear pad and the point where boom 2's front "
        "pad touches boom 3). The sketch is the `paper_extraction` run at t = %.2f s, vertical scale "
        "exaggerated. The deflection δ drawn (from `postprocess/centerline.py`, with the j3 contact coordinate "
        "s = %.4f m) is %.4f mm; boomdyn wrote %.4f mm for the same step (`/steps/frame_deflection`): "
        "difference %.1e mm. Same definition as the paper; nothing to compare numerically.\n"
        % (g9["time"], g9["s3"], 1e3 * g9["delta"], 1e3 * g9["written"], 1e3 * abs(g9["delta"] - g9["written"])))

    # Fig. 10
    add("## Fig. 10: effect of the tip load\n")
    add(link("fig10", "Fig. 10 reproduced"))
    add("")
    add("Scenes `paper_extraction_5kN`, `paper_extraction` (10 kN), `paper_extraction_20kN`. The paper: "
        "*\"The similar vibration behavior is observed even when the tip load is changed from 5 kN to 20 kN\"*; "
        "its Fig. 10 shows the moving-frame deflection growing with the load (axis to −0.05 m), i.e. roughly in "
        "proportion to it.\n")
    add("| tip load | mean deflection, last 0.1 s | deflection at 7 s | per kN (last 0.1 s) | vibration amplitude, last 0.5 s at rest / last 0.5 s at full speed |")
    add("|---:|---:|---:|---:|---:|")
    for kn, d in ((5, d5), (10, base), (20, d20)):
        add("| %d kN | %s | %s | %.3f mm/kN | %s / %s |" % (kn, mm(d["end_mean"]), mm(d["final"]),
                                                           1e3 * d["end_mean"] / kn, mm(d["amp_rest"]),
                                                           mm(d["amp_end"])))
    add("")
    add("Ratios of the mean deflection at full extension: 10 kN / 5 kN = %.3f, 20 kN / 10 kN = %.3f (2 for "
        "exact proportionality). A straight line through the three gives %.3f mm/kN and %.3f mm at zero load "
        "(the part from the booms' own weight), with a largest misfit of %.3f mm.\n"
        % (ratio(base["end_mean"], d5["end_mean"]), ratio(d20["end_mean"], base["end_mean"]),
           1e3 * fit["slope"], 1e3 * fit["intercept"], 1e3 * fit["residual"]))
    add("**Agrees:** the deflection is linear in the tip load (plus a small gravity part), and the vibration "
        "pattern is the same for the three loads (its amplitude scales with the load too, since the step load "
        "starts it, and the damping removes it alike). The magnitudes are predictions of the two-number "
        "calibration: the paper's Fig. 10 axis reaches −0.05 m at 20 kN; here %s.\n" % mm(d20["end_mean"]))

    # Fig. 11
    add("## Fig. 11: booms 1 and 2 rigid\n")
    add(link("fig11", "Fig. 11 reproduced"))
    add("")
    add("Scene `paper_rigid_booms` (booms 1-2 rigid, boom 3 flexible) against `paper_extraction`. The paper: "
        "*\"there is no vibration excited after the residual vibration is damped out at approximately 2 s ... "
        "the vibration coupling between the flexible booms resulting from the relative sliding motion can "
        "contribute to the increase in vibration of the telescopic boom.\"*\n")
    add("| | paper | all flexible | booms 1-2 rigid |")
    add("|---|---|---:|---:|")
    add("| mean deflection, last 0.1 s | — | %s | %s |" % (mm(base["end_mean"]), mm(rig["end_mean"])))
    add("| vibration amplitude, 0.2-0.7 s | — | %s | %s |" % (mm(base["amp_early"]), mm(rig["amp_early"])))
    add("| vibration amplitude, last 0.5 s at rest | rigid: damped out | %s | %s |"
        % (mm(base["amp_rest"]), mm(rig["amp_rest"])))
    add("| vibration amplitude, last 0.5 s at full speed | rigid: not re-excited | %s | %s |"
        % (mm(base["amp_end"]), mm(rig["amp_end"])))
    add("| largest amplitude over 0.5 s of the extraction | rigid: not re-excited | %s | %s |"
        % (mm(base["amp_max_ext"]), mm(rig["amp_max_ext"])))
    add("| growth: last 0.5 s at full speed / last 0.5 s at rest; largest / last 0.5 s at rest | flexible: grows; rigid: none "
        "| %s; %s | %s; %s |" % (growth(base["amp_end"], base), growth(base["amp_max_ext"], base),
                                 growth(rig["amp_end"], rig), growth(rig["amp_max_ext"], rig)))
    add("")
    quiet = rig["amp_end"] < 0.5 * base["amp_end"]
    add("**Agrees:** in both scenes the residual vibration is damped out by about 2 s (%s and %s over the last "
        "0.5 s at rest, from %s and %s over 0.2-0.7 s). %s (largest over 0.5 s of the extraction: %s "
        "against %s). The mean deflection of boom 3 in its own frame is nearly the same in both (%s against %s), "
        "as it should be: the moving frame removes the motion of boom 3 as a whole. %s\n"
        % (mm(base["amp_rest"]), mm(rig["amp_rest"]), mm(base["amp_early"]), mm(rig["amp_early"]),
           ("**Agrees:** with booms 1-2 rigid the extraction at full speed excites less vibration of boom 3 in "
            "its frame than with all booms flexible: %s against %s over the last 0.5 s at full speed (%.1f times "
            "less)" if quiet else
            "**Differs:** with booms 1-2 rigid the extraction at full speed excites as much vibration of boom 3 in "
            "its frame as with all booms flexible: %s against %s over the last 0.5 s at full speed (ratio %.1f)")
           % (mm(rig["amp_end"]), mm(base["amp_end"]), ratio(base["amp_end"], rig["amp_end"])),
           mm(rig["amp_max_ext"]), mm(base["amp_max_ext"]), mm(rig["end_mean"]), mm(base["end_mean"]),
           ("**Agrees:** with all booms flexible the vibration grows again (factor %.1f), so the growth needs "
            "flexible booms 1-2, as the paper concludes." % ratio(base["amp_end"], base["amp_rest"])
            if ratio(base["amp_end"], base["amp_rest"]) > 1.5 and quiet else
            "**Differs:** with all booms flexible the vibration does not grow above its level at rest (factor "
            "%.2f, largest 0.5 s window %.2f): these runs show the paper's contrast between flexible and rigid "
            "booms 1-2 during the extraction, but at a level far below the residual vibration at rest, not as "
            "a regrowth (see Fig. 8 for why)." % (ratio(base["amp_end"], base["amp_rest"]),
                                                  ratio(base["amp_max_ext"], base["amp_rest"])))))

    # Fig. 12
    add("## Fig. 12: angular velocity of the elevation angle\n")
    add(link("fig12", "Fig. 12 reproduced"))
    add("")
    add("Scenes `paper_elevation_35` and `paper_elevation_70`: boom 1 luffed from 0° by a quintic "
        "(smooth_step) angle profile during the extraction. The paper gives the profile only as its Fig. 12, "
        "with peaks of approx. 0.2 and 0.4 rad/s. The curves are the time derivative of the slope angle of "
        "boom 1's base node from `/state/q` (every 10 ms), and, dotted, the derivative of the scene's angle "
        "function.\n")
    add("| | paper (approx.) | θ = 0 → 35° | θ = 0 → 70° |")
    add("|---|---:|---:|---:|")
    add("| peak angular velocity, from the motion | 0.2 / 0.4 rad/s | %.3f rad/s at %.2f s | %.3f rad/s at %.2f s |"
        % (e35["rate_peak"], e35["rate_t_peak"], e70["rate_peak"], e70["rate_t_peak"]))
    add("| peak from the scene's profile | | %s rad/s | %s rad/s |" % (f3(e35["rate_analytic_peak"]),
                                                                     f3(e70["rate_analytic_peak"])))
    add("| largest difference motion − profile | | %s rad/s | %s rad/s |" % (
        "%.1e" % e35["rate_diff"] if np.isfinite(e35["rate_diff"]) else "n/a",
        "%.1e" % e70["rate_diff"] if np.isfinite(e70["rate_diff"]) else "n/a"))
    add("| angular velocity above 0.001 rad/s | | %.2f-%.2f s | %.2f-%.2f s |" % (e35["rate_span"] + e70["rate_span"]))
    add("| elevation at the end | 35° / 70° | %.2f° | %.2f° |" % (e35["theta_end"], e70["theta_end"]))
    add("")
    add("**Differs:** the profile's shape and timing are a choice (a quintic over 1.0-6.73 s with the "
        "paper's peak values); the paper does not give its profile in numbers.\n")

    # Fig. 13
    add("## Fig. 13: effect of the elevation angle\n")
    add(link("fig13", "Fig. 13 reproduced"))
    add("")
    add("The paper: *\"the deflection becomes smaller as the elevation angle is larger since the effect of "
        "gravity that contributes to the transverse deflection of the boom becomes smaller as the elevation "
        "angle increases.\"*\n")
    add("| final elevation | mean deflection, last 0.1 s | deflection at 7 s | ratio to 0° | cos θ | vibration amplitude, last 0.5 s at full speed |")
    add("|---:|---:|---:|---:|---:|---:|")
    for deg, d in ((0, base), (35, e35), (70, e70)):
        add("| %d° | %s | %s | %.3f | %.3f | %s |" % (deg, mm(d["end_mean"]), mm(d["final"]),
                                                      ratio(d["end_mean"], base["end_mean"]), np.cos(np.radians(deg)),
                                                      mm(d["amp_end"])))
    add("")
    add("**Agrees:** the deflection is smaller at larger elevation, in the paper's order (0°, 35°, 70°), and "
        "for the paper's reason: the weight and the dead vertical tip load bend the boom with their components "
        "normal to it, ∝ cos θ. The ratios to the horizontal case are within %.0f %% of cos θ, slightly above "
        "it (plausibly the axial compression, ∝ sin θ, which softens the boom in bending; not investigated "
        "further). The luffing adds hardly any vibration (amplitude over the last 0.5 s at full speed %s and %s against %s "
        "at 0°). The magnitudes are predictions (Fig. 8).\n"
        % (100 * max(abs(ratio(d["end_mean"], base["end_mean"]) / np.cos(np.radians(deg)) - 1)
                     for deg, d in ((35, e35), (70, e70))),
           mm(e35["amp_end"]), mm(e70["amp_end"]), mm(base["amp_end"])))

    # Fig. 14
    add("## Fig. 14: motion of the telescopic boom (70°)\n")
    add(link("fig14", "Fig. 14 reproduced"))
    add("")
    add("The paper shows snapshots of the 70° case without numbers. Here the shapes of `paper_elevation_70` at "
        "%s s, drawn true to scale (beams sampled inside the elements with the ANCF shape functions). Tip "
        "positions:\n" % ", ".join("%g" % t for t, _ in n["fig14"]))
    add("| t [s] | " + " | ".join("%.2f" % t for t, _ in n["fig14"]) + " |")
    add("|---|" + "---:|" * len(n["fig14"]))
    add("| tip x [m] | " + " | ".join("%.3f" % p[0] for _, p in n["fig14"]) + " |")
    add("| tip y [m] | " + " | ".join("%.3f" % p[1] for _, p in n["fig14"]) + " |")
    add("")
    add("An animation of any run: `/usr/bin/python3 postprocess/snapshots.py RUN.h5 --animate` (MP4 with "
        "ffmpeg, else GIF).\n")

    # Issue 15: the parts
    add("## The ropes and the slide pads\n")
    add("Every extraction scene moves boom 3 with an extension and a retraction rope (elastic, tension-only, "
        "EA = 1.2e7 N, 1 kN pretension, 500 N s/m damping) and carries the booms on four slide pads "
        "(k_pad = 5e8 N/m, no clearance, 2e4 N s/m). Tensions in N, at rest (t ≤ 2 s, including the step "
        "start) and during the extraction; pad forces are the normal contact forces (negative: the pad presses "
        "on side +1); a lift-off is a pad force passing through zero (with no clearance the pad then bears on "
        "the other side at once).\n")
    add("| scene | extension rope: at rest; extraction [N] | retraction rope: at rest; extraction [N] | "
        "slack events (first) | pad force range during the extraction [kN] | pad lift-offs (last at) |")
    add("|---|---:|---:|---:|---:|---:|")
    for key in EXTRACTION_SCENES:
        parts = n[key]["parts"]
        ropes, pads = parts["ropes"], parts["pads"]
        rng = lambda r: "%.0f … %.0f; %.0f … %.0f" % (r["rest"] + r["moving"])  # noqa: E731
        ev = [r["first"] for r in ropes.values() if r["first"]]
        first = min(ev) if ev else None
        lo = [p["lift_offs"] for p in pads.values()]
        last = max((p["last_lift_off"] for p in pads.values() if p["lift_offs"]), default=float("nan"))
        add("| %s | %s | %s | %d%s | %s | %d%s |" % (
            runs[key].scene, rng(ropes["extension"]) if "extension" in ropes else "-",
            rng(ropes["retraction"]) if "retraction" in ropes else "-",
            sum(r["events"] for r in ropes.values()),
            " (%s %s at %.3f s)" % (first[1], first[2], first[0]) if first else "",
            ", ".join("%s %.1f … %.1f" % (j, 1e-3 * p["moving"][0], 1e-3 * p["moving"][1])
                      for j, p in sorted(pads.items())),
            sum(lo), " (%.3f s)" % last if np.isfinite(last) else ""))
    add("")
    main_parts = n["paper_extraction"]["parts"]
    add("In `paper_extraction` the ropes stay taut through the step start and the start of the extraction "
        "(the acceleration-limited drive asks boom 3 for at most 2 m/s², about 40 N on 19.5 kg); %s The "
        "pads j1 and j3 (the inner booms' front pads) stay on one side for the whole run; j2 and j4 (the rear "
        "pads) change sides only while the step-load vibration lasts (%d lift-offs, the last at %.3f s). "
        "With the ramp drive (velocity jump at 2 s) and no rope damping the same ropes went slack and taut 893 "
        "times after 2 s (docs/paper-scenes.md).\n"
        % ("the extension rope loses its pretension during the extraction (%d slack event%s, first at %.3f s): "
           "the sag of the bent booms shortens its path more than 0.33 mm, its stretch at 1 kN; the retraction "
           "rope then holds boom 3 (%.0f … %.0f N)."
           % (main_parts["ropes"]["extension"]["events"], "" if main_parts["ropes"]["extension"]["events"] == 1
              else "s", main_parts["ropes"]["extension"]["first"][0], *main_parts["ropes"]["retraction"]["moving"])
           if main_parts["ropes"].get("extension", {}).get("first") else "neither rope goes slack.",
           sum(p["lift_offs"] for p in main_parts["pads"].values()),
           max((p["last_lift_off"] for p in main_parts["pads"].values() if p["lift_offs"]), default=float("nan"))))

    # Single-number calibration
    sc = n["single"]
    add("## Single-number calibration (variant)\n")
    add("`inputs/paper_extraction_single_calibration.yaml` is `paper_extraction` as it was before issue 15: "
        "rigid bilateral joints, one inextensible rope, the ramp drive, steel density, every I × 0.5747 so "
        "that the retracted frequency is 27.0 Hz (one number). Against the two-number calibration:\n")
    add("| quantity | paper | single number (c = 0.5747, steel density) | two numbers (c = 0.1877, m = 0.3262, pads, ropes) |")
    add("|---|---:|---:|---:|")
    add("| first frequency at t = 0 | 27.0 Hz | %.3f Hz | %.3f Hz |" % (sc["freq"]["f0"], fr["f0"]))
    add("| first frequency fully extended | 10.2 Hz | %.3f Hz | %.3f Hz |" % (sc["freq"]["f_end"], fr["f_end"]))
    add("| tip y, mean over the last 0.1 s | approx. −0.2 m | %.4f m | %.4f m |" % (sc["tip_end_mean"], tip["end_mean"]))
    add("| moving-frame deflection, mean over the last 0.1 s | approx. −0.02 to −0.03 m | %s | %s |"
        % (mm(sc["end_mean"]), mm(base["end_mean"])))
    add("| moving-frame vibration, last 0.5 s at rest / last 0.5 s at full speed | decreases, then increases | %s / %s | %s / %s |"
        % (mm(sc["amp_rest"]), mm(sc["amp_end"]), mm(base["amp_rest"]), mm(base["amp_end"])))
    add("")
    add("The single number fixes the stiffness-to-mass ratio only, and with steel-box masses the deflections "
        "come out 3-4 times smaller than the paper's. The second number (the extended tip) fixes the stiffness "
        "itself: the booms are then a third of the steel boxes' mass and a fifth of their bending stiffness, "
        "and the moving-frame deflection, not fitted, lands in the paper's range.\n")

    add("## Without structural damping (variant)\n")
    add("The same scenes without the damping keys, with the single-number calibration (as in `inputs/` up to "
        "commit c610d0f; quoted from this report as generated then, not recomputed here). The first-mode vibration started at t = 0 never decays: "
        "global tip 6.60 mm over 0.2-0.7 s, 6.44 mm over the last 0.5 s at rest, 13.16 mm over the last 0.5 s "
        "(Fig. 6). In boom 3's frame (Fig. 8) 0.16 / 0.11 / 0.52 mm (growth factor 4.8), with booms 1-2 rigid "
        "0.08 / 0.05 / 0.06 mm (factor 1.1, Fig. 11); 5 kN and 20 kN 0.06 / 0.28 mm and 0.21 / 0.98 mm at rest "
        "/ at the end (Fig. 10); at 35° and 70° 0.53 mm over the last 0.5 s (Fig. 13). The mean deflections are "
        "those with damping to within a few hundredths of a millimetre (-6.27 mm fully extended, Fig. 8). That "
        "growth is no evidence that the extraction feeds the vibration: an undamped vibration whose frequency "
        "falls slowly keeps E/ω about constant, so its amplitude grows as ω^(−1/2) without any energy input "
        "(about 1.6 for 27.0 → 10.0 Hz against 2.0 measured for the global tip), and it shows more in boom 3's "
        "frame as the first mode bends the longer overhang. With damping (above) the vibration decays before "
        "the extraction, and what remains to grow is what the extraction itself excites.\n")
    add("The damped runs use generalized-α with ρ∞ = 0.8 at h = 1 ms like the undamped ones, started (and "
        "restarted at the drive's kinks) from accelerations without the modes a step cannot resolve "
        "(docs/model.md §4.3). From the consistent accelerations themselves the scheme fed the mesh's overdamped "
        "top modes (ζ = ηω/2 ≫ 1 at ωh ≫ 1) about 47 J in the single-calibration scene's second step, and the "
        "ropes' tension peaked at 1052 N instead of their 1000 N pretension at the start of the paper "
        "extraction (docs/model.md §7.1); now the energy only falls there. The energy check counts the damping "
        "work as the discrete forces do it and the balance closes (paper extraction: excess %.2f J of %.0f J "
        "involved over 7 s).\n"
        % (float(runs["paper_extraction"].summary.get("energy_excess_J", float("nan"))),
           float(runs["paper_extraction"].summary.get("energy_involved_J", float("nan")))))
    with open(path, "w") as out:
        out.write("\n".join(L))
    return path


# ----------------------------------------------------------------------------- main

def make_figures(runs, fig_dir):
    """Every figure from the loaded runs; returns {figure key: path}."""
    os.makedirs(fig_dir, exist_ok=True)
    p = lambda name: os.path.join(fig_dir, name)  # noqa: E731
    r = runs
    return {
        "fig05": fig05(r["paper_stick_slip"], p("fig05_stick_slip.png")),
        "fig06": fig06(r["paper_extraction"], p("fig06_tip_vertical_position.png")),
        "fig07": fig07(r["paper_extraction"], p("fig07_frequency.png")),
        "fig08": fig08(r["paper_extraction"], p("fig08_moving_frame_deflection.png")),
        "fig09": fig09(r["paper_extraction"], p("fig09_moving_frame.png")),
        "fig10": fig10([(5, r["paper_extraction_5kN"]), (10, r["paper_extraction"]),
                        (20, r["paper_extraction_20kN"])], p("fig10_tip_load.png")),
        "fig11": fig11(r["paper_extraction"], r["paper_rigid_booms"], p("fig11_rigid_booms.png")),
        "fig12": fig12([(35, r["paper_elevation_35"]), (70, r["paper_elevation_70"])], p("fig12_elevation_rate.png")),
        "fig13": fig13([(0, r["paper_extraction"]), (35, r["paper_elevation_35"]), (70, r["paper_elevation_70"])],
                       p("fig13_elevation_deflection.png")),
        "fig14": fig14(r["paper_elevation_70"], p("fig14_motion_70deg.png")),
    }


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", default=os.path.join(ROOT, "docs"),
                    help="folder of paper-comparison.md; figures go to OUT/figures (default: docs)")
    ap.add_argument("--build", default=os.path.join(ROOT, "build"), help="build folder holding boomdyn (default: build)")
    ap.add_argument("--work", help="folder for the results files (default: BUILD/paper_comparison)")
    ap.add_argument("--jobs", type=int, default=2, help="runs at a time (default 2)")
    ap.add_argument("--no-run", action="store_true", help="reuse the results files already in --work")
    a = ap.parse_args(argv)
    work = a.work or os.path.join(a.build, "paper_comparison")
    start = time.time()
    if not a.no_run:
        boomdyn = os.path.join(a.build, "boomdyn")
        if not os.access(boomdyn, os.X_OK):
            raise SystemExit("no boomdyn executable at %s (build it: cmake --build %s)" % (boomdyn, a.build))
        run_scenes(boomdyn, work, jobs=a.jobs)
    runs = {k: Run(os.path.join(work, k + ".h5")) for k in SCENES}
    bad = [k for k, r in runs.items() if r.summary.get("status") != "completed"]
    if bad:
        raise SystemExit("runs not completed: %s" % ", ".join(bad))
    figures = make_figures(runs, os.path.join(a.out, "figures"))
    numbers = collect(runs)
    report = write_report(os.path.join(a.out, "paper-comparison.md"), runs, figures, numbers)
    for path in list(figures.values()) + [report]:
        print("wrote %s" % path)
    print("done in %.0f s" % (time.time() - start))
    return 0


if __name__ == "__main__":
    sys.exit(main())
