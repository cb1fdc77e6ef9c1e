#!/usr/bin/env python3
"""The tutorial boom's results (docs/tutorial.md), read from its HDF5 file.

  /usr/bin/python3 docs/tutorial/boom_results.py RUN.h5 [--plot PNG] [--compare OTHER.h5]

Prints the numbers a crane engineer looks at first (static tip deflection,
rope tension, root moment, the tracked frequencies at the start and the end,
how far the payload rose) next to closed-form estimates for the retracted
boom; --plot draws the hook's rise and swing, the rope tension and the tracked
frequencies against time; --compare prints the largest differences from a
second run of the same scene (e.g. on 2 ranks).

Needs numpy, h5py, matplotlib and PyYAML (Debian: python3-h5py,
python3-matplotlib, python3-yaml) and postprocess/ on sys.path (done below).
"""
import argparse
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "postprocess"))
import boomdyn_h5  # noqa: E402


def channel(f, name):
    """Column `name` of /steps/outputs (e.g. 'elastic_rope/hoist/tension')."""
    names = [n.decode() if isinstance(n, bytes) else n for n in f["layout/output_names"][()]]
    return f["steps/outputs"][:, names.index(name)]


def telescope_compliance(base, fly):
    """Tip deflection per newton of tip load (m/N) of the two-stage telescope,
    and its deflected shape, from Euler-Bernoulli beam theory.

    The base is a cantilever of length L1 clamped at x = 0; the fly (length L2)
    starts at x = a inside it. The fly rests on two supports: the base's front
    pad at x = L1 and its own rear pad at x = a, a lever with the overlap
    o = L1 - a as its span and c = L2 - o sticking out. A tip load P pushes
    the base down by P (1 + c/o) at its front and up by P c/o at x = a."""
    L1, EI1 = base["length"], base["EI"]
    a, L2, EI2 = fly["origin"], fly["length"], fly["EI"]
    o = L1 - a
    c = L2 - o
    down, up = 1 + c / o, c / o

    def cantilever(x, at):  # deflection at x of a cantilever (EI = 1) under a unit force at `at`
        return np.where(x <= at, x**2 * (3 * at - x), at**2 * (3 * x - at)) / 6.0

    def base_w(x):
        return (down * cantilever(x, L1) - up * cantilever(x, a)) / EI1

    wa, wb = base_w(a), base_w(L1)
    tip = wb + (wb - wa) * c / o + c**2 * (c + o) / (3 * EI2)

    def fly_w(s):  # s along the fly from its rear end
        chord = wa + (wb - wa) * s / o  # the fly follows its two supports ...
        span = -c * s * (o**2 - s**2) / (6 * EI2 * o)  # ... bulges up between them ...
        u = s - o  # ... and bends down beyond the front pad
        overhang = c * o * u / (3 * EI2) + u**2 * (3 * c - u) / (6 * EI2)
        return chord + np.where(s <= o, span, overhang)

    return tip, base_w, fly_w


def estimates(scene, static_tension):
    """Closed-form root moment and first frequencies of the retracted boom with the payload.

    Bounce: the payload on two springs in series, the boom tip (beam theory
    above) and the rope (length l / EA), plus the booms' own mass by Rayleigh's
    quotient with the static deflection shape. Pendulum: a simple pendulum of
    the hanging rope length plus half the payload's length."""
    bodies = {b["name"]: b for b in scene["bodies"]}
    rope = next(c for c in scene["constraints"] if c.get("type") == "elastic_rope")

    def beam(name):
        b = bodies[name]
        s = {key: float(value) for key, value in b["section"].items()}  # PyYAML reads 2.1e11 as text
        return {"length": float(b["length"]), "EI": s["E"] * s["I"], "rhoA": s["rho"] * s["A"],
                "origin": float(b["origin"][0])}

    base, fly = beam(rope["from"]), beam(rope["pulley"])
    payload = bodies[rope["to"]]
    mass = float(payload["length"]) * float(payload["section"]["rhoA"])
    tip, base_w, fly_w = telescope_compliance(base, fly)
    # Rope: winch to sheave along the boom, then down to the payload.
    hang = -float(payload["origin"][1])
    EA = float(rope["EA"])
    rope_length = (fly["origin"] + fly["length"] - float(rope["from_at"])) + hang
    rope_compliance = rope_length / (EA * (1 + static_tension / EA))
    r = tip / (tip + rope_compliance)  # share of the payload's motion that is the boom's
    x = np.linspace(0, base["length"], 2001)
    s = np.linspace(0, fly["length"], 2001)
    integral = getattr(np, "trapezoid", None) or np.trapz  # numpy >= 2 renamed it
    boom_mass = integral(base["rhoA"] * (base_w(x) / tip) ** 2, x) + integral(fly["rhoA"] * (fly_w(s) / tip) ** 2, s)
    k = 1 / (tip + rope_compliance)
    bounce = math.sqrt(k / (mass + r**2 * boom_mass)) / (2 * math.pi)
    g = math.hypot(*(float(v) for v in scene.get("gravity", [0, 0])))
    pendulum = math.sqrt(g / (hang + float(payload["length"]) / 2)) / (2 * math.pi)
    # Root moment of the horizontal boom at rest: the payload's weight hangs at
    # the tip (the rope's pulls along the boom cancel), each boom's weight at
    # its middle.
    root_moment = g * (mass * (fly["origin"] + fly["length"])
                       + sum(b["rhoA"] * b["length"] * (b["origin"] + b["length"] / 2) for b in (base, fly)))
    return {"tip_stiffness": 1 / tip, "rope_stiffness": 1 / rope_compliance, "boom_mass": boom_mass,
            "root_moment": root_moment, "bounce": bounce, "pendulum": pendulum}


def summary(path):
    """The run's key numbers as a dict."""
    with boomdyn_h5.open_run(path) as f:
        t = f["steps/time"][()]
        tip = f["sensors/tip/position"][()]
        hook = f["sensors/hook/position"][()]
        tension = channel(f, "elastic_rope/hoist/tension")
        tr = f["tracking"]
        return {"status": f["summary"].attrs["status"], "time": t, "tip": tip, "hook": hook, "tension": tension,
                "track_time": tr["time"][()], "followed_hz": tr["followed_hz"][()],
                "damping_ratio": tr["followed_damping_ratio"][()] if "followed_damping_ratio" in tr else None,
                "root_moment": f["summary"].attrs["design.clamp.root.static_root_moment_Nm"],
                "peak_root_moment": f["summary"].attrs["design.clamp.root.peak_root_moment_Nm"],
                "scene": boomdyn_h5.load_scene(f)}


def report(run):
    t, tip, hook, tension = run["time"], run["tip"], run["hook"], run["tension"]
    f0, f1 = run["followed_hz"][0], run["followed_hz"][-1]
    print("status: %s, %d steps to t = %g s" % (run["status"], len(t) - 1, t[-1]))
    print("static state (t = 0):")
    print("  tip at x = %.4f m, deflection %.2f mm" % (tip[0, 0], 1e3 * tip[0, 1]))
    print("  hoist rope tension %.1f N, root moment %.1f kN m" % (tension[0], 1e-3 * run["root_moment"]))
    print("  pendulum %.4f Hz, bounce %.3f Hz" % (f0[0], f0[1]))
    if run["damping_ratio"] is not None:
        print("  damping ratio of the bounce %.2f %%" % (100 * run["damping_ratio"][0, 1]))
    print("end of the run (t = %g s):" % t[-1])
    print("  tip at x = %.4f m, deflection %.2f mm" % (tip[-1, 0], 1e3 * tip[-1, 1]))
    print("  payload rose by %.3f m, largest swing %.1f mm" % (hook[-1, 1] - hook[0, 1],
                                                         1e3 * np.abs(hook[:, 0] - tip[:, 0]).max()))
    print("  pendulum %.4f Hz, bounce %.3f Hz" % (f1[0], f1[1]))
    k = int(np.argmax(tension))
    print("  peak rope tension %.1f N at t = %.3f s (dynamic factor %.3f)"
          % (tension[k], t[k], tension[k] / tension[0]))
    print("  peak root moment %.1f kN m" % (1e-3 * run["peak_root_moment"]))
    e = estimates(run["scene"], tension[0])
    print("closed form, retracted (t = 0):")
    print("  tip stiffness %.4g N/m, rope %.4g N/m, boom mass at the tip %.1f kg"
          % (e["tip_stiffness"], e["rope_stiffness"], e["boom_mass"]))
    print("  root moment %.2f kN m (boomdyn %.2f kN m)" % (1e-3 * e["root_moment"], 1e-3 * run["root_moment"]))
    print("  bounce %.3f Hz (boomdyn %.3f Hz, %+.2f %%)" % (e["bounce"], f0[1], 100 * (f0[1] / e["bounce"] - 1)))
    print("  pendulum %.4f Hz (boomdyn %.4f Hz, %+.2f %%)" % (e["pendulum"], f0[0], 100 * (f0[0] / e["pendulum"] - 1)))


def compare(run, other):
    """Largest differences between two runs of the same scene."""
    n = min(len(run["time"]), len(other["time"]))
    m = min(len(run["track_time"]), len(other["track_time"]))
    dtip = np.abs(run["tip"][:n] - other["tip"][:n]).max()
    dtension = np.abs(run["tension"][:n] - other["tension"][:n]).max() / np.abs(run["tension"]).max()
    dfreq = (np.abs(run["followed_hz"][:m] - other["followed_hz"][:m]) / run["followed_hz"][:m]).max()
    print("compared over %d steps and %d analyses:" % (n - 1, m))
    print("  largest tip position difference %.1e m" % dtip)
    print("  largest rope tension difference %.1e (relative)" % dtension)
    print("  largest frequency difference %.1e (relative)" % dfreq)


def plot(run, png):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (ax_y, ax_t, ax_f) = plt.subplots(3, 1, figsize=(8, 8), sharex=True)
    t, tip, hook = run["time"], run["tip"], run["hook"]
    ax_y.plot(t, hook[:, 1] - hook[0, 1], label="hook rise")
    ax_y.plot(t, tip[:, 1] - tip[0, 1], label="tip height change")
    ax_y.plot(t, hook[:, 0] - tip[:, 0], label="swing (hook x - tip x)")
    ax_y.set_ylabel("[m]")
    ax_t.plot(t, 1e-3 * run["tension"])
    ax_t.set_ylabel("hoist rope tension [kN]")
    hz = run["followed_hz"]
    for k, label in enumerate(("pendulum", "bounce")):
        ax_f.plot(run["track_time"], hz[:, k] / hz[0, k], label="%s (%.3g Hz at t = 0)" % (label, hz[0, k]))
    ax_f.set_ylabel("frequency / its value at t = 0")
    ax_f.set_xlabel("time [s]")
    for ax in (ax_y, ax_t, ax_f):
        ax.grid(True)
    ax_y.legend(fontsize="small")
    ax_f.legend(fontsize="small")
    fig.tight_layout()
    fig.savefig(png, dpi=90)
    print("wrote %s" % png)


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("run")
    p.add_argument("--plot", help="write a PNG of the hook's rise and swing, rope tension and frequencies")
    p.add_argument("--compare", help="a second run of the same scene: print the largest differences")
    a = p.parse_args()
    run = summary(a.run)
    if a.compare:
        compare(run, summary(a.compare))
    else:
        report(run)
    if a.plot:
        plot(run, a.plot)


if __name__ == "__main__":
    main()
