#!/usr/bin/env python3
"""The output channels that registered types declare reach the results file
without a change to the writer: /steps/outputs and /layout/output_names.
A beam pinned at its start and held at its end by a vertical distance link
(statics) carries half its weight W/2 = rhoA L g / 2 in the link; a short
run of the paper extraction scene writes its rope's tension both as
/steps/rope_tension and as the channel rope/rope/tension.
Usage: test_output_channels.py BOOMDYN_EXECUTABLE SOURCE_DIR WORK_DIR"""
import os
import subprocess
import sys

import h5py
import numpy as np

boomdyn, source, work = sys.argv[1:4]
sys.path.insert(0, os.path.join(source, "tests"))
import script_checks  # noqa: E402

results = []


check = script_checks.checker(results)

STAYED_BEAM = """name: stayed_beam
analysis: static
gravity: [0, -9.81]
bodies:
  - {name: beam, length: 2, elements: 8, section: {EA: 1.0e10, EI: 1.0e8, rhoA: 30}}
constraints:
  - {type: pin, body: beam, at: start}
  - {type: distance, name: stay, body: beam, at: end, point: [2, 1]}
static: {load_steps: 2}
"""


def run(scene, name, extra=()):
    out = os.path.join(work, name + ".h5")
    subprocess.run([boomdyn, scene, "-o", out, "-boom_overwrite", "-boom_quiet", *extra], check=True,
                   stdout=subprocess.DEVNULL)
    return out


def main():
    scene = os.path.join(work, "stayed_beam.yaml")
    with open(scene, "w") as f:
        f.write(STAYED_BEAM)
    with h5py.File(run(scene, "stayed_beam")) as f:
        names = list(f["layout/output_names"].asstr()[:])
        units = list(f["layout/output_units"].asstr()[:])
        check(names == ["distance/stay/tension"] and units == ["N"],
                     "the distance link declares one channel distance/stay/tension [N] (got %s %s)" % (names, units))
        tension = float(f["steps/outputs"][-1][0]) if "steps/outputs" in f else float("nan")
        half_weight = 30 * 2 * 9.81 / 2
        check(abs(tension - half_weight) < 1e-6 * half_weight,
                     "the link carries W/2 = %.6f N (written %.9f N)" % (half_weight, tension))

    extraction = os.path.join(source, "inputs", "paper_extraction_single_calibration.yaml")  # inextensible rope
    with h5py.File(run(extraction, "extraction_channels", ["-ts_max_time", "0.05", "-boom_elements", "4"])) as f:
        names = list(f["layout/output_names"].asstr()[:])
        check("rope/rope/tension" in names, "the rope declares rope/rope/tension (got %s)" % names)
        if "rope/rope/tension" in names:
            column = f["steps/outputs"][:, names.index("rope/rope/tension")]
            ropes = list(f["layout/rope_names"].asstr()[:])
            written = f["steps/rope_tension"][:, ropes.index("rope")]
            check(len(column) == len(written) and np.array_equal(column, written) and np.all(np.abs(written) > 0),
                         "the channel equals /steps/rope_tension at every step (%d steps)" % len(written))


sys.exit(script_checks.finish(main, results))
