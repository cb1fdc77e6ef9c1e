#!/usr/bin/env python3
"""Output of a spatial scene (docs/output.md): inputs/spatial_boom_side_load.yaml
with a tip point sensor and three frame sensors runs, and its results file,
XDMF file and plots are checked against independent evaluations from
/state/q: 3-D sensor series, the sections of the frame sensors (triad
orthonormal, d1 along the beam's slope, the twist recomputed from the triad
by the smallest rotation, and its size against T L / GJ), the sampled booms
of /paraview (node points, d2 and the twist beside the frames), the XDMF
file (meshio and its own dataset references), and postprocess/plot_run.py's
spatial plots and boomdyn_h5's spatial readers.
Usage: test_spatial_output.py BOOMDYN_EXECUTABLE SOURCE_DIR WORK_DIR"""
import os
import subprocess
import sys
import xml.etree.ElementTree as ET

import h5py
import matplotlib.image as mpimg
import meshio
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(HERE)), "postprocess"))
import boomdyn_h5  # noqa: E402
import script_checks  # noqa: E402

boomdyn, source, work = sys.argv[1:4]
work = os.path.join(work, "test_output", "spatial_output")
os.makedirs(work, exist_ok=True)
scene = os.path.join(work, "side_load.yaml")
with open(os.path.join(source, "inputs", "spatial_boom_side_load.yaml")) as f:
    text = f.read()
assert "\noutput:\n" in text
with open(scene, "w") as f:
    f.write(text.replace("\noutput:\n", "\noutput:\n  sensors:\n    - {name: tip, body: boom, at: end}\n"
                         "  frames:\n    - {name: tip, body: boom, at: end}\n    - {name: root, body: boom, at: start}\n"
                         "    - {name: inside, body: boom, at: 1.3}\n"))
out = os.path.join(work, "run.h5")
subprocess.run([boomdyn, scene, "-o", out, "-boom_overwrite", "-boom_quiet"], check=True)

ELEMENTS, LENGTH, PER_ELEMENT = 8, 3.0, 4
# Box 200 x 150 x 6 mm (the scene's comment): Bredt's J, torque 1 kN m at the 3 m tip.
J = 2 * 0.006 * 0.15**2 * 0.2**2 / (0.15 + 0.2)
STATIC_TWIST = 1000.0 * LENGTH / (8.1e10 * J)

checks = []
check = checks.append


def twist_from_triad(initial, triad):
    """Angle about d1 from the initial d2, carried to d1 by the smallest rotation, to d2."""
    a, t = initial[:, 0], triad[:, 0]
    v, c = np.cross(a, t), a @ t
    vx = np.array([[0, -v[2], v[1]], [v[2], 0, -v[0]], [-v[1], v[0], 0]])
    b2 = (np.eye(3) + vx + vx @ vx / (1 + c)) @ initial[:, 1]
    b3 = np.cross(t, b2)
    return np.arctan2(triad[:, 1] @ b3, triad[:, 1] @ b2)


with h5py.File(out, "r") as f:
    check((int(f["layout"].attrs["dimension"]) == 3, "/layout dimension 3"))
    t = f["steps/time"][()]
    position, velocity = f["sensors/tip/position"][()], f["sensors/tip/velocity"][()]
    check((position.shape == (len(t), 3) and velocity.shape == (len(t), 3), "sensor series (n, 3)"))
    frames = {name: {k: f["frames"][name][k][()] for k in f["frames"][name]} for name in f["frames"]}
    check((set(frames) == {"tip", "root", "inside"}, "a /frames group per frame sensor"))
    tipframe = frames["tip"]
    check((tipframe["triad"].shape == (len(t), 9) and tipframe["twist"].shape == (len(t),)
           and tipframe["angular_velocity"].shape == (len(t), 3) and tipframe["strains"].shape == (len(t), 4),
           "frame series: triad (n, 9), twist (n), angular_velocity (n, 3), strains (n, 4)"))
    first = int(f["layout/body_first_coordinate"][0])
    times, Q, V = f["state/time"][()], f["state/q"][()], f["state/v"][()]
    tip_node = first + 7 * ELEMENTS
    rows = [int(np.argmin(abs(t - s))) for s in times]
    check((max(abs(t[rows] - times)) == 0, "every snapshot is a step row"))
    worst = {"position": 0.0, "velocity": 0.0, "d1": 0.0, "orthonormal": 0.0, "twist": 0.0, "paraview": 0.0,
             "d2": 0.0, "paraview twist": 0.0, "root twist": 0.0}
    for k, row in enumerate(rows):
        q, v = Q[k], V[k]
        worst["position"] = max(worst["position"], abs(position[row] - q[tip_node:tip_node + 3]).max())
        worst["velocity"] = max(worst["velocity"], abs(velocity[row] - v[tip_node:tip_node + 3]).max())
        R = tipframe["triad"][row].reshape(3, 3)
        slope = q[tip_node + 3:tip_node + 6]
        worst["d1"] = max(worst["d1"], abs(R[:, 0] - slope / np.linalg.norm(slope)).max())
        worst["orthonormal"] = max(worst["orthonormal"], abs(R.T @ R - np.eye(3)).max(), abs(np.linalg.det(R) - 1))
        worst["twist"] = max(worst["twist"], abs(twist_from_triad(np.eye(3), R) - tipframe["twist"][row]))
        g = f["paraview/%d" % k]
        points, d2, twist = g["points"][()], g["d2"][()], g["twist"][()]
        nodes = q[first:first + 7 * (ELEMENTS + 1)].reshape(ELEMENTS + 1, 7)[:, :3]
        worst["paraview"] = max(worst["paraview"], abs(points[::PER_ELEMENT][:ELEMENTS + 1] - nodes).max())
        tip_point = PER_ELEMENT * ELEMENTS  # the beam's last sample point
        worst["d2"] = max(worst["d2"], abs(d2[tip_point] - R[:, 1]).max())
        worst["paraview twist"] = max(worst["paraview twist"], abs(twist[tip_point] - tipframe["twist"][row]))
        worst["root twist"] = max(worst["root twist"], abs(twist[0]), abs(frames["root"]["twist"][row]))
    print("largest differences over %d snapshots: %s" % (len(rows), ", ".join("%s %.1e" % kv for kv in worst.items())))
    for key in worst:
        check((worst[key] < 1e-12, "%s (%.1e)" % (key, worst[key])))
    # The 1 kN m torque twists the tip about T L / GJ (the step response rings around it and the numerical
    # damping of rho_inf 0.8 at 9 steps per torsional period settles it).
    late = tipframe["twist"][t > 0.05]
    print("tip twist: mean %.4e rad over t > 0.05 s, largest %.4e rad; T L / GJ = %.4e rad"
          % (late.mean(), tipframe["twist"].max(), STATIC_TWIST))
    check((abs(late.mean() / STATIC_TWIST - 1) < 0.05, "tip twist about T L / GJ"))
    check((abs(frames["inside"]["twist"][t > 0.05].mean() / (STATIC_TWIST * 1.3 / LENGTH) - 1) < 0.05,
           "twist at s = 1.3 m about T s / GJ"))
    torsion = tipframe["strains"][t > 0.05, 1].mean()
    check((abs(torsion / (STATIC_TWIST / LENGTH) - 1) < 0.05, "torsion about T / GJ (%.4e 1/m)" % torsion))
    swing = abs(position[:, 1]).max()
    check((swing > 1e-4 and abs(position[:, 2]).max() > 1e-6, "the tip moves sideways (%.2e m) and sags" % swing))

# XDMF: every grid carries the section fields, with the sizes of their datasets.
xmf = os.path.join(work, "run.xmf")
grids = ET.parse(xmf).getroot().find("Domain/Grid").findall("Grid")
check((len(grids) == len(times), "one XDMF grid per snapshot (%d)" % len(grids)))
sizes_ok, names_ok = True, True
with h5py.File(out, "r") as f:
    for g in grids:
        attributes = {a.get("Name"): a for a in g.findall("Attribute")}
        names_ok &= set(attributes) == {"axial_strain", "curvature", "velocity", "twist", "torsion", "d2", "d3"}
        for name, a in attributes.items():
            item = a.find("DataItem")
            shape = f[item.text.strip().split(":", 1)[1]].shape
            sizes_ok &= tuple(int(n) for n in item.get("Dimensions").split()) == shape
            sizes_ok &= a.get("AttributeType") == ("Vector" if len(shape) == 2 else "Scalar")
check((names_ok, "XDMF attributes: axial_strain, curvature, velocity, twist, torsion, d2, d3"))
check((sizes_ok, "XDMF dimensions and attribute types match the datasets"))
with meshio.xdmf.TimeSeriesReader(xmf) as reader:
    points, cells = reader.read_points_cells()
    _, data, _ = reader.read_data(reader.num_steps - 1)
    d2, d3 = data["d2"], data["d3"]
    unit = max(abs(np.linalg.norm(d2, axis=1) - 1).max(), abs(np.einsum("ij,ij->i", d2, d3)).max())
    check((points.shape[1] == 3 and cells[0].type == "line" and unit < 1e-12,
           "meshio reads the polylines, d2 and d3 unit and normal to each other (%.1e)" % unit))

# The readers and the plots.
with boomdyn_h5.open_run(out) as f:
    layout = boomdyn_h5.load_layout(f)
    beam = layout.bodies[0]
    check((layout.dimension == 3 and beam.is_beam and beam.node_positions(Q).shape == (len(times), ELEMENTS + 1, 3),
           "boomdyn_h5: spatial layout, beam nodes (m, nodes, 3)"))
    loaded = boomdyn_h5.load_frames(f)["tip"]
    check((loaded["triad"].shape == (len(t), 3, 3) and np.array_equal(loaded["triad"][:, :, 1], tipframe["triad"][:, 1::3]),
           "boomdyn_h5.load_frames: triad (n, 3, 3), column j = d_(j+1)"))
    polylines = boomdyn_h5.load_polylines(f)
    check((len(polylines) == len(times) and len(polylines[0][1]) == 1
           and polylines[0][1][0].shape == (ELEMENTS * PER_ELEMENT + 1, 3), "boomdyn_h5.load_polylines: one boom"))
plots = os.path.join(work, "plots")
result = subprocess.run([sys.executable, os.path.join(source, "postprocess", "plot_run.py"), out, "-o", plots],
                        capture_output=True, text=True)
check((result.returncode == 0, "plot_run.py runs on a spatial file"))
for name in ("sensor_positions", "tip_vertical_position", "boom_shape_3d", "section_twist", "energy"):
    path = os.path.join(plots, name + ".png")
    ok = os.path.isfile(path) and np.ptp(mpimg.imread(path)) > 0
    check((ok, "plot %s.png" % name))
check((not os.path.exists(os.path.join(plots, "boom_shape.png")), "no planar boom_shape.png for a spatial file"))
sys.exit(script_checks.report(checks))
