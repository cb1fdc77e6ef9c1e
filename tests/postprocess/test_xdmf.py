#!/usr/bin/env python3
"""ParaView output (issue 7): the XDMF file written beside a run's results is
read back with meshio (Debian's python3-meshio) and by following its own
dataset references, and the geometry and the fields (axial strain,
curvature, velocity) at every snapshot are checked against an independent
evaluation from /state/q and /state/v (cubic Hermite shape functions for
ANCF beams, the rigid-body formula for rigid booms).
Usage: test_xdmf.py BOOMDYN_EXECUTABLE SOURCE_DIR WORK_DIR"""
import os
import subprocess
import sys
import xml.etree.ElementTree as ET

import h5py
import meshio
import numpy as np
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import script_checks  # noqa: E402

boomdyn, source, work = sys.argv[1:4]
work = os.path.join(work, "test_output", "xdmf")
os.makedirs(work, exist_ok=True)
out = os.path.join(work, "run.h5")
subprocess.run([boomdyn, os.path.join(source, "inputs", "paper_rigid_booms.yaml"), "-o", out, "-boom_overwrite",
                "-boom_quiet", "-ts_max_time", "0.05", "-boom_state_interval", "0.01", "-boom_elements", "5"],
               check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
xmf = os.path.join(work, "run.xmf")
PER_ELEMENT = 4


def hermite(xi, l, d):
    """Cubic Hermite shape values S1..S4 (derivative order d with respect to x) at xi."""
    if d == 0:
        return np.array([1 - 3 * xi**2 + 2 * xi**3, l * (xi - 2 * xi**2 + xi**3), 3 * xi**2 - 2 * xi**3, l * (-xi**2 + xi**3)])
    if d == 1:
        return np.array([-6 * xi + 6 * xi**2, l * (1 - 4 * xi + 3 * xi**2), 6 * xi - 6 * xi**2, l * (-2 * xi + 3 * xi**2)]) / l
    return np.array([-6 + 12 * xi, l * (-4 + 6 * xi), 6 - 12 * xi, l * (-2 + 6 * xi)]) / l**2


def expected(q, v, layout, lengths):
    """Points, velocity, axial strain, curvature of every body, sampled as boomdyn does."""
    P, V, E, K = [], [], [], []
    for (first, n), L in zip(layout, lengths):
        if n == 3:  # rigid: (x_c, y_c, theta)
            for s in (0.0, L):
                a = s - L / 2
                d, perp = np.array([np.cos(q[first + 2]), np.sin(q[first + 2])]), np.array([-np.sin(q[first + 2]), np.cos(q[first + 2])])
                P.append(q[first:first + 2] + a * d)
                V.append(v[first:first + 2] + a * v[first + 2] * perp)
                E.append(0.0), K.append(0.0)
            continue
        ne = n // 4 - 1
        l = L / ne
        m = ne * PER_ELEMENT + 1
        for k in range(m):
            s = L * k / (m - 1)
            el = min(int(np.floor(s / l)), ne - 1)
            xi = (s - el * l) / l
            e, ev = q[first + 4 * el: first + 4 * el + 8].reshape(4, 2), v[first + 4 * el: first + 4 * el + 8].reshape(4, 2)
            r, r1, r2 = (hermite(xi, l, d) @ e for d in (0, 1, 2))
            P.append(r), V.append(hermite(xi, l, 0) @ ev)
            E.append(0.5 * (r1 @ r1 - 1)), K.append((r1[0] * r2[1] - r1[1] * r2[0]) / (r1 @ r1))
    return np.array(P), np.array(V), np.array(E), np.array(K)


with h5py.File(out) as f:
    layout = list(zip(f["layout/body_first_coordinate"][()], f["layout/body_num_coordinates"][()]))
    times, Q, Vs = f["state/time"][()], f["state/q"][()], f["state/v"][()]
lengths = [2.0, 2.0, 2.0]  # the paper booms

checks = []
with meshio.xdmf.TimeSeriesReader(xmf) as reader:
    points, cells = reader.read_points_cells()
    checks.append((reader.num_steps == len(times), "one XDMF grid per state snapshot (%d)" % reader.num_steps))
    P0, _, _, _ = expected(Q[0], Vs[0], layout, lengths)
    checks.append((np.abs(points[:, :2] - P0).max() < 1e-12, "meshio: geometry of the first snapshot"))
    checks.append((cells[0].type == "line" and len(cells[0].data) == len(P0) - len(layout), "line segments within each boom"))
    worst = {"velocity": 0.0, "axial_strain": 0.0, "curvature": 0.0, "time": 0.0}
    for k in range(reader.num_steps):
        t, pd, _ = reader.read_data(k)
        P, V, E, K = expected(Q[k], Vs[k], layout, lengths)
        worst["time"] = max(worst["time"], abs(t - times[k]))
        worst["velocity"] = max(worst["velocity"], np.abs(pd["velocity"][:, :2] - V).max())
        worst["axial_strain"] = max(worst["axial_strain"], np.abs(pd["axial_strain"] - E).max())
        worst["curvature"] = max(worst["curvature"], np.abs(pd["curvature"] - K).max())
    print("largest differences over %d snapshots: %s" % (reader.num_steps, ", ".join("%s %.1e" % kv for kv in worst.items())))
    checks.append((worst["time"] < 1e-12, "times"))
    checks.append((worst["velocity"] < 1e-10, "velocity field"))
    checks.append((worst["axial_strain"] < 1e-12, "axial strain field"))
    checks.append((worst["curvature"] < 1e-9, "curvature field"))
# The geometry moves: follow each grid's Geometry reference to its dataset.
grids = ET.parse(xmf).getroot().find("Domain/Grid").findall("Grid")
worst_geometry, moved = 0.0, 0.0
with h5py.File(out) as f:
    for k, g in enumerate(grids):
        ref = g.find("Geometry/DataItem").text.strip().split(":", 1)[1]
        P, _, _, _ = expected(Q[k], Vs[k], layout, lengths)
        worst_geometry = max(worst_geometry, np.abs(f[ref][()][:, :2] - P).max())
        moved = max(moved, np.abs(P - expected(Q[0], Vs[0], layout, lengths)[0]).max())
print("geometry: largest difference %.1e m over all snapshots; the booms moved up to %.1e m" % (worst_geometry, moved))
checks.append((worst_geometry < 1e-12 and moved > 1e-5, "geometry of every snapshot (and it moves)"))
checks.append((any(len(P) > 2 * 6 for P in [expected(Q[0], Vs[0], layout, lengths)[0]]), "beams sampled inside elements"))
sys.exit(script_checks.report(checks))
