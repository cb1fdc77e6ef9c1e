#!/usr/bin/env python3
"""The figure and report functions of postprocess/paper_comparison.py on short,
coarse runs (4 elements per boom; extraction scenes to 2.5 s, elevation to
2 s, stick-slip to 0.5 s), not the full paper runs (those take minutes: run
paper_comparison.py itself). Every figure must be a real picture, the report
must link every figure and print the numbers of the results files (read
here with h5py alone), the Fig. 9 sketch must measure the deflection boomdyn
wrote, and the elevation rate from the motion must follow the scene's profile.
Usage: test_paper_comparison.py BOOMDYN_EXECUTABLE SOURCE_DIR WORK_DIR"""
import os
import re
import subprocess
import sys

import matplotlib
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import script_checks  # noqa: E402

matplotlib.use("Agg")
import h5py  # noqa: E402
import matplotlib.image  # noqa: E402
import numpy as np  # noqa: E402

boomdyn, source, work = sys.argv[1:4]
sys.path.insert(0, os.path.join(source, "postprocess"))
import paper_comparison as pc  # noqa: E402

COARSE = ["-boom_overwrite", "-boom_quiet", "-boom_elements", "4"]
results = []


check = script_checks.checker(results)


def run(scene, t_end, extra=()):
    out = os.path.join(work, "pc_" + scene + ".h5")
    subprocess.run([boomdyn, os.path.join(source, "inputs", scene + ".yaml"), "-o", out, "-ts_max_time", str(t_end)]
                   + COARSE + list(extra), check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return pc.Run(out)


def table_row(text, label):
    """The cells of the report's table row whose first cell starts with `label` (None if absent)."""
    for line in text.splitlines():
        if line.startswith("| " + label):
            return [c.strip() for c in line.strip().strip("|").split("|")]
    return None


def printed_as(printed, value):
    """Whether the number `printed` (e.g. '-0.0716') is `value` rounded to the printed digits."""
    decimals = len(printed.split(".")[1]) if "." in printed else 0
    return abs(float(printed) - value) <= 0.5 * 10.0 ** -decimals * (1 + 1e-9)


def numbers_in(cell):
    return re.findall(r"-?[0-9]+\.?[0-9]*(?:e[-+]?[0-9]+)?", cell or "")


def check_report_numbers(text, extraction, elevation, stick):
    """The numbers the report prints are those of the results files, read here
    with h5py alone (not through paper_comparison.Run), plus one physical check."""
    for run in (extraction, elevation, stick):
        with h5py.File(run.path, "r") as f:
            steps = int(f["summary"].attrs["steps"])
            violation = float(f["summary"].attrs["max_constraint_violation"])
            name = f.attrs["scene_name"]
            name = name.decode() if isinstance(name, bytes) else str(name)
        row = table_row(text, name + " |")
        check(row is not None and int(row[3]) == steps and abs(float(row[4]) - violation) <= 0.051 * violation,
              "summary table, %s: %s steps, violation %s (file: %d, %.1e)"
              % (name, row and row[3], row and row[4], steps, violation))

    with h5py.File(extraction.path, "r") as f:
        tracked0 = float(f["tracking/tracked_hz"][0])
        t = f["steps/time"][()]
        y = f["sensors/tip/position"][:, 1]
    # Fig. 7: the retracted frequency as tracked, and (independently of the
    # report) near the paper's 27.0 Hz, to which the 16-element sections are
    # calibrated; the coarse 4-element mesh is a little stiffer.
    row = table_row(text, "retracted (t = 0)")
    got = numbers_in(row[2] if row else "")
    check(len(got) == 1 and printed_as(got[0], tracked0),
          "Fig. 7 table: retracted frequency %s Hz, /tracking/tracked_hz[0] = %.6f Hz" % (got, tracked0))
    check(abs(tracked0 / 27.0 - 1) < 0.02, "retracted first frequency %.3f Hz within 2 %% of 27.0 Hz" % tracked0)
    # Fig. 6: last and lowest tip y, and when.
    row = table_row(text, "tip y at 7 s; lowest tip y")
    got = numbers_in(row[2] if row else "")
    expected = (float(y[-1]), float(y.min()), float(t[np.argmin(y)]))
    check(len(got) == 3 and all(printed_as(g, e) for g, e in zip(got, expected)),
          "Fig. 6 table: last, lowest tip y and its time %s, file: %.5f m, %.5f m at %.3f s" % ((got,) + expected))

    # Fig. 5: the start-up events of j2 listed in the report are /events of j2.
    with h5py.File(stick.path, "r") as f:
        names = [n.decode() if isinstance(n, bytes) else str(n) for n in f["layout/friction_joint_names"][()]]
        ev = {k: f["events/" + k][()] for k in ("time", "joint", "to_slip")} if "events" in f else None
    j = names.index("j2")
    expected = [(float(tt), bool(sl)) for tt, jj, sl in zip(ev["time"], ev["joint"], ev["to_slip"])
                if jj == j and tt <= 3.0] if ev is not None else []
    row = table_row(text, "start-up slip")
    listed = re.findall(r"([0-9.]+) s (stick→slip|slip→stick)", row[2] if row else "")
    check(row is not None and len(listed) == len(expected) and (expected or row[2] == "none")
          and all(printed_as(tt, e[0]) and (kind == "stick→slip") == e[1] for (tt, kind), e in zip(listed, expected)),
          "Fig. 5 table: start-up events of j2 %s, file: %s" % (listed, expected))

    # Issue 15: the rope tensions the report prints are /steps/outputs of the extraction run.
    with h5py.File(extraction.path, "r") as f:
        names = list(f["layout/output_names"].asstr()[()])
        tension = f["steps/outputs"][:, names.index("elastic_rope/extension/tension")]
        t = f["steps/time"][()]
    row = table_row(text.split("## The ropes and the slide pads", 1)[-1], extraction.scene + " | ")
    rest = tension[t <= 2.0]
    got = numbers_in(row[1] if row else "")
    check(len(got) >= 2 and abs(float(got[0]) - rest.min()) <= 0.5 and abs(float(got[1]) - rest.max()) <= 0.5,
          "ropes table: extension rope tension at rest %s N, file: %.1f … %.1f N" % (got[:2], rest.min(), rest.max()))


def main():
    extraction = run("paper_extraction", 2.5, ["-boom_tracking_interval", "0.05"])
    rigid = run("paper_rigid_booms", 2.5)
    elevation = run("paper_elevation_70", 2.0)
    stick = run("paper_stick_slip", 0.5)
    # Stand-ins: the short extraction run plays every load case, the 70° run both elevations.
    runs = {"paper_extraction": extraction, "paper_extraction_5kN": extraction, "paper_extraction_20kN": extraction,
            "paper_rigid_booms": rigid, "paper_elevation_35": elevation, "paper_elevation_70": elevation,
            "paper_stick_slip": stick, "paper_extraction_single_calibration": extraction}
    out = os.path.join(work, "pc_docs")
    figures = pc.make_figures(runs, os.path.join(out, "figures"))
    check(sorted(figures) == ["fig%02d" % k for k in range(5, 15)], "a figure for each of Figs. 5-14")
    for key, path in sorted(figures.items()):
        ok = os.path.isfile(path) and os.path.getsize(path) > 0 and float(matplotlib.image.imread(path).std()) > 0
        check(ok, "%s is a non-uniform PNG" % os.path.basename(path))

    numbers = pc.collect(runs)
    report = pc.write_report(os.path.join(out, "paper-comparison.md"), runs, figures, numbers)
    text = open(report).read()
    links = [line.split("](", 1)[1].rstrip(")") for line in text.splitlines() if line.startswith("![")]
    check(len(links) == 10 and all(os.path.isfile(os.path.join(out, link)) for link in links),
          "the report links the 10 figures by relative paths that exist")
    check_report_numbers(text, extraction, elevation, stick)

    g = numbers["frame9"]
    check(abs(g["delta"] - g["written"]) < 1e-12, "Fig. 9 sketch: deflection %.6e m, boomdyn wrote %.6e m"
          % (g["delta"], g["written"]))
    check(abs(np.dot(g["ex"], g["contact"] - g["origin"]) - np.linalg.norm(g["contact"] - g["origin"])) < 1e-12,
          "Fig. 9 sketch: the x3 axis runs through boom 3's rear end and the j3 contact point")

    te, numeric, analytic, theta = pc.elevation_rates(elevation)
    if analytic is None:
        print("skipped: elevation profile from the scene (no PyYAML)")
    else:
        inside = (te > 0.05) & (te < te[-1] - 0.05)  # np.gradient is one-sided at the ends
        err = np.abs(numeric - analytic)[inside].max()
        check(err < 1e-3 * max(analytic.max(), 1e-3) + 1e-5,
              "Fig. 12: rate from the motion follows the scene's profile (largest difference %.1e rad/s)" % err)
    check(numbers["freq"]["f0"] > 0 and np.isfinite(numbers["freq"]["zc_start"]), "Fig. 7 numbers from the tracking")

    # The time-function derivatives against finite differences of the functions themselves.
    t = np.linspace(0, 8, 8001)
    smooth = {"type": "smooth_step", "t0": 1.0, "t1": 6.73, "from": 0, "to": 70}
    s = np.clip((t - 1.0) / 5.73, 0, 1)
    value = 70 * (10 * s**3 - 15 * s**4 + 6 * s**5)
    fd = np.gradient(value, t)
    check(np.abs(pc.time_function_rate(smooth, t) - fd)[1:-1].max() < 1e-4, "smooth_step rate = d/dt of the profile")
    sine = {"type": "sine", "amplitude": 15, "frequency": 0.04431, "phase": 158.3, "offset": 5}
    value = 5 + 15 * np.sin(2 * np.pi * 0.04431 * t + np.radians(158.3))
    err = np.abs(pc.time_function_rate(sine, t) - np.gradient(value, t))[1:-1]  # central differences only
    check(err.max() < 1e-4, "sine rate = d/dt of the sine")


if __name__ == "__main__":
    sys.exit(script_checks.finish(main, results))
