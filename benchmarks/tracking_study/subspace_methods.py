#!/usr/bin/env python3
"""Offline study of the tracking refinement on dumped pencils (issue 18,
docs/performance-history.md "Twelfth round").

The pencils come from a build with dump_pencils.patch applied (study only,
not on main): every refined analysis writes A, B (and D), the start basis V
and the shift tau to $BOOM_DUMP/pencil_NNNN.bin(.txt):

    git apply benchmarks/tracking_study/dump_pencils.patch && make -C build boomdyn
    mkdir -p /tmp/dump10 && BOOM_DUMP=/tmp/dump10 build/boomdyn inputs/paper_extraction.yaml \
        -boom_quiet -o /tmp/d.h5 -boom_overwrite -ts_max_time 3
    mkdir -p /tmp/dump1 && BOOM_DUMP=/tmp/dump1 build/boomdyn inputs/paper_extraction.yaml \
        -boom_quiet -o /tmp/d.h5 -boom_overwrite -ts_max_time 0.3 -boom_tracking_interval 0.001
    git checkout src/analysis/mode_refinement.cpp

Then, e.g.:

    benchmarks/tracking_study/subspace_methods.py methods /tmp/dump10
    benchmarks/tracking_study/subspace_methods.py lag /tmp/dump1
    benchmarks/tracking_study/subspace_methods.py relax /tmp/dump10
    benchmarks/tracking_study/subspace_methods.py extrapolate /tmp/dump1

Counts solves (columns) to bring the `count` wanted pairs to the relative
residual 5e-9 of the code (||A x - theta B x|| / ||A x||), by the code's
subspace iteration ("si") and by Rayleigh-Ritz on larger spaces: "tb"
[V, S^-1 B V] (two blocks of a block Krylov space) and "lb" [V, S^-1 B V,
V_previous] (LOBPCG-like). Dense numpy/scipy arithmetic: solve counts and
rates, not timings.
"""
import os
import sys
import warnings

import numpy as np
import scipy.sparse.linalg as spl

warnings.filterwarnings("ignore")
sys.path.insert(0, os.path.join(os.environ.get("PETSC_DIR", "/usr/lib/petsc"), "lib/petsc/bin"))
import PetscBinaryIO  # noqa: E402

TOL = 5e-9


def load(directory, k):
    name = f"{directory}/pencil_{k:04d}.bin"
    tau, m, count, damped = open(name + ".txt").read().split()
    objs = PetscBinaryIO.PetscBinaryIO().readBinaryFile(name, mattype="scipy.sparse")
    first = 3 if int(damped) else 2
    V = np.column_stack([np.asarray(v) for v in objs[first:first + int(m)]])
    return dict(A=objs[0].tocsr(), B=objs[1].tocsr(), V=V, tau=float(tau), m=int(m), count=int(count))


def residuals(A, B, X, theta):
    AX = A @ X
    return np.linalg.norm(AX - (B @ X) * theta, axis=0) / np.linalg.norm(AX, axis=0)


def b_orthonormal(blocks, B):
    """B-orthonormal basis of the blocks' span, block by block (classical
    Gram-Schmidt twice against the earlier blocks, then the block's own Gram
    matrix), dropping directions at round-off."""
    Q = None
    for Z in blocks:
        Z = Z.copy()
        for _ in range(2):
            if Q is not None:
                Z -= Q @ (Q.T @ (B @ Z))
            Z = Z / np.sqrt(np.einsum("ij,ij->j", Z, B @ Z))
        G = Z.T @ (B @ Z)
        w, U = np.linalg.eigh((G + G.T) / 2)
        keep = w > 1e-12 * w.max()
        Z = Z @ (U[:, keep] / np.sqrt(w[keep]))
        if Q is not None:
            Z -= Q @ (Q.T @ (B @ Z))
        Q = Z if Q is None else np.hstack([Q, Z])
    return Q


def refine(p, method="si", m=None, expand=None, tols=None, maxit=15):
    """Returns (iterations or None, solves, the count lowest Ritz values).
    m: basis columns used (the first m of the dumped basis); expand: the
    number of leading columns that get a new direction after the first
    iteration (None: all m); tols: per wanted pair (default TOL)."""
    A, B, tau, count = p["A"], p["B"], p["tau"], p["count"]
    m = m or p["m"]
    V = p["V"][:, :m]
    tols = np.full(count, TOL) if tols is None else np.asarray(tols)
    lu = spl.splu((A - tau * B).tocsc())
    solves, locked, Vprev = 0, 0, None
    for it in range(1, maxit + 1):
        # The first step is always subspace iteration on all m: the last
        # analysis' vectors violate this pencil's constraint rows.
        top = m if expand is None or it == 1 else expand
        W = lu.solve(B @ V[:, locked:top])
        solves += top - locked
        if method == "si" or it == 1:
            Z = V.copy()
            Z[:, locked:top] = W
            Q = b_orthonormal([Z], B)
        elif method == "tb":
            Q = b_orthonormal([V, W], B)
        else:  # "lb"
            Q = b_orthonormal([V, W] + ([Vprev[:, locked:top]] if it > 2 else []), B)
        theta, Y = np.linalg.eigh(Q.T @ (A @ Q))
        Vprev, V, theta = V, Q @ Y[:, :m], theta[:m]
        r = residuals(A, B, V[:, :count], theta[:count])
        locked = 0
        while locked < count and r[locked] <= tols[locked]:
            locked += 1
        if (r <= tols).all():
            return it, solves, theta[:count]
    return None, solves, theta[:count]


def analyses(directory):
    return sorted(int(f[7:11]) for f in os.listdir(directory) if f.startswith("pencil_") and f.endswith(".bin"))


def sweep(directory, step=3, **options):
    """Every step-th analysis refined by refine(**options) against the
    code's subspace iteration: (solves per analysis, mean and largest
    iteration count, largest relative difference of omega^2)."""
    ks = analyses(directory)[1::step]
    its, solves, dev = [], 0, 0.0
    for k in ks:
        p = load(directory, k)
        ref = refine(p, "si")
        it, s, theta = refine(p, **options)
        its.append(it or 99)
        solves += s
        dev = max(dev, np.abs(theta / ref[2] - 1).max())
    return solves / len(ks), np.mean(its), max(its), dev


def cmd_methods(directory):
    for method, m, expand in [("si", 6, None), ("si", 5, None), ("tb", 6, None), ("tb", 6, 4), ("lb", 6, None),
                              ("lb", 6, 4), ("lb", 5, 4), ("lb", 4, None)]:
        solves, mean, most, dev = sweep(directory, method=method, m=m, expand=expand)
        print(f"{method} m={m} expand={expand}: solves per analysis {solves:.1f}, "
              f"iterations {mean:.2f} (max {most}), omega^2 against si {dev:.1e}")


def cmd_relax(directory):
    for relax in [5e-9, 1e-7, 1e-6, 1e-5]:
        tols = np.full(4, relax)
        tols[0] = TOL  # the followed mode (the lowest on the paper scene; count 4)
        solves, mean, _, dev = sweep(directory, tols=tols)
        print(f"other pairs to {relax:.0e}: solves per analysis {solves:.1f}, "
              f"iterations {mean:.2f}, omega^2 against all at 5e-9 {dev:.1e}")


def cmd_extrapolate(directory, step=10):
    ks = [k for k in analyses(directory) if k >= 3][::step]
    totals = {"last": 0, "linear": 0, "quadratic": 0}
    for k in ks:
        p0, p1, p2 = load(directory, k), load(directory, k - 1), load(directory, k - 2)
        def align(X, ref):
            return X * np.sign(np.einsum("ij,ij->j", X, ref))
        V0 = p0["V"]
        V1 = align(p1["V"], V0)
        V2 = align(p2["V"], V1)
        for name, start in [("last", V0), ("linear", 2 * V0 - V1), ("quadratic", 3 * V0 - 3 * V1 + V2)]:
            q = dict(p0, V=start)
            totals[name] += refine(q, "si")[1]
    for name, s in totals.items():
        print(f"start from {name}: solves per analysis {s / len(ks):.1f}")


def cmd_lag(directory, step=10):
    """Refinement with the previous analysis' factorization: corrections
    P_old^-1 r projected onto the null space of this pencil's constraint
    rows, Rayleigh-Ritz on [V, corrections] of the constrained problem
    (coordinates only), multipliers fitted by least squares for the
    residual. Also prints how much K changed between the two analyses."""
    for k in analyses(directory)[1::step]:
        p, po = load(directory, k), load(directory, k - 1)
        A, B = p["A"], p["B"]
        if po["A"].shape != A.shape:
            continue  # a contact point changed element between the two
        n = A.shape[0]
        dense = A.toarray()
        nq = n  # the multiplier rows follow the coordinates, with a zero block
        while nq > 0 and not dense[nq - 1:, nq - 1:].any():
            nq -= 1
        K, M, C = A[:nq, :nq], B[:nq, :nq], A[nq:, :nq].toarray()
        Ko = po["A"][:nq, :nq]
        G = np.linalg.inv(C @ C.T)
        project = lambda X: X - C.T @ (G @ (C @ X))  # noqa: E731
        CT = A[:nq, nq:].toarray()
        lu_old = spl.splu((po["A"] - po["tau"] * po["B"]).tocsc())
        Vq = project(p["V"][:nq])
        Q = b_orthonormal([Vq], M)
        count, m = p["count"], p["m"]
        history = []
        for it in range(8):
            theta, Y = np.linalg.eigh(Q.T @ (K @ Q))
            Vq, theta = Q @ Y[:, :m], theta[:m]
            X = np.zeros((n, count))
            X[:nq] = Vq[:, :count]
            R0 = A @ X - (B @ X) * theta[:count]
            X[nq:] = np.linalg.lstsq(CT, -R0[:nq], rcond=None)[0]
            history.append(residuals(A, B, X, theta[:count]).max())
            Rq = K @ Vq - (M @ Vq) * theta
            rhs = np.zeros((n, m))
            rhs[:nq] = Rq
            Q = b_orthonormal([Vq, project(lu_old.solve(rhs)[:nq])], M)
        dK = np.abs((K - Ko).toarray())
        i = np.unravel_index(dK.argmax(), dK.shape)
        print(f"analysis {k}: worst residual per iteration " + " ".join(f"{h:.1e}" for h in history) +
              f"; largest change of K {dK[i]:.2e} at {i} (entry {K[i]:.2e})")


if __name__ == "__main__":
    if len(sys.argv) != 3 or sys.argv[1] not in ("methods", "relax", "extrapolate", "lag"):
        sys.exit(__doc__)
    globals()["cmd_" + sys.argv[1]](sys.argv[2])
