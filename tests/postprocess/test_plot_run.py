#!/usr/bin/env python3
"""plot_run.py on synthetic results files written with h5py after docs/output.md.

Run: python3 tests/postprocess/test_plot_run.py  (exit code 1 on any failure)
"""

import subprocess
import sys
import tempfile
import traceback
from pathlib import Path

import h5py
import matplotlib
matplotlib.use("Agg")
import matplotlib.image as mpimg
import numpy as np

POSTPROCESS = Path(__file__).resolve().parents[2] / "postprocess"
PLOT_RUN = POSTPROCESS / "plot_run.py"
sys.path.insert(0, str(POSTPROCESS))
import boomdyn_h5  # noqa: E402  (needs the path above)

ALL_PLOTS = ["sensor_positions", "tip_vertical_position", "solver_effort", "constraint_violation", "energy",
             "modal_frequencies", "boom_shape"]
STEP_PLOTS = ["sensor_positions", "tip_vertical_position", "solver_effort", "constraint_violation", "energy"]

LENGTH = 2.0  # m, the beam of the synthetic scene
STRING = h5py.string_dtype("utf-8")  # variable-length UTF-8, as the C++ writer stores text


def angle(t):
    return 0.3 * np.sin(2 * np.pi * t)


def beam_q(t):
    """A 2-node ANCF beam pinned at the origin, rotated rigidly by angle(t): nq = 8."""
    c, s = np.cos(angle(t)), np.sin(angle(t))
    return np.array([0.0, 0.0, c, s, LENGTH * c, LENGTH * s, c, s])


def write_run(path, steps=True, sensors=True, states=True, modal=True, analysis="dynamic"):
    """A results file of a swinging beam, with the groups asked for."""
    n, dt = 200, 0.005
    time = dt * np.arange(1, n + 1)
    with h5py.File(path, "w") as f:
        for key, value in {"boomdyn_version": "0.1.0 (test)", "scene_name": "swinging test beam",
                           "scene_file": "swing.yaml", "analysis": analysis, "command_line": "boomdyn swing.yaml",
                           "petsc_options": "", "created_utc": "2024-01-01T00:00:00Z"}.items():
            f.attrs.create(key, value, dtype=STRING)
        f.attrs["mpi_ranks"] = np.int64(1)
        f.create_dataset("scene/text", data="name: swinging test beam\n", dtype=STRING)

        layout = f.create_group("layout")
        layout.attrs["nq"] = np.int64(8)
        layout.attrs["nlambda"] = np.int64(3)
        layout.create_dataset("body_names", data=["boom"], dtype=STRING)
        layout.create_dataset("body_first_coordinate", data=[0], dtype=np.int32)
        layout.create_dataset("body_num_coordinates", data=[8], dtype=np.int32)
        layout.create_dataset("constraint_names", data=["base pin", "luffing drive"], dtype=STRING)
        layout.create_dataset("constraint_first_row", data=[0, 2], dtype=np.int32)
        layout.create_dataset("constraint_num_rows", data=[2, 1], dtype=np.int32)

        if steps:
            g = f.create_group("steps")
            g["time"] = time
            g["dt"] = np.full(n, dt)
            g.create_dataset("newton_iterations", data=3 + (np.arange(n) % 3), dtype=np.int32)
            g["constraint_violation"] = 1e-12 * (1 + np.arange(n))
            kinetic = 0.5 * (0.3 * 2 * np.pi * np.cos(2 * np.pi * time)) ** 2
            gravity = 9.81 * np.sin(angle(time))
            g["energy"] = np.column_stack([kinetic, np.zeros(n), gravity, kinetic + gravity])
        if sensors:
            tip = np.array([beam_q(t)[4:6] for t in time])
            f["sensors/tip/position"] = tip
            f["sensors/tip/velocity"] = np.gradient(tip, dt, axis=0)
            f["sensors/mid/position"] = tip / 2
            f["sensors/mid/velocity"] = np.gradient(tip / 2, dt, axis=0)
        if states:
            snapshot_times = time[::50]
            f["state/time"] = snapshot_times
            f["state/q"] = np.array([beam_q(t) for t in snapshot_times])
            f["state/v"] = np.zeros((len(snapshot_times), 8))
            f["state/lambda"] = np.ones((len(snapshot_times), 3))
        if modal:
            f["modal/frequencies_hz"] = np.array([1.5, 9.4, 26.3])
            f["modal/shapes"] = np.eye(3, 8)
            f["modal"].attrs["state_time"] = time[-1]
        summary = f.create_group("summary")
        summary.attrs.create("status", "completed", dtype=STRING)
        summary.attrs["steps"] = np.int64(n if steps else 0)


def run_plot(*args):
    result = subprocess.run([sys.executable, str(PLOT_RUN), *map(str, args)], capture_output=True, text=True)
    assert result.returncode == 0, f"plot_run.py failed ({result.returncode}):\n{result.stdout}\n{result.stderr}"
    return result.stdout


def check_png(path):
    assert path.is_file(), f"missing {path}"
    assert path.stat().st_size > 0, f"empty {path}"
    with open(path, "rb") as f:
        assert f.read(8) == b"\x89PNG\r\n\x1a\n", f"not a PNG: {path}"
    image = mpimg.imread(path)
    assert image.shape[0] > 0 and image.shape[1] > 0, f"no pixels in {path}"
    assert np.ptp(image) > 0, f"uniform image {path}"


def test_full_file_gives_every_plot(tmp):
    run = tmp / "full.h5"
    write_run(run)
    out = run_plot(run, "-o", tmp / "plots")
    for name in ALL_PLOTS:
        check_png(tmp / "plots" / f"{name}.png")
        assert f"{name}.png" in out, f"{name}.png not reported in:\n{out}"
    assert sorted(p.stem for p in (tmp / "plots").iterdir()) == sorted(ALL_PLOTS)


def test_default_outdir_is_beside_the_file(tmp):
    run = tmp / "swing_run.h5"
    write_run(run, states=False, modal=False)
    run_plot(run)
    outdir = tmp / "swing_run_plots"
    for name in STEP_PLOTS:
        check_png(outdir / f"{name}.png")


def test_missing_groups_are_skipped(tmp):
    run = tmp / "layout_only.h5"
    write_run(run, steps=False, sensors=False, states=False, modal=False)
    out = run_plot(run, "-o", tmp / "none")
    assert not (tmp / "none").exists() or not any((tmp / "none").iterdir()), "plots from missing data"
    assert "nothing to plot" in out and "skipped energy" in out, out


def test_tip_height_falls_back_to_the_last_beam_node(tmp):
    run = tmp / "no_sensors.h5"
    write_run(run, sensors=False, steps=False)
    out = run_plot(run, "-o", tmp / "plots")
    for name in ("tip_vertical_position", "boom_shape", "modal_frequencies"):
        check_png(tmp / "plots" / f"{name}.png")
    assert "skipped sensor positions" in out, out


def test_static_run_plots(tmp):
    run = tmp / "static.h5"  # time holds the load factor; zero violation cannot go on a log axis
    write_run(run, analysis="static")
    with h5py.File(run, "a") as f:
        f["steps/constraint_violation"][...] = 0.0
    out = run_plot(run, "-o", tmp / "plots")
    for name in ALL_PLOTS:
        if name != "constraint_violation":
            check_png(tmp / "plots" / f"{name}.png")
    assert "skipped constraint violation" in out, out


def test_unreadable_file_is_an_error(tmp):
    bad = tmp / "bad.h5"
    bad.write_text("not hdf5")
    result = subprocess.run([sys.executable, str(PLOT_RUN), str(bad)], capture_output=True, text=True)
    assert result.returncode != 0 and "bad.h5" in result.stderr, result.stderr


def test_reader_follows_the_layout(tmp):
    run = tmp / "reader.h5"
    write_run(run)
    with boomdyn_h5.open_run(run) as f:
        assert boomdyn_h5.scene_name(f) == "swinging test beam"
        assert boomdyn_h5.attributes(f)["mpi_ranks"] == 1
        layout = boomdyn_h5.load_layout(f)
        assert (layout.nq, layout.nlambda) == (8, 3)
        assert [c.name for c in layout.constraints] == ["base pin", "luffing drive"]
        assert layout.constraints[1].first_row == 2
        boom = layout.body("boom")
        assert boom.is_beam and (boom.first, boom.count) == (0, 8)
        states = boomdyn_h5.load_states(f)
        nodes = boom.node_positions(states["q"])
        assert nodes.shape == (len(states["time"]), 2, 2)
        t = states["time"][1]
        assert np.allclose(nodes[1, 1], LENGTH * np.array([np.cos(angle(t)), np.sin(angle(t))]))
        steps = boomdyn_h5.load_steps(f)
        assert steps["energy"].shape == (200, 4) and steps["newton_iterations"].dtype.kind == "i"
        assert set(boomdyn_h5.load_sensors(f)) == {"tip", "mid"}
        assert boomdyn_h5.load_modal(f)["state_time"] == steps["time"][-1]
        assert boomdyn_h5.load_summary(f)["status"] == "completed"


def main():
    tests = [(name, test) for name, test in globals().items() if name.startswith("test_")]
    failed = 0
    for name, test in tests:
        with tempfile.TemporaryDirectory(prefix="plot_run_") as tmp:
            try:
                test(Path(tmp))
                print(f"PASS {name}")
            except Exception:  # a failure of one test must not stop the others
                failed += 1
                print(f"FAIL {name}")
                traceback.print_exc()
    print(f"{len(tests) - failed} passed, {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
