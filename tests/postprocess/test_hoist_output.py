#!/usr/bin/env python3
"""Hoisting output (issue 16, items 3 and 4) of a real run: a 1 t payload on
an elastic rope from a cantilever's root over a pulley at its tip (the scene
of tests/verification/test_payload_modes.cpp), static start, pushed sideways
and released, 6.5 s with tracking every 0.1 s. Checks:
  - XDMF: RUN.ropes.xmf beside RUN.xmf holds one rope grid per snapshot, and every snapshot's rope polyline runs through the rope's
    material points: the root (0, 0), the tip sensor and the hook sensor of
    that time (to 1e-12 m);
  - /summary design numbers: static tension = the tension at t = 0
    (m g sqrt(1 + (a/l)^2) under the push m g a / l, to 1e-9), peak and
    dynamic factor = max and max / first of the tension column, the root
    moment at t = 0 = m g L + rhoA g L^2 / 2 - F delta (the push F at the tip
    deflected by delta; to 2e-6);
  - plot_hoist.py: writes the figure; the swing frequency from its zero
    crossings (first to last) agrees with the mean tracked pendulum
    frequency within 1e-3, and with sqrt(g / l) / 2 pi within 1e-3 (l = 1 m).
Usage: test_hoist_output.py BOOMDYN_EXECUTABLE SOURCE_DIR WORK_DIR"""
import os
import subprocess
import sys
import xml.etree.ElementTree as ET

import h5py
import numpy as np

boomdyn, source, work = sys.argv[1:4]
sys.path.insert(0, os.path.join(source, "postprocess"))
import plot_hoist  # noqa: E402

work = os.path.join(work, "test_output", "hoist_output")
os.makedirs(work, exist_ok=True)
g, m, L, l, rhoA = 9.81, 1000.0, 2.0, 1.0, 7850 * 6.944e-3
scene = os.path.join(work, "boom_payload.yaml")
with open(scene, "w") as f:
    f.write(f"""name: boom-payload
analysis: dynamic
gravity: [0, -9.81]
bodies:
  - {{name: boom, length: 2.0, elements: 8, section: {{E: 2.1e11, A: 6.944e-3, I: 6.395214e-5, rho: 7850}}}}
  - {{name: payload, type: rigid, length: 0.2, origin: [1.9, -1.0], section: {{rhoA: 5000}}}}
constraints:
  - {{type: clamp, name: root, body: boom, at: start}}
  - {{type: angle_drive, body: payload, at: 0.1, angle: 0}}
  - {{type: elastic_rope, name: hoist, from: boom, from_at: 0.0, pulley: boom, pulley_at: end, to: payload, to_at: 0.1, EA: 2.0e7, pretension: 9810}}
loads:
  - {{type: point_force, body: payload, at: 0.1, force: [{m * g * 0.05 / l}, 0], scale: {{type: ramp, t0: 0, t1: 0.01, from: 1, to: 0}}}}
dynamic: {{t_end: 6.5, dt: 2.0e-3, rho_inf: 0.8, initial: static}}
tracking: {{interval: 0.1, count: 4}}
output:
  state_interval: 0.5
  sensors:
    - {{name: tip, body: boom, at: end}}
    - {{name: hook, body: payload, at: 0.1}}
""")
out = os.path.join(work, "run.h5")
subprocess.run([boomdyn, scene, "-o", out, "-boom_overwrite", "-boom_quiet"], check=True)
failures = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        failures.append(what)


# XDMF: the ropes collection and its geometry.
root = ET.parse(os.path.join(work, "run.ropes.xmf")).getroot()
collections = {grid.get("Name"): grid for grid in root.find("Domain").findall("Grid")}
check(list(collections) == ["boom-payload ropes"], f"run.ropes.xmf: one temporal collection {list(collections)}")
collections["ropes"] = collections.get("boom-payload ropes")
import meshio  # noqa: E402  (Debian's python3-meshio, as tests/postprocess/test_xdmf.py)
with meshio.xdmf.TimeSeriesReader(os.path.join(work, "run.ropes.xmf")) as reader:
    mesh_points, _ = reader.read_points_cells()
check(mesh_points.shape == (3, 3), f"meshio reads run.ropes.xmf: {mesh_points.shape[0]} rope points")
with h5py.File(out, "r") as f:
    steps_t = f["steps/time"][()]
    tip, hook = f["sensors/tip/position"][()], f["sensors/hook/position"][()]
    delta = -tip[0, 1]  # static tip deflection
    snapshots = [k for k in f["paraview"] if k.isdigit()]
    grids = collections["ropes"].findall("Grid") if "ropes" in collections else []
    check(len(grids) == len(snapshots) >= 9, f"{len(grids)} rope grids for {len(snapshots)} snapshots")
    check(f["paraview/rope_segments"][()].tolist() == [[0, 1], [1, 2]], "rope segments: root-tip, tip-hook")
    worst = 0.0
    for grid in grids:
        t = float(grid.find("Time").get("Value"))
        ref = grid.find("Geometry/DataItem").text.split(":", 1)[1]
        pts = f[ref][()]
        row = int(np.argmin(np.abs(steps_t - t)))
        expected = np.array([[0.0, 0.0], tip[row], hook[row]])
        worst = max(worst, float(np.max(np.abs(pts[:, :2] - expected))))
    check(worst < 1e-12, f"rope polylines through root, tip and hook at every snapshot (max deviation {worst:.1e} m)")
    summary = dict(f["summary"].attrs)
    names = [n.decode() for n in f["layout/output_names"][()]]
    tension = f["steps/outputs"][:, names.index("elastic_rope/hoist/tension")]
p = "design.elastic_rope.hoist."
F = m * g * 0.05 / l
T_s = m * g * np.sqrt(1 + (0.05 / l) ** 2)
check(abs(summary[p + "static_tension_N"] - T_s) < 1e-9 * T_s, f"static tension {summary[p + 'static_tension_N']:.6f} N = {T_s:.6f}")
check(summary[p + "static_tension_N"] == tension[0], "static tension = tension at t = 0")
check(summary[p + "peak_tension_N"] == tension.max(), f"peak tension {tension.max():.3f} N = max of the column")
check(abs(summary[p + "dynamic_factor"] - tension.max() / tension[0]) < 1e-14,
      f"dynamic factor {summary[p + 'dynamic_factor']:.6f} = peak / static")
root_moment = m * g * L + rhoA * g * L * L / 2 - F * delta
M0 = summary["design.clamp.root.static_root_moment_Nm"]
check(abs(M0 / root_moment - 1) < 2e-6, f"root moment at t = 0 {M0:.3f} N m vs {root_moment:.3f} (rel. {abs(M0 / root_moment - 1):.1e})")

# plot_hoist.py
r = plot_hoist.plot_hoist(out, os.path.join(work, "hoist.png"))
check(os.path.getsize(r["figure"]) > 10000, f"figure {r['figure']} written")
tc = r["swing_crossings"]
swing = 0.5 * (len(tc) - 1) / (tc[-1] - tc[0])
tracked = float(np.mean(r["tracked_hz"]))
pendulum = np.sqrt(g / l) / (2 * np.pi)
check(len(tc) >= 6, f"{len(tc)} zero crossings")
check(abs(tracked / swing - 1) < 1e-3, f"tracked {tracked:.5f} Hz vs swing {swing:.5f} Hz (rel. {abs(tracked / swing - 1):.1e})")
check(abs(swing / pendulum - 1) < 1e-3, f"swing {swing:.5f} Hz vs sqrt(g/l)/2pi {pendulum:.5f} Hz (rel. {abs(swing / pendulum - 1):.1e})")
check(2.8 < r["max_swing_deg"] < 2.95, f"max swing {r['max_swing_deg']:.3f} deg (push a = 0.05 m on l = 1 m: 2.86 deg)")
sys.exit(1 if failures else 0)
