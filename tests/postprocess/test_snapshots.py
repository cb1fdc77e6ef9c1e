#!/usr/bin/env python3
"""postprocess/snapshots.py on short runs of the paper extraction scene (three
flexible booms) and of the rigid-booms scene (booms 1-2 rigid): the PNG and the
animation (MP4 with ffmpeg on the PATH, else GIF) exist and are real pictures,
and the drawn poly-lines are the ANCF centerlines: through the nodes at the
nodes, the shape functions between them, straight segments of the right
length for rigid bodies.
Usage: test_snapshots.py BOOMDYN_EXECUTABLE SOURCE_DIR WORK_DIR"""
import os
import subprocess
import sys

import matplotlib
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import script_checks  # noqa: E402

matplotlib.use("Agg")
import matplotlib.image  # noqa: E402
import numpy as np  # noqa: E402

boomdyn, source, work = sys.argv[1:4]
sys.path.insert(0, os.path.join(source, "postprocess"))
import boomdyn_h5  # noqa: E402
import centerline  # noqa: E402
import snapshots  # noqa: E402

OPTIONS = ["-boom_overwrite", "-boom_quiet", "-ts_max_time", "0.3", "-boom_elements", "4"]
results = []


check = script_checks.checker(results)


def run(scene, name):
    out = os.path.join(work, name + ".h5")
    subprocess.run([boomdyn, os.path.join(source, "inputs", scene), "-o", out] + OPTIONS, check=True,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return out


def picture_ok(path):
    """Exists, non-empty, and not one uniform colour (PNG via matplotlib, GIF via Pillow: several frames)."""
    if not os.path.isfile(path) or os.path.getsize(path) == 0:
        return False
    if path.endswith(".mp4"):
        return os.path.getsize(path) > 1000
    if path.endswith(".gif"):
        from PIL import Image
        with Image.open(path) as im:
            frames = getattr(im, "n_frames", 1)
            im.seek(frames // 2)
            pixels = np.asarray(im.convert("RGB"), dtype=float)
        return frames > 1 and pixels.std() > 0
    return float(matplotlib.image.imread(path).std()) > 0


def main():
    flexible = run("paper_extraction.yaml", "snapshots_flexible")
    rigid = run("paper_rigid_booms.yaml", "snapshots_rigid")
    outdir = os.path.join(work, "snapshots_out")

    # The command line, with --animate and with --times.
    p = subprocess.run([sys.executable, os.path.join(source, "postprocess", "snapshots.py"), flexible, "-o", outdir,
                        "--animate", "--max-frames", "12"], capture_output=True, text=True)
    check(p.returncode == 0, "snapshots.py --animate exits with 0" + ("" if p.returncode == 0 else ": " + p.stderr))
    written = [line.split(" ", 1)[1] for line in p.stdout.splitlines() if line.startswith("wrote ")]
    png = [w for w in written if w.endswith(".png")]
    anim = [w for w in written if w.endswith((".gif", ".mp4"))]
    check(len(png) == 1 and picture_ok(png[0]), "snapshot PNG written and not uniform: %s" % png)
    check(len(anim) == 1 and picture_ok(anim[0]), "animation written and not uniform: %s" % anim)
    p = subprocess.run([sys.executable, os.path.join(source, "postprocess", "snapshots.py"), rigid, "-o", outdir,
                        "--times", "0", "0.15", "0.3"], capture_output=True, text=True)
    png = os.path.join(outdir, "snapshots_rigid_snapshots.png")
    check(p.returncode == 0 and picture_ok(png), "snapshots.py --times on the rigid-booms run")

    # The poly-lines through the nodes, and the shape functions between them.
    shapes = snapshots.Shapes(flexible)
    with boomdyn_h5.open_run(flexible) as f:
        layout = boomdyn_h5.load_layout(f)
    per = snapshots.SAMPLES_PER_ELEMENT
    worst_node = worst_inside = 0.0
    bent = 0.0
    for i in range(len(shapes.time)):
        for (name, points), body in zip(shapes.polylines(i), layout.bodies):
            nodes = body.node_positions(shapes.q[i])
            check_shape = len(points) == (len(nodes) - 1) * per + 1
            if not check_shape:
                check(False, "%s: %d points for %d nodes" % (name, len(points), len(nodes)))
                continue
            worst_node = max(worst_node, np.abs(points[::per] - nodes).max())
            length = shapes.bodies[[b[0] for b in shapes.bodies].index(name)][3]
            s = np.linspace(0, length, len(points))
            scalar = np.array([centerline.position(shapes.q[i], body.first, body.count, length, x) for x in s])
            worst_inside = max(worst_inside, np.abs(points - scalar).max())
            # Distance of the mid-element samples from the chord between the nodes: the curve is not straight.
            mid = points[per // 2::per]
            chord = 0.5 * (nodes[:-1] + nodes[1:])
            bent = max(bent, np.abs(mid - chord).max())
    check(worst_node <= 1e-12, "poly-lines pass through the nodal positions (largest difference %.1e m)" % worst_node)
    check(worst_inside <= 1e-12, "samples between the nodes are the Hermite interpolation (largest difference "
          "from centerline.position %.1e m)" % worst_inside)
    check(bent > 1e-6, "samples between the nodes leave the chord (largest %.1e m): the elements are drawn curved"
          % bent)

    rigid_shapes = snapshots.Shapes(rigid)
    lines = dict(rigid_shapes.polylines(len(rigid_shapes.time) - 1))
    ok = all(len(lines[b]) == 2 and abs(np.linalg.norm(lines[b][1] - lines[b][0]) - 2.0) < 1e-12
             for b in ("boom1", "boom2"))
    check(ok, "rigid booms drawn as straight segments of their length (2 points, 2.0 m)")
    check(len(lines["boom3"]) == 4 * per + 1, "flexible boom 3 of the rigid-booms scene sampled inside its elements")


if __name__ == "__main__":
    sys.exit(script_checks.finish(main, results))
