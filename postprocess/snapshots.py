#!/usr/bin/env python3
"""Boom shapes at several times (one PNG) and, with --animate, an animation
of the whole run (MP4 through ffmpeg when `ffmpeg` is on the PATH, else an
animated GIF through Pillow).

  /usr/bin/python3 postprocess/snapshots.py RUN.h5 [-o OUTDIR] [--times t1 t2 ...] [--animate]

Shapes come from the full-state snapshots (/state/q; their spacing is the
scene's output.state_interval). Beams are drawn as poly-lines sampled inside
every element with the ANCF (cubic Hermite) shape functions, which pass
through the nodes; rigid bodies as straight segments. Axes are equal (true
scale). Writes OUTDIR/<RUN stem>_snapshots.png and, with --animate,
OUTDIR/<RUN stem>_animation.mp4 or .gif; OUTDIR defaults to RUN's folder.
"""
import argparse
import os
import shutil
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.lines  # noqa: E402
import matplotlib.transforms  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import boomdyn_h5  # noqa: E402
import centerline  # noqa: E402

SAMPLES_PER_ELEMENT = 8
DEFAULT_COUNT = 6  # snapshots in the PNG when no --times are given


class Shapes:
    """What is needed to draw a run's bodies: scene name, body geometry, the /state snapshots."""

    def __init__(self, path):
        with boomdyn_h5.open_run(path) as f:
            self.scene = boomdyn_h5.scene_name(f)
            layout = boomdyn_h5.load_layout(f)
            states = boomdyn_h5.load_states(f)
            if layout is None or states is None:
                raise SystemExit("%s: no /layout or no /state snapshots to draw" % path)
            lengths = boomdyn_h5.body_lengths(f)
        self.path = path
        self.time = states["time"]
        self.q = states["q"]
        # (name, first coordinate, number of coordinates, length); rigid bodies have 3 coordinates.
        self.bodies = [(b.name, b.first, b.count, lengths[b.name]) for b in layout.bodies]

    def is_rigid(self, body):
        return body[2] == 3

    def polylines(self, index, per_element=SAMPLES_PER_ELEMENT):
        """[(body name, (N, 2) points)] of snapshot `index`: beams sampled inside the elements, rigid bodies as 2 points."""
        q = self.q[index]
        return [(name, centerline.polyline(q, first, count, length, per_element))
                for name, first, count, length in self.bodies]

    def indices(self, times):
        """Snapshot rows nearest to the requested times (sorted, without repeats)."""
        return sorted(set(int(np.argmin(np.abs(self.time - t))) for t in times))

    def default_indices(self, count=DEFAULT_COUNT):
        return sorted(set(np.linspace(0, len(self.time) - 1, min(count, len(self.time))).round().astype(int).tolist()))

    def limits(self, indices, margin=0.05):
        """(xmin, xmax, ymin, ymax) holding every body at the given snapshots, with a margin."""
        pts = np.concatenate([p for i in indices for _, p in self.polylines(i, per_element=2)])
        lo, hi = pts.min(axis=0), pts.max(axis=0)
        pad = margin * max(hi - lo) + 1e-9
        return lo[0] - pad, hi[0] + pad, lo[1] - pad, hi[1] + pad


def fitted_figsize(limits, max_width=7.0, max_height=6.5, margin_w=1.2, margin_h=1.2, min_height=2.0):
    """Figure size (inches) whose equal-axes box fits the data with little blank space:
    the axes box gets the data's aspect within max_width x max_height, plus margins for labels."""
    xmin, xmax, ymin, ymax = limits
    ratio = (ymax - ymin) / max(xmax - xmin, 1e-12)
    box_w = max_width - margin_w
    box_h = box_w * ratio
    if box_h > max_height - margin_h:  # tall: the height limits, the width follows
        box_h = max_height - margin_h
        box_w = box_h / ratio
    return max(box_w + margin_w, 3.5), max(box_h + margin_h, min_height)


def set_equal_limits(ax, limits):
    """Equal axes showing `limits`: the box shrinks in the direction with less data."""
    xmin, xmax, ymin, ymax = limits
    ax.set_xlim(xmin, xmax)
    ax.set_ylim(ymin, ymax)
    ax.set_aspect("equal", adjustable="box")


def line_widths(count):
    """Outer (first) bodies drawn thicker, like the sections of a telescope."""
    if count == 1:
        return [2.5]
    return [1.5 + 3.0 * (count - 1 - k) / (count - 1) for k in range(count)]


def draw(ax, shapes, indices, colors=None, per_element=SAMPLES_PER_ELEMENT, legend=True):
    """Draws the bodies at the given snapshots into `ax`, one colour per time; returns the legend handles
    (one line per time, then one grey line per body showing its width)."""
    if colors is None:
        colors = plt.cm.viridis(np.linspace(0, 0.9, len(indices)))
    widths = line_widths(len(shapes.bodies))
    handles = []
    for color, index in zip(colors, indices):
        for k, (name, points) in enumerate(shapes.polylines(index, per_element)):
            line, = ax.plot(points[:, 0], points[:, 1], "-", color=color, lw=widths[k], solid_capstyle="butt",
                            label="t = %.2f s" % shapes.time[index])
            if k == 0:
                handles.append(line)
    for (name, _, count, _), w in zip(shapes.bodies, widths):
        handles.append(matplotlib.lines.Line2D([], [], color="0.5", lw=w, label=name + (" (rigid)" if count == 3 else "")))
    set_equal_limits(ax, shapes.limits(indices))
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.grid(True, alpha=0.4)
    return handles


def plot_snapshots(shapes, out, times=None, title=None, dpi=100):
    """PNG of the boom at the snapshots nearest `times` (default: evenly over the run). Returns `out`."""
    if not isinstance(shapes, Shapes):
        shapes = Shapes(shapes)
    indices = shapes.indices(times) if times else shapes.default_indices()
    limits = shapes.limits(indices)
    w, h = fitted_figsize(limits)
    flat = h < 3.5
    entries = len(indices) + len(shapes.bodies)
    if flat:  # legend below the axes
        fig, ax = plt.subplots(figsize=(max(w, 8.0), h + 0.25 * np.ceil(entries / 4) + 0.4))
    else:  # legend to the right
        fig, ax = plt.subplots(figsize=(w + 1.8, h))
    handles = draw(ax, shapes, indices)
    ax.set_title(title or "%s: boom shape at %d times (true scale)" % (shapes.scene, len(indices)), fontsize=10)
    if flat:  # below the x label: 0.5 inch under the axes
        below = ax.transAxes + matplotlib.transforms.ScaledTranslation(0, -0.5, fig.dpi_scale_trans)
        ax.legend(handles=handles, fontsize=8, ncol=4, loc="upper center", bbox_to_anchor=(0.5, 0.0),
                  bbox_transform=below)
        fig.tight_layout()
    else:
        ax.legend(handles=handles, fontsize=8, loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0.0)
        fig.tight_layout()
    fig.savefig(out, dpi=dpi, bbox_inches="tight", pad_inches=0.1)  # equal axes leave blank space: crop it
    plt.close(fig)
    return out


def animate(shapes, out_base, max_frames=150, fps=20, dpi=80):
    """Animation of the run, at most `max_frames` snapshots evenly spread.

    Writes out_base + ".mp4" (ffmpeg on the PATH) or else out_base + ".gif"
    (Pillow). Returns the path written."""
    from matplotlib.animation import FFMpegWriter, FuncAnimation, PillowWriter
    if not isinstance(shapes, Shapes):
        shapes = Shapes(shapes)
    n = len(shapes.time)
    frames = np.unique(np.linspace(0, n - 1, min(n, max_frames)).round().astype(int))
    limits = shapes.limits(frames)
    fig, ax = plt.subplots(figsize=fitted_figsize(limits))
    set_equal_limits(ax, limits)
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.grid(True, alpha=0.4)
    widths = line_widths(len(shapes.bodies))
    colors = plt.cm.tab10(np.arange(len(shapes.bodies)) % 10)
    lines = [ax.plot([], [], "-", lw=w, color=c, solid_capstyle="butt",
                     label=name + (" (rigid)" if count == 3 else ""))[0]
             for (name, _, count, _), w, c in zip(shapes.bodies, widths, colors)]
    # Path of the end of the last body (the tip), up to the current frame.
    tip = np.array([shapes.polylines(i, per_element=1)[-1][1][-1] for i in frames])
    trail, = ax.plot([], [], ":", color="0.4", lw=1, label="tip path")
    ax.legend(fontsize=8, loc="upper left")
    title = ax.set_title("")

    def update(k):
        index = frames[k]
        for line, (_, points) in zip(lines, shapes.polylines(index)):
            line.set_data(points[:, 0], points[:, 1])
        trail.set_data(tip[:k + 1, 0], tip[:k + 1, 1])
        title.set_text("%s: frame %d/%d, t = %.2f s" % (shapes.scene, k + 1, len(frames), shapes.time[index]))
        return lines + [trail, title]

    anim = FuncAnimation(fig, update, frames=len(frames), blit=False)
    if shutil.which("ffmpeg"):
        out, writer = out_base + ".mp4", FFMpegWriter(fps=fps)
    else:
        out, writer = out_base + ".gif", PillowWriter(fps=fps)
    anim.save(out, writer=writer, dpi=dpi)
    plt.close(fig)
    return out


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("run", help="results file (.h5)")
    p.add_argument("-o", "--outdir", help="folder for the PNG and animation (default: RUN's folder)")
    p.add_argument("--times", type=float, nargs="+", help="times [s] of the snapshots (nearest /state rows)")
    p.add_argument("--animate", action="store_true", help="also write an animation (MP4 with ffmpeg, else GIF)")
    p.add_argument("--max-frames", type=int, default=150, help="frames of the animation (default 150)")
    p.add_argument("--fps", type=float, default=20, help="frames per second of the animation (default 20)")
    a = p.parse_args(argv)
    outdir = a.outdir or os.path.dirname(os.path.abspath(a.run))
    os.makedirs(outdir, exist_ok=True)
    stem = os.path.join(outdir, os.path.splitext(os.path.basename(a.run))[0])
    shapes = Shapes(a.run)
    print("wrote %s" % plot_snapshots(shapes, stem + "_snapshots.png", a.times))
    if a.animate:
        print("wrote %s" % animate(shapes, stem + "_animation", a.max_frames, a.fps))
    return 0


if __name__ == "__main__":
    sys.exit(main())
