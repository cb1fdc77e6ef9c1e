#!/usr/bin/env python3
"""Plots of one boomdyn run: python3 postprocess/plot_run.py RUN.h5 [-o OUTDIR]

Writes PNG files (sensor positions, tip height, solver effort, constraint
violation, energy, modal frequencies, boom shapes) into OUTDIR, by default
RUN's stem + "_plots" beside RUN. Plots whose data the file lacks are skipped,
so files of failed or partial runs still give what they can. Results of
spatial scenes (dimension: 3) give x, y, z sensor series, the booms in space
(boom_shape_3d) and the sections of their frame sensors (section_twist).
"""

import argparse
import sys
from pathlib import Path

try:
    import matplotlib
    matplotlib.use("Agg")  # files only, no display needed
    import matplotlib.ticker
    import matplotlib.pyplot as plt
    import numpy as np
    import boomdyn_h5
except ImportError as error:
    sys.exit(f"plot_run.py needs numpy, h5py and matplotlib ({error}); this Python is {sys.executable}. "
             "On Debian: apt-get install python3-h5py python3-matplotlib, and run it with /usr/bin/python3.")

SNAPSHOTS_SHOWN = 5  # boom shapes drawn, spread over the run
MIN_SHAPE_ASPECT = 0.05  # flatter boom-shape plots are stretched, not drawn to scale


def tip_sensor(sensors):
    """The sensor whose name says it is at the tip, if any."""
    return next((name for name in sensors if "tip" in name.lower()), None)


class Plotter:
    def __init__(self, f, outdir):
        self.outdir = Path(outdir)
        self.scene = boomdyn_h5.scene_name(f)
        self.static = boomdyn_h5.is_static(f)
        # Static runs store the load factor where dynamic runs store time.
        self.time_name = "load factor" if self.static else "time"
        self.time_axis = "load factor [-]" if self.static else "time [s]"
        self.time_unit = "" if self.static else " s"
        self.written = []

    def figure(self, rows=1, height=4.0):
        fig, axes = plt.subplots(rows, 1, figsize=(8, height * rows), sharex=rows > 1, squeeze=False)
        return fig, axes[:, 0]

    def save(self, fig, name, title):
        fig.suptitle(f"{self.scene}: {title}")
        fig.tight_layout()
        self.outdir.mkdir(parents=True, exist_ok=True)
        path = self.outdir / f"{name}.png"
        fig.savefig(path, dpi=120)
        plt.close(fig)
        self.written.append(path)

    @staticmethod
    def skip(what, why):
        print(f"skipped {what}: {why}")

    def sensor_positions(self, steps, sensors):
        if "time" not in steps or not any("position" in s for s in sensors.values()):
            return self.skip("sensor positions", "no /steps/time or /sensors/*/position")
        # x, y; spatial scenes' sensors also z.
        components = max(s["position"].shape[1] for s in sensors.values() if "position" in s)
        fig, axes = self.figure(rows=components, height=3.2)
        for name, series in sensors.items():
            if "position" in series:
                n = min(len(steps["time"]), len(series["position"]))
                for c, ax in enumerate(axes[:series["position"].shape[1]]):
                    ax.plot(steps["time"][:n], series["position"][:n, c], label=name)
        for ax, label in zip(axes, ("x [m]", "y [m]", "z [m]")):
            ax.set_ylabel(label)
            ax.grid(True)
            ax.legend(loc="best", fontsize="small")
        axes[-1].set_xlabel(self.time_axis)
        self.save(fig, "sensor_positions", "sensor positions")

    def tip_height(self, steps, sensors, layout, states):
        # The height is y in a planar scene, z in a spatial one.
        up = 2 if layout and layout.dimension == 3 else 1
        tip = tip_sensor(sensors)
        if tip and "time" in steps and "position" in sensors[tip] and sensors[tip]["position"].shape[1] > up:
            n = min(len(steps["time"]), len(sensors[tip]["position"]))
            t, y, source = steps["time"][:n], sensors[tip]["position"][:n, up], f"sensor '{tip}'"
        elif layout and states and any(b.is_beam for b in layout.bodies):
            # Without a tip sensor: the last node of the last beam, at the snapshots only.
            beam = [b for b in layout.bodies if b.is_beam][-1]
            t, y = states["time"], beam.node_positions(states["q"])[:, -1, up]
            source = f"last node of '{beam.name}'"
        else:
            return self.skip("tip height", "no sensor named *tip* and no beam snapshots in /state")
        fig, (ax,) = self.figure()
        ax.plot(t, y, marker="." if len(t) < 50 else None)
        ax.set_xlabel(self.time_axis)
        ax.set_ylabel("tip %s [m]" % "xyz"[up])
        ax.grid(True)
        self.save(fig, "tip_vertical_position", f"tip vertical position ({source})")

    def solver_effort(self, steps):
        if "time" not in steps or ("newton_iterations" not in steps and "dt" not in steps):
            return self.skip("solver effort", "no /steps/newton_iterations or /steps/dt")
        fig, (ax_it, ax_dt) = self.figure(rows=2, height=3.2)
        if "newton_iterations" in steps:
            ax_it.step(steps["time"], steps["newton_iterations"], where="post")
        ax_it.set_ylim(bottom=0)  # counts: from 0, in whole ticks
        ax_it.yaxis.set_major_locator(matplotlib.ticker.MaxNLocator(integer=True))
        ax_it.set_ylabel("Newton iterations [-]")
        if "dt" in steps:
            dt = steps["dt"]
            ax_dt.plot(steps["time"], dt)
            if dt.min() > 0 and dt.max() > 10 * dt.min():  # step cuts span decades
                ax_dt.set_yscale("log")
        ax_dt.set_ylabel("load-factor increment [-]" if self.static else "time step dt [s]")
        ax_dt.set_xlabel(self.time_axis)
        for ax in (ax_it, ax_dt):
            ax.grid(True)
        self.save(fig, "solver_effort", "Newton iterations and step size")

    def constraint_violation(self, steps):
        if "time" not in steps or "constraint_violation" not in steps:
            return self.skip("constraint violation", "no /steps/constraint_violation")
        violation = steps["constraint_violation"]
        positive = violation > 0
        if not positive.any():  # a log axis cannot show zeros
            return self.skip("constraint violation", "it is zero at every step")
        fig, (ax,) = self.figure()
        ax.semilogy(steps["time"][positive], violation[positive])
        ax.set_xlabel(self.time_axis)
        ax.set_ylabel("max |C| [m or -]")  # pin rows are lengths, angle rows are not
        ax.grid(True, which="both")
        self.save(fig, "constraint_violation", "constraint violation")

    def energy(self, steps):
        if "time" not in steps or "energy" not in steps:
            return self.skip("energy", "no /steps/energy")
        fig, (ax,) = self.figure()
        for column, label in enumerate(boomdyn_h5.ENERGY_COLUMNS):
            ax.plot(steps["time"], steps["energy"][:, column], label=label,
                    linestyle="--" if label == "total" else "-")
        ax.set_xlabel(self.time_axis)
        ax.set_ylabel("energy [J]")
        ax.grid(True)
        ax.legend(loc="best")
        self.save(fig, "energy", "energy")

    def modal_frequencies(self, modal):
        if modal is None:
            return self.skip("modal frequencies", "no /modal/frequencies_hz")
        frequencies = modal["frequencies_hz"]
        modes = np.arange(1, len(frequencies) + 1)
        fig, (ax,) = self.figure()
        bars = ax.bar(modes, frequencies)
        ax.bar_label(bars, fmt="%.3g", fontsize="small")
        ax.set_xticks(modes)
        ax.set_xlabel("mode [-]")
        ax.set_ylabel("frequency [Hz]")
        ax.grid(True, axis="y")
        when = "" if modal["state_time"] is None else f" at {self.time_name} {modal['state_time']:g}{self.time_unit}"
        self.save(fig, "modal_frequencies", f"natural frequencies{when}")

    def boom_shapes_3d(self, polylines, layout, states):
        """The booms in space (mplot3d) at up to SNAPSHOTS_SHOWN snapshots: the sampled axes of every body
        from /paraview, or else the beam nodes from /state/q."""
        if polylines:
            times, shapes = [p[0] for p in polylines], [p[1] for p in polylines]
        elif layout and states is not None and any(b.is_beam for b in layout.bodies):
            times = list(states["time"])
            shapes = [[b.node_positions(q) for b in layout.bodies if b.is_beam] for q in states["q"]]
        else:
            return self.skip("boom shapes in space", "no /paraview snapshots and no beams in /state/q")
        count = min(SNAPSHOTS_SHOWN, len(times))
        chosen = np.unique(np.linspace(0, len(times) - 1, count).round().astype(int))
        colors = plt.cm.viridis(np.linspace(0, 1, len(chosen)))
        fig = plt.figure(figsize=(8, 6))
        ax = fig.add_subplot(projection="3d")
        for color, index in zip(colors, chosen):
            label = f"{self.time_name} = {times[index]:g}{self.time_unit}"
            for k, line in enumerate(shapes[index]):
                ax.plot(line[:, 0], line[:, 1], line[:, 2], color=color, label=label if k == 0 else None)
        points = np.concatenate([line for index in chosen for line in shapes[index]])
        # Equal scales on the three axes (a straight boom stays straight), around the points' box.
        centre, half = points.mean(axis=0), max(np.ptp(points, axis=0).max() / 2, 1e-9)
        for axis, c in zip("xyz", centre):
            getattr(ax, f"set_{axis}lim")(c - half, c + half)
        ax.set_xlabel("x [m]")
        ax.set_ylabel("y [m]")
        ax.set_zlabel("z [m]")
        ax.legend(loc="best", fontsize="small")
        self.save(fig, "boom_shape_3d", "booms in space")

    def section_twist(self, steps, frames):
        """Twist and strains of the sections of a spatial scene's frame sensors (/frames)."""
        if "time" not in steps or not any("twist" in s for s in frames.values()):
            return self.skip("section twist", "no /frames/*/twist (frame sensors of a spatial scene)")
        fig, (ax_twist, ax_torsion, ax_bending) = self.figure(rows=3, height=3.0)
        for name, series in frames.items():
            n = min(len(steps["time"]), len(series.get("twist", [])))
            t = steps["time"][:n]
            ax_twist.plot(t, np.degrees(series["twist"][:n]), label=name)
            if "strains" in series:
                ax_torsion.plot(t, series["strains"][:n, 1], label=name)
                ax_bending.plot(t, np.hypot(series["strains"][:n, 2], series["strains"][:n, 3]), label=name)
        ax_twist.set_ylabel("twist [deg]")
        ax_torsion.set_ylabel("torsion [1/m]")
        ax_bending.set_ylabel("|curvature| [1/m]")
        ax_bending.set_xlabel(self.time_axis)
        for ax in (ax_twist, ax_torsion, ax_bending):
            ax.grid(True)
            ax.legend(loc="best", fontsize="small")
        self.save(fig, "section_twist", "sections of the frame sensors")

    def boom_shapes(self, layout, states):
        beams = [b for b in layout.bodies if b.is_beam] if layout else []
        if not beams or states is None:
            return self.skip("boom shapes", "no beams in /layout or no /state/q")
        count = min(SNAPSHOTS_SHOWN, len(states["time"]))
        chosen = np.unique(np.linspace(0, len(states["time"]) - 1, count).round().astype(int))
        colors = plt.cm.viridis(np.linspace(0, 1, len(chosen)))
        fig, (ax,) = self.figure(height=5.0)
        for color, index in zip(colors, chosen):
            label = f"{self.time_name} = {states['time'][index]:g}{self.time_unit}"
            for k, beam in enumerate(beams):
                xy = beam.node_positions(states["q"][index])
                ax.plot(xy[:, 0], xy[:, 1], marker="o", markersize=3, color=color, label=label if k == 0 else None)
        ax.set_xlabel("x [m]")
        ax.set_ylabel("y [m]")
        # True to scale unless that would flatten small deflections to a line.
        nodes = np.concatenate([b.node_positions(states["q"][chosen]).reshape(-1, 2) for b in beams])
        span_x, span_y = np.ptp(nodes, axis=0)
        to_scale = min(span_x, span_y) >= MIN_SHAPE_ASPECT * max(span_x, span_y)
        if to_scale:
            ax.set_aspect("equal", adjustable="datalim")
        ax.grid(True)
        ax.legend(loc="best", fontsize="small")
        scale = "" if to_scale else ", axes not to scale"
        self.save(fig, "boom_shape", f"boom shape (beam nodes joined by straight lines{scale})")


def _names(f, path):
    return [x.decode() if isinstance(x, bytes) else str(x) for x in f[path][()]] if path in f else []


def normal_forces(f):
    """{sliding joint: normal force per step (N)}: the channel
    joint_resultants/<joint>/normal_force (a rigid joint's lambda_n, a padded
    joint's pad force), else lambda_n, the second multiplier row of a rigid
    joint (a padded joint has one row only; its next row is another
    constraint's)."""
    joints = _names(f, "/layout/sliding_joint_names")
    channels = _names(f, "/layout/output_names")
    forces = {}
    for j in joints:
        channel = "joint_resultants/%s/normal_force" % j
        if channel in channels and "steps/outputs" in f:
            forces[j] = f["steps/outputs"][:, channels.index(channel)]
        elif "steps/lambda" in f:
            names = _names(f, "/layout/constraint_names")
            k = names.index(j)
            if f["layout/constraint_num_rows"][k] == 2:
                forces[j] = f["steps/lambda"][:, f["layout/constraint_first_row"][k] + 1]
    return forces


def joint_plots(plotter, f):
    """Moving-frame deflection, slack coordinates, normal contact forces and rope tension (when present)."""
    if "steps/time" not in f:
        return
    t = f["steps/time"][()]
    series = [
        ("frame_deflection", "/steps/frame_deflection", "/layout/frame_names", "deflection in the moving frame [m]",
         "tip deflection in the moving frame (paper Fig. 9)"),
        ("slack_coordinates", "/steps/slack", "/layout/sliding_joint_names", "arc-length coordinate s [m]",
         "slack coordinates of the sliding joints"),
        ("rope_tension", "/steps/rope_tension", "/layout/rope_names", "tension [N]",
         "rope force (positive: extension rope pulls; negative: retraction rope pulls)"),
    ]
    # Tension-only (elastic) ropes write their tensions as output channels
    # (`elastic_rope/<name>/tension` in /steps/outputs), not to /steps/rope_tension.
    channels = _names(f, "/layout/output_names")
    elastic = [k for k, c in enumerate(channels) if c.startswith("elastic_rope/") and c.endswith("/tension")]
    for name, path, names_path, ylabel, title in series:
        if name == "rope_tension" and elastic:
            outputs = f["steps/outputs"][()]
            data = outputs[:, elastic] if path not in f else np.hstack([f[path][()], outputs[:, elastic]])
            names = _names(f, names_path) + [channels[k].split("/")[1] for k in elastic]
            title = "rope tensions (elastic ropes pull only)" if path not in f else title
        elif path not in f:
            plotter.skip(name, "no " + path)
            continue
        else:
            data, names = f[path][()], _names(f, names_path)
        fig, (ax,) = plotter.figure()
        for k in range(data.shape[1]):
            ax.plot(t[: len(data)], data[:, k], label=names[k] if k < len(names) else str(k))
        ax.set_xlabel(plotter.time_axis)
        ax.set_ylabel(ylabel)
        ax.grid(True)
        ax.legend(loc="best", fontsize="small")
        plotter.save(fig, name, title)
    forces = normal_forces(f)
    if forces:
        fig, (ax,) = plotter.figure()
        for j, force in forces.items():
            ax.plot(t[: len(force)], force, label=j)
        ax.set_xlabel(plotter.time_axis)
        ax.set_ylabel("normal force [N]")
        ax.grid(True)
        ax.legend(loc="best", fontsize="small")
        plotter.save(fig, "contact_forces", "normal contact forces of the sliding joints")
    else:
        plotter.skip("contact forces", "no sliding joints")


def special_plots(plotter, run_path):
    """Frequency along the run (Fig. 7 style) and stick/slip bands (Fig. 5 style), when the run has them."""
    import plot_frequency
    import plot_stick_slip

    with boomdyn_h5.open_run(run_path) as f:
        has_tracking, has_friction = "tracking" in f, "steps/friction_slipping" in f
    for present, module, name in ((has_tracking, plot_frequency, "frequency"), (has_friction, plot_stick_slip, "stick_slip")):
        if not present:
            plotter.skip(name, "no data for it in this file")
            continue
        made = module.make_figure(run_path)
        fig = made[0] if isinstance(made, tuple) else made
        plotter.outdir.mkdir(parents=True, exist_ok=True)
        path = plotter.outdir / f"{name}.png"
        fig.savefig(path, dpi=120)
        plt.close(fig)
        plotter.written.append(path)


def plot_run(run_path, outdir=None):
    """Writes every plot the file has data for; returns the paths written."""
    run_path = Path(run_path)
    outdir = Path(outdir) if outdir else run_path.with_name(run_path.stem + "_plots")
    with boomdyn_h5.open_run(run_path) as f:
        plotter = Plotter(f, outdir)
        steps = boomdyn_h5.load_steps(f)
        sensors = boomdyn_h5.load_sensors(f)
        layout = boomdyn_h5.load_layout(f)
        states = boomdyn_h5.load_states(f)
        plotter.sensor_positions(steps, sensors)
        plotter.tip_height(steps, sensors, layout, states)
        plotter.solver_effort(steps)
        plotter.constraint_violation(steps)
        plotter.energy(steps)
        plotter.modal_frequencies(boomdyn_h5.load_modal(f))
        if layout and layout.dimension == 3:
            plotter.boom_shapes_3d(boomdyn_h5.load_polylines(f), layout, states)
            plotter.section_twist(steps, boomdyn_h5.load_frames(f))
        else:
            plotter.boom_shapes(layout, states)
        joint_plots(plotter, f)
    special_plots(plotter, run_path)
    for path in plotter.written:
        print(f"wrote {path}")
    return plotter.written


def main(argv=None):
    parser = argparse.ArgumentParser(description="Plot a boomdyn results file (layout: docs/output.md).")
    parser.add_argument("run", help="results file (.h5)")
    parser.add_argument("-o", "--outdir", help="directory for the PNG files (default: RUN stem + '_plots' beside RUN)")
    args = parser.parse_args(argv)
    try:
        written = plot_run(args.run, args.outdir)
    except OSError as error:  # h5py reports unreadable files as OSError
        sys.exit(f"plot_run.py: cannot read {args.run}: {error}")
    if not written:
        print(f"nothing to plot in {args.run}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
