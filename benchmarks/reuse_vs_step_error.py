#!/usr/bin/python3
"""How far Jacobian reuse moves each scene's results, against its time-step error.

    /usr/bin/python3 benchmarks/reuse_vs_step_error.py [--boomdyn build/boomdyn] [--scenes a b ...] [--jobs 2]
        [--reference "-boom_jacobian_reuse 0"] [--variant "-boom_jacobian_reuse 1"]

For every scene of inputs/ (or the ones named) this runs boomdyn three times,
one rank, and extracts the regression digest of each run
(tests/regression/digest.py):

  full    -boom_jacobian_reuse 0             (full Newton, step h of the scene)
  reuse   -boom_jacobian_reuse 1             (modified Newton, step h)
  half    -boom_jacobian_reuse 0 -ts_dt h/2  (full Newton, half the step; dynamic scenes only)

(--reference and --variant replace the options of "full" and "reuse", so
that any default can be judged the same way: --reference
"-boom_acceleration_predictor 0" --variant "" measures the Newton predictor;
"half" is the reference with -ts_dt h/2), and prints, per scene, the largest difference reuse - full and the largest
difference half - full over the real-valued digest entries, each relative to
the size of its family (the rule the digest comparison uses: a sensor
component near zero is measured against the largest value of that sensor),
with the key where it occurs. "move / step error" is the largest ratio, over
the entries whose step error is above 1e-12 of the family, of the reuse
difference to the step-size difference: below 1 means that reuse changes
each result by less than halving the step does. The integer entries (step
and iteration counts) and the roundoff-only entries (violation.*) are left out.
docs/performance-history.md, "Defaults and start-up", has the table this made.
"""

import argparse
import concurrent.futures
import math
import os
import re
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests" / "regression"))
import digest  # noqa: E402


def scene_step(scene):
    """The scene's time step (dynamic: {... dt: X ...}), or None for static and modal scenes."""
    m = re.search(r"\bdt:\s*([0-9.eE+-]+)", scene.read_text())
    return float(m.group(1)) if m else None


def run(boomdyn, scene, out, options):
    cmd = [str(boomdyn), str(scene), "-o", str(out), "-boom_overwrite", "-boom_quiet", "-boom_allow_unused"] + options
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    for _ in range(3):  # Open MPI's session directory under /tmp can vanish under a parallel cleanup: retry
        r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, env=env)
        if r.returncode == 0 or b"orte_init failed" not in r.stdout:
            break
    if r.returncode != 0:
        raise RuntimeError(" ".join(cmd) + " failed:\n" + r.stdout.decode("utf-8", "replace"))
    return dict((k, v) for k, v in digest.extract(out))


def differences(ref, other, scale):
    """{key: |other - ref| / family scale} over the real entries both have."""
    out = {}
    for k, v in ref.items():
        if isinstance(v, int) or k.startswith("violation.") or k.startswith("run.") or k not in other:
            continue
        a, b = float(v), float(other[k])
        if not (math.isfinite(a) and math.isfinite(b)):
            continue
        s = max(abs(a), scale.get(digest.family(k), 0.0))
        out[k] = abs(b - a) / s if s > 0 else 0.0
    return out


def study(boomdyn, scene, tmp, reference, variant):
    h = scene_step(scene)
    stem = scene.stem
    full = run(boomdyn, scene, tmp / f"{stem}_full.h5", reference)
    reuse = run(boomdyn, scene, tmp / f"{stem}_reuse.h5", variant)
    scale = digest.family_scales(list(full.items()))
    move = differences(full, reuse, scale)
    step = {}
    if h is not None:
        half = run(boomdyn, scene, tmp / f"{stem}_half.h5", reference + ["-ts_dt", repr(h / 2)])
        step = differences(full, half, scale)
    return stem, move, step


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--boomdyn", type=Path, default=ROOT / "build" / "boomdyn")
    ap.add_argument("--scenes", nargs="*", help="scene stems (default: every scene of inputs/)")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--reference", default="-boom_jacobian_reuse 0", help="options of the reference run (and of h/2)")
    ap.add_argument("--variant", default="-boom_jacobian_reuse 1", help="options of the run it is compared with")
    args = ap.parse_args()
    reference, variant = args.reference.split(), args.variant.split()
    scenes = sorted((ROOT / "inputs").glob("*.yaml"))
    if args.scenes:
        scenes = [s for s in scenes if s.stem in args.scenes]
    print("| scene | variant - reference (largest, key) | h/2 - h (largest, key) | variant - reference at that key, / its step error | largest move / step error |")
    print("|---|---|---|---|---:|")
    with tempfile.TemporaryDirectory() as d, concurrent.futures.ThreadPoolExecutor(args.jobs) as pool:
        for stem, move, step in pool.map(lambda s: study(args.boomdyn, s, Path(d), reference, variant), scenes):
            km = max(move, key=move.get) if move else None
            ks = max(step, key=step.get) if step else None
            ratios = {k: move[k] / step[k] for k in move if k in step and step[k] > 1e-12}
            kr = max(ratios, key=ratios.get) if ratios else None
            cell = lambda d, k: f"{d[k]:.1e} `{k}`" if k else "–"
            at = f"{step[km]:.1e}" if km in step else "–"
            print(f"| {stem} | {cell(move, km)} | {cell(step, ks)} | {at} | "
                  + (f"{ratios[kr]:.2g} `{kr}`" if kr else "–") + " |", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
