#!/usr/bin/env python3
"""Modal analysis and frequency tracking of spatial scenes (dimension: 3)
through the program (scene -> model -> SLEPc -> HDF5), against closed forms
derived here, with the energy-split mode labels (docs/model.md §5, "Mode
labels"; docs/output.md):

1. A 4 m steel box cantilever (midline 0.3 x 0.4 m, wall 0.01 m; width along
   the section's y = d2, height along z = d3) with EI_y != EI_z and Bredt's
   GJ, modal at the initial state: the first two bending frequencies in each
   principal plane (beta_n^2 / L^2 sqrt(EI / rhoA), cos(beta L) cosh(beta L)
   = -1), the first two torsional ((2n - 1) pi / (2 L) sqrt(GJ / rho Ip)) and
   the first axial (pi / (2 L) sqrt(EA / rhoA)) within 1e-4 at 128 elements,
   with the rates measured over 8 ... 128 elements (cubic centreline: 4;
   linear twist with consistent inertia: 2). Each mode is picked by its
   label, and its largest share must exceed 0.99: bending about d3 (EI_z,
   in the plane of the axis and `up`) is bending_in_plane, about d2 (EI_y)
   bending_out_of_plane.
2. A spatial compound pendulum (rigid rod of 1 m, 2 kg, hanging from a
   revolute joint) in a dynamic run at rest, modal at the end: omega^2 =
   m g l / (J + m l^2) within 1e-8, labelled geometric (its stiffness is the
   joint reaction's curvature).
3. The box cantilever on 2 ranks: frequencies and shares equal the 1-rank
   run's to 1e-10.
4. A spatial beam luffed by an angle drive (revolute joint about y, tip mass,
   gravity) with frequency tracking: it runs, every followed mode keeps its
   identity (MAC > 0.99) and the followed frequencies vary smoothly (the
   second differences of the samples are below 1e-3 of the frequency).
5. A planar luffing-boom tracking scene (ANCF beam, clamp with a moving angle,
   tip mass, gravity) run with -boom_spatial: every planar tracked frequency
   is among the spatial run's to 1e-8 relative at every analysis (the
   spatial scene asks for twice the modes: the out-of-plane ones come in
   addition), and the planar followed mode, followed in the spatial run
   too, has the same energy shares to 1e-6.
6. A rigid boom luffed by a closed hydraulic cylinder (planar): its luffing
   mode is labelled hydraulic with a share > 0.99.
Usage: test_spatial_modal.py BOOMDYN_EXECUTABLE SOURCE_DIR WORK_DIR"""
import math
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
work = os.path.join(work, "test_output", "spatial_modal")
os.makedirs(work, exist_ok=True)
mpi = ["mpiexec", "-n", "2", "--oversubscribe", "--allow-run-as-root"]


def run(name, text, args=(), ranks=1):
    scene = os.path.join(work, name + ".yaml")
    with open(scene, "w") as f:
        f.write(text)
    out = os.path.join(work, name + ".h5")
    cmd = (mpi if ranks == 2 else []) + [boomdyn, scene, "-o", out, "-boom_overwrite"] + list(args)
    done = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if done.returncode != 0:
        print(done.stdout)
        raise SystemExit("boomdyn failed on " + scene)
    return out, done.stdout


def modes(path):
    with h5py.File(path) as f:
        m = f["modal"]
        kinds = [k.decode() if isinstance(k, bytes) else k for k in m["energy_kinds"][()]]
        labels = [k.decode() if isinstance(k, bytes) else k for k in m["labels"][()]]
        return np.array(m["frequencies_hz"]), np.array(m["energy_shares"]), kinds, labels


# 1. The box cantilever.
E, G, RHO, B, H, T, L = 2.1e11, 8.1e10, 7850.0, 0.3, 0.4, 0.01, 4.0
A = 2 * T * (B + H)
IY, IZ = T * H * H * (3 * B + H) / 6, T * B * B * (3 * H + B) / 6
J = 2 * T * B * B * H * H / (B + H)
RHO_A = RHO * A


def cantilever_root(x):
    for _ in range(50):
        x -= (math.cos(x) * math.cosh(x) + 1) / (-math.sin(x) * math.cosh(x) + math.cos(x) * math.sinh(x))
    return x


BETAS = [cantilever_root(1.875), cantilever_root(4.694)]
HZ = 1 / (2 * math.pi)
EXACT = {
    "bending_in_plane": [b * b / L**2 * math.sqrt(E * IZ / RHO_A) * HZ for b in BETAS],
    "bending_out_of_plane": [b * b / L**2 * math.sqrt(E * IY / RHO_A) * HZ for b in BETAS],
    "torsion": [(2 * n - 1) * math.pi / (2 * L) * math.sqrt(G * J / (RHO * (IY + IZ))) * HZ for n in (1, 2)],
    "axial": [math.pi / (2 * L) * math.sqrt(E / RHO) * HZ],
}

BOX = """name: spatial-box-cantilever-{n}
dimension: 3
analysis: modal
gravity: [0, 0, 0]
bodies:
  - name: boom
    type: ancf_beam
    length: {L}
    elements: {n}
    axis: [1, 0, 0]
    up: [0, 1, 0]
    section: {{E: {E}, G: {G}, rho: {RHO}, width: {B}, height: {H}, thickness: {T}}}
constraints:
  - {{type: clamp, name: root, body: boom, at: start}}
modal: {{count: 10, at: start}}
"""


def box(n):
    return BOX.format(n=n, L=L, E=E, G=G, RHO=RHO, B=B, H=H, T=T)


def by_kind(freq, shares, kinds):
    out = {}
    for f, s in zip(freq, shares):
        k = int(np.argmax(s))
        out.setdefault(kinds[k], []).append((f, s[k]))
    return out


def cantilever_modes():
    previous = {}
    for n in (8, 16, 32, 64, 128):
        path, log = run("box_%d" % n, box(n))
        freq, shares, kinds, labels = modes(path)
        check(abs(shares.sum(axis=1) - 1).max() < 1e-12, "%d elements: the shares of every mode sum to 1" % n)
        found = by_kind(freq, shares, kinds)
        for kind, exact in EXACT.items():
            for j, ref in enumerate(exact):
                if len(found.get(kind, [])) <= j:
                    check(False, "%d elements: %s mode %d found among the 10 lowest" % (n, kind, j + 1))
                    continue
                f, share = found[kind][j]
                err = abs(f / ref - 1)
                line = "%3d elements %-20s mode %d: %.9f Hz, exact %.9f, error %.3e, share %.8f" % (
                    n, kind, j + 1, f, ref, err, share)
                key = (kind, j)
                if key in previous:
                    rate = math.log2(previous[key] / err)
                    line += ", rate %.2f" % rate
                    if kind == "torsion":
                        check(abs(rate - 2) < 0.1, "%d elements: %s %d converges at rate 2 (%.3f)" % (n, kind, j + 1, rate))
                    elif previous[key] > 1e-7:  # above the round-off floor of the pencil
                        check(rate > 3.5, "%d elements: %s %d converges at rate 4 (%.3f)" % (n, kind, j + 1, rate))
                print(line)
                previous[key] = err
                check(share > 0.99, "%d elements: %s mode %d is labelled by a share > 0.99 (%.6f)" % (n, kind, j + 1, share))
                if n == 128:
                    check(err < 1e-4, "128 elements: %s mode %d within 1e-4 of the closed form (%.2e)" % (kind, j + 1, err))
        if n == 16:
            check("torsion 1.00" in log and "bending_in_plane 1.00" in log, "the log labels the modes")

def two_ranks():
    # 3. The same analysis on 2 ranks.
    path1, _ = run("box_16", box(16))
    path2, _ = run("box_16_2ranks", box(16), ranks=2)
    f1, s1, _, _ = modes(path1)
    f2, s2, _, _ = modes(path2)
    df = np.max(np.abs(f2 / f1 - 1))
    ds = np.max(np.abs(s2 - s1))
    print("1 vs 2 ranks: frequencies %.2e relative, shares %.2e" % (df, ds))
    check(df < 1e-10 and ds < 1e-10, "2 ranks give the 1-rank frequencies and shares to 1e-10")


def pendulum():
    # 2. The compound pendulum: a rod along -z from a hinge about y; with up = y
    # it swings about its body y axis (J = 0.2), with up = x about its body z
    # axis (J = 0.23).
    for axis, up, jc in (("[0, 1, 0]", "[0, 1, 0]", 0.2), ("[0, 1, 0]", "[1, 0, 0]", 0.23)):
        text = """name: spatial-pendulum-modes
dimension: 3
analysis: dynamic
gravity: [0, 0, -9.81]
bodies:
  - {name: rod, type: rigid, length: 1.0, mass: 2.0, inertia: [0.05, 0.2, 0.23], axis: [0, 0, -1], up: %s}
constraints:
  - {type: revolute_joint, body: rod, at: start, axis: %s}
dynamic: {t_end: 0.01, dt: 1.0e-3}
modal: {count: 1}
""" % (up, axis)
        path, _ = run("pendulum", text)
        freq, shares, kinds, labels = modes(path)
        exact = math.sqrt(2.0 * 9.81 * 0.5 / (jc + 2.0 * 0.25)) * HZ
        print("pendulum, J = %g: %.12f Hz, exact %.12f, error %.2e, label %s" % (
            jc, freq[0], exact, abs(freq[0] / exact - 1), labels[0]))
        check(abs(freq[0] / exact - 1) < 1e-8, "the pendulum with J = %g swings at the closed-form frequency" % jc)
        check(labels[0].startswith("geometric") and shares[0].max() > 0.99, "the pendulum mode is labelled geometric")


def luffing_tracking():
    # 4. Tracking on a spatial luffing beam.
    LUFFING = """name: spatial-luffing-tracking
dimension: 3
analysis: dynamic
gravity: [0, 0, -9.81]
bodies:
  - name: boom
    type: ancf_beam
    length: 4.0
    elements: 8
    axis: [1, 0, 0]
    up: [0, 0, 1]
    section: {E: 2.1e11, G: 8.1e10, rho: 7850, width: 0.4, height: 0.3, thickness: 0.01}
constraints:
  - {type: revolute_joint, name: foot, body: boom, at: start, axis: [0, 1, 0]}
  - type: angle_drive
    name: luffing
    body: boom
    at: start
    axis: [0, 1, 0]
    angle: {type: smooth_step, t0: 0.0, t1: 0.4, from: 0, to: -40}
masses:
  - {body: boom, at: end, mass: 500}
dynamic: {t_end: 0.5, dt: 1.0e-3, rho_inf: 0.8}
tracking: {interval: 0.02, count: 6, follow: 3}
"""
    path, _ = run("luffing", LUFFING)
    with h5py.File(path) as f:
        t = np.array(f["tracking/time"])
        hz = np.array(f["tracking/followed_hz"])
        mac = np.array(f["tracking/followed_mac"])
        shares = np.array(f["tracking/followed_energy_shares"])
        every = np.array(f["tracking/energy_shares"])
        kinds = [k.decode() if isinstance(k, bytes) else k for k in f["tracking/energy_kinds"][()]]
    check(len(t) >= 20, "the luffing beam's tracking made %d analyses" % len(t))
    second = np.abs(hz[2:] - 2 * hz[1:-1] + hz[:-2]) / hz[1:-1]
    print("luffing: followed %s Hz at the start, %s at the end; min MAC %.6f; largest second difference %.2e" % (
        np.round(hz[0], 4), np.round(hz[-1], 4), mac.min(), second.max()))
    print("luffing: labels at the end: %s" % [
        "%s %.3f" % (kinds[int(np.argmax(s))], s.max()) for s in shares[-1].reshape(-1, len(kinds))])
    every = every.reshape(len(t), 6, len(kinds))
    print("luffing: all 6 modes at the end: %s" % ["%s %.3f" % (kinds[int(np.argmax(x))], x.max()) for x in every[-1]])
    check(np.abs(every.sum(axis=2) - 1).max() < 1e-12, "every tracked mode's shares sum to 1 (/tracking/energy_shares)")
    check(mac.min() > 0.99, "every followed mode keeps its identity along the luffing (MAC > 0.99)")
    check(second.max() < 1e-3, "the followed frequencies vary smoothly (second differences < 1e-3)")
    check(np.ptp(hz[:, 0]) > 1e-4 * hz[0, 0], "the luffing changes the first followed frequency")


def planar_in_space():
    # 5. A planar tracking scene as a spatial model in its plane.
    PLANAR = """name: planar-luffing-tracking
analysis: dynamic
gravity: [0, -9.81]
bodies:
  - {{name: boom, length: 4.0, elements: 8, angle: 10, section: {{E: 2.1e11, rho: 7850, A: 1.4e-2, I: 2.5e-4}}}}
constraints:
  - type: clamp
    name: foot
    body: boom
    at: start
    angle: {{type: smooth_step, t0: 0.0, t1: 0.3, from: 10, to: 40}}
masses:
  - {{body: boom, at: end, mass: 500}}
dynamic: {{t_end: 0.4, dt: 1.0e-3, rho_inf: 0.8}}
tracking: {{interval: 0.05, count: {count}, follow: {follow}}}
"""
    # The spatial run follows the lowest two: the in-plane mode the planar
    # run follows and the out-of-plane one beside it (EI_y = EI_z = EI).
    planar, _ = run("planar_luffing", PLANAR.format(count=4, follow=1))
    spatial, _ = run("planar_luffing_spatial", PLANAR.format(count=8, follow=2), args=["-boom_spatial"])
    with h5py.File(planar) as p, h5py.File(spatial) as s:
        fp, fs = np.array(p["tracking/frequencies_hz"]), np.array(s["tracking/frequencies_hz"])
        tp, ts = np.array(p["tracking/time"]), np.array(s["tracking/time"])
        sp, ss = np.array(p["tracking/followed_energy_shares"]), np.array(s["tracking/followed_energy_shares"])
        hp, hs = np.array(p["tracking/followed_hz"]), np.array(s["tracking/followed_hz"])
    check(np.array_equal(tp, ts), "both runs analyse at the same times")
    worst = 0.0
    for a, b in zip(fp, fs):
        for f in a:
            worst = max(worst, np.min(np.abs(b / f - 1)))
    print("planar tracked frequencies in the spatial run: %.2e relative (planar %s Hz, spatial %s Hz at the end)" % (
        worst, np.round(fp[-1], 6), np.round(fs[-1], 6)))
    check(worst < 1e-8, "every planar tracked frequency is a spatial one to 1e-8")
    # The planar followed mode among the spatial followed ones (by frequency),
    # with its energy split.
    nk = sp.shape[1]
    worst_share, matched = 0.0, 0
    for k in range(len(hp)):
        # Equal frequencies (at rest the two are degenerate): the closer split.
        columns = [j for j in range(len(hs[k])) if abs(hs[k, j] / hp[k, 0] - 1) < 1e-8]
        if columns:
            matched += 1
            worst_share = max(worst_share, min(np.abs(ss[k, j * nk:(j + 1) * nk] - sp[k]).max() for j in columns))
    print("planar followed mode in the spatial run at %d of %d analyses; its shares agree to %.2e "
          "(planar at the end: %s)" % (matched, len(hp), worst_share, np.round(sp[-1], 6)))
    check(matched == len(hp), "the spatial run follows the planar followed mode at every analysis")
    check(worst_share < 1e-6, "the planar followed mode has the same energy shares in the spatial run")


CYLINDER = """name: cylinder-luffed-rigid-boom
analysis: dynamic
gravity: [0, -9.81]
bodies:
  - {name: boom, type: rigid, length: 4.0, section: {rhoA: 100}}
constraints:
  - {type: pin, name: foot, body: boom, at: start, point: [0, 0]}
  - type: hydraulic_cylinder
    name: luffing
    body: boom
    at: 1.0
    base_point: [0.3, -0.5]
    piston_diameter: 0.125
    rod_diameter: 0.07
    stroke: 0.7
    closed_length: 0.80
    dead_volume_piston: 1.0e-4
    dead_volume_rod: 1.0e-4
    hose_volume_piston: 1.9e-4
    hose_volume_rod: 1.9e-4
    valve: closed
    initial_pressure_rod: 1.0e+6
dynamic: {t_end: 0.002, dt: 1.0e-3, initial: static}
modal: {count: 1}
"""


def hydraulic_label():
    # 6. The luffing mode of a rigid boom held by a closed hydraulic cylinder
    # (the cylinder of paper_elevation_35_cylinder.yaml, planar): the boom
    # turns about its foot pin against the oil columns, so the mode's strain
    # energy is the cylinder's (gravity's geometric part aside).
    path, log = run("cylinder", CYLINDER)
    freq, shares, kinds, labels = modes(path)
    print("cylinder-luffed rigid boom: %.4f Hz, %s, shares %s" % (freq[0], labels[0], np.round(shares[0], 6)))
    check(labels[0].startswith("hydraulic") and shares[0][kinds.index("hydraulic")] > 0.99,
          "the luffing mode is labelled hydraulic with a share > 0.99")


def main():
    hydraulic_label()
    cantilever_modes()
    two_ranks()
    pendulum()
    luffing_tracking()
    planar_in_space()


sys.exit(script_checks.finish(main, results))
