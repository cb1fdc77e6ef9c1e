#!/usr/bin/python3
"""Regression digest of a boomdyn results file: extract, compare, update.

    /usr/bin/python3 tests/regression/digest.py RESULTS.h5 DIGEST            compare
    /usr/bin/python3 tests/regression/digest.py RESULTS.h5 DIGEST --update   (re)write DIGEST
    /usr/bin/python3 tests/regression/digest.py RESULTS.h5                   print the digest
    /usr/bin/python3 tests/regression/digest.py RESULTS.h5 DIGEST --boomdyn build/boomdyn --scene inputs/X.yaml [--args "..."]
        runs boomdyn on the scene first (quiet, RESULTS overwritten), then compares
    (CTest: digest.<scene>, one per scene in inputs/, tests/digest.cmake; docs/verification.md)

With the environment variable BOOMDYN_DIGEST_UPDATE=1 a compare becomes an
update, so that `BOOMDYN_DIGEST_UPDATE=1 ctest --test-dir build -L digest`
regenerates every stored digest.

A digest is a small text file, one `key value` per line, of the numbers that
say what a run computed (docs/verification.md, "Regression digests"):

  run.*        step count, rejected steps, total Newton iterations,
               final time, smallest and largest step
  state.*      2-norms of the final q, v and lambda (last row of /state)
  violation.*  the largest constraint violation of the run
  energy.*     the final energy row and the energy balance of /summary
  sample.*     the step times at 1/5, 2/5, ..., 5/5 of the run and, at those
               steps, every sensor (position, velocity), rope tension, slack
               coordinate, friction force, frame deflection, section twist
               (spatial frame sensors) and |lambda|
  modal.*      every computed natural frequency
  tracking.*   the tracked frequency: rows, first, last, min, max
  events.*     the stick/slip events: count, and time, joint and kind of the
               first 20 and the last
  elastic_rope.*  (scenes with elastic ropes) tension, length and stretch of
               each at the sample steps (/steps/outputs)
  type_events.*   (scenes whose types report events) count, and time,
               component and kind of the first 20 and the last

Comparison. Integers (written without a decimal point) must be equal, except
the total of Newton iterations (INT_TOLERANCES below: within 5e-3). A real
value passes when |new - stored| <= RTOL * max(|stored|, scale) + ATOL(key),
where `scale` is the largest |stored| value of the key's family (the key
without its sample index and last part: sensor.tip.position for
sensor.tip.position.x@3, energy.balance for energy.balance.excess_J): a
component that passes near zero (a tip velocity at a turning point) is
compared at RTOL of its own family's size, not at RTOL of itself, because
its roundoff is that of the family. RTOL = 1e-9: the refactors of issue 12
must reproduce results to about 1e-12 on one rank (the same arithmetic in
a different order), while a real change to the model or the integrator
(rho_inf 0.8 -> 0.79, another step size) moves many of these numbers by 1e-3
or more. Measured on paper_extraction: the same run on 2 ranks (another order
of summation) agrees to 4e-11 of the family scale; a step of 1e-3 * (1 + 1e-13)
instead of 1e-3 moves the numbers by up to 3e-10.
The absolute floors ATOL (table FLOORS below) are only for quantities that are
roundoff by nature; each says why. A scene whose dynamics amplify roundoff has
its own RTOL (SCENE_RTOL below: paper_stick_slip 1e-5, with the measurements).

After an intended change of results, regenerate with --update (all scenes:
BOOMDYN_DIGEST_UPDATE=1 ctest --test-dir build -L digest) and say in the commit message which
numbers moved and by how much (this script prints them when comparing).
"""

import argparse
import math
import os
import re
import shlex
import subprocess
import sys
from pathlib import Path

import h5py
import numpy as np

RTOL = 1e-9

# (family prefix, absolute floor, why). The first matching prefix wins.
FLOORS = [
    # The largest violation of the position constraints is roundoff in every
    # scene (1e-34 .. 1e-14 m): Newton converges on the residual, and the last
    # iteration leaves the constraints satisfied to rounding. Its value
    # depends on the order of operations; a real change (a constraint not
    # enforced, a Newton tolerance loosened) makes it 1e-10 m or larger.
    ("violation.", 1e-10, "roundoff by nature; a real change makes it > 1e-10 m"),
    # The modal scenes analyse an unloaded, weightless cantilever: its
    # multipliers and strain energy are roundoff (8e-22 N, 4e-22 J), 0.15 of
    # it on 2 ranks. Every real force and energy in inputs/ is above 1e-3.
    ("state.lambda", 1e-9, "multipliers of an unloaded state are roundoff; real ones are > 1e-3 N"),
    ("steps.lambda", 1e-9, "multipliers of an unloaded state are roundoff; real ones are > 1e-3 N"),
    ("energy.", 1e-12, "energies of an unloaded state are roundoff; real ones are > 1e-3 J"),
]

# Scenes (digest file stems) whose dynamics amplify roundoff, with the
# relative tolerance that replaces RTOL and why.
SCENE_RTOL = {
    # LuGre friction switching between stick and slip amplifies roundoff by
    # about 1e5 over the 14 s: the same run on 2 ranks moves the friction
    # forces at 14 s by 1.1e-7 of their scale, a step of 1e-3 (1 + 1e-13) by
    # 1.5e-8. rho_inf 0.79 instead of 0.8 moves 61 of its 103 values by more
    # than 1e-5 (the pad forces at 14 s by a factor of 8).
    "paper_stick_slip": (1e-5, "LuGre stick/slip amplifies roundoff about 1e5-fold over 14 s"),
}

# Integers compared with a relative tolerance instead of exactly (key, rtol, why).
INT_TOLERANCES = {
    # Newton's convergence test sits on a threshold: a change of the order of
    # summation alone (the same run on 2 ranks) takes 14 more iterations in
    # paper_extraction (19697 of 19683, 7e-4) while every real number of its
    # digest agrees to 4e-11. The reals, not this count, detect real changes
    # (rho_inf 0.8 -> 0.79 changes it by 7e-4 too, and 35 reals by far more).
    "run.newton.total": (5e-3, "iteration counts flip at the convergence threshold under roundoff"),
}

SAMPLE_FRACTIONS = (0.2, 0.4, 0.6, 0.8, 1.0)
EVENTS_LISTED = 20

INT_RE = re.compile(r"^[+-]?[0-9]+$")


# ----------------------------------------------------------------- extract

def _strings(ds):
    return [s.decode("utf-8") if isinstance(s, bytes) else str(s) for s in ds[()]]


def _plain(v):
    if isinstance(v, bytes):
        return v.decode("utf-8")
    if isinstance(v, np.generic):
        return v.item()
    return v


def _names(f, dataset, count, fallback):
    if dataset in f:
        names = _strings(f[dataset])
        if len(names) == count:
            return names
    return [f"{fallback}{i}" for i in range(count)]


def extract(path):
    """The digest of results file `path` as an ordered list of (key, value);
    value is an int (compared exactly) or a float."""
    out = []

    def put(key, value):
        if isinstance(value, (bool, np.bool_)):
            value = int(value)
        if isinstance(value, (int, np.integer)):
            out.append((key, int(value)))
        else:
            out.append((key, float(value)))

    with h5py.File(path, "r") as f:
        attrs = {k: _plain(v) for k, v in f.attrs.items()}
        summary = {k: _plain(v) for k, v in f["summary"].attrs.items()} if "summary" in f else {}
        if summary.get("status") != "completed":
            raise SystemExit(f"digest: {path}: run did not complete (/summary/status = {summary.get('status')!r})")
        put("layout.nq.count", f["layout"].attrs["nq"])
        put("layout.nlambda.count", f["layout"].attrs["nlambda"])
        analysis = attrs.get("analysis", "?")

        steps = f["steps"]
        time = steps["time"][()]
        put("run.steps.count", summary["steps"])
        put("run.rejected.count", summary["rejected_steps"])
        put("run.rows.count", len(time))
        put("run.newton.total", int(np.sum(steps["newton_iterations"][()])))
        put("run.time.final", time[-1])
        if analysis == "dynamic" and len(time) > 1:
            dt = steps["dt"][()][1:]  # row 0 is the initial state
            put("run.dt.min", np.min(dt))
            put("run.dt.max", np.max(dt))
        if "slack_rope_steps" in summary:
            put("run.slack_rope_steps.count", summary["slack_rope_steps"])

        st = f["state"]
        put("state.time.final", st["time"][-1])
        put("state.q.norm", np.linalg.norm(st["q"][-1]))
        put("state.v.norm", np.linalg.norm(st["v"][-1]))
        if "lambda" in st:
            put("state.lambda.norm", np.linalg.norm(st["lambda"][-1]))
        put("violation.max.value", summary["max_constraint_violation"])

        if "energy" in steps:
            for name, value in zip(("kinetic", "strain", "gravity", "total"), steps["energy"][-1]):
                put(f"energy.final.{name}", value)
        for key in ("input_work_J", "energy_excess_J", "energy_involved_J"):
            if key in summary:
                put(f"energy.balance.{key.replace('energy_', '')}", summary[key])

        # Samples: the last row at or before each fraction of the final time
        # (for a static run, of the final load factor).
        rows = []
        t_end = time[-1]
        for frac in SAMPLE_FRACTIONS:
            target = frac * t_end
            rows.append(int(np.searchsorted(time, target + 1e-9 * abs(t_end), side="right") - 1))
        series = []  # (family prefix, 2-D array, component names)
        if "sensors" in f:
            for name in f["sensors"]:
                g = f["sensors"][name]
                for q in ("position", "velocity"):
                    if q in g:  # x, y; spatial scenes also z
                        data = g[q][()]
                        series.append((f"sensor.{name}.{q}", data, ("x", "y", "z")[:data.shape[1]]))
        if "frames" in f:  # the sections of a spatial scene's frame sensors
            for name in f["frames"]:
                if "twist" in f["frames"][name]:
                    series.append((f"section.{name}.twist", f["frames"][name]["twist"][()][:, None], None))
        per_joint = [
            ("rope_tension", "/layout/rope_names", "rope", "tension"),
            ("slack", "/layout/sliding_joint_names", "slack", "s"),
            ("friction_force", "/layout/friction_joint_names", "friction", "force"),
            ("frame_deflection", "/layout/frame_names", "frame", "deflection"),
        ]
        for ds, names_ds, group, q in per_joint:
            if ds in steps:
                data = steps[ds][()]
                data = data.reshape(len(data), -1)
                for j, name in enumerate(_names(f, names_ds, data.shape[1], "column")):
                    series.append((f"{group}.{name}.{q}", data[:, j:j + 1], None))
        # State output channels of elastic ropes (the multiplier channels
        # repeat /steps/rope_tension and stay out of the digests).
        if "outputs" in steps and "/layout/output_names" in f:
            data = steps["outputs"][()]
            for j, name in enumerate(_names(f, "/layout/output_names", data.shape[1], "column")):
                if name.startswith("elastic_rope/"):
                    series.append((name.replace("/", "."), data[:, j:j + 1], None))
        if "lambda" in steps:
            data = steps["lambda"][()]
            series.append(("steps.lambda.norm", np.linalg.norm(data.reshape(len(data), -1), axis=1)[:, None], None))
        for k, row in enumerate(rows, start=1):
            put(f"sample.time.t@{k}", time[row])
            for family, data, comps in series:
                for c in range(data.shape[1]):
                    suffix = f".{comps[c]}" if comps else ""
                    put(f"{family}{suffix}@{k}", data[row, c])

        if "modal" in f:
            for i, hz in enumerate(f["modal"]["frequencies_hz"][()], start=1):
                put(f"modal.mode{i}.hz", hz)

        if "tracking" in f:
            tracked = f["tracking"]["tracked_hz"][()]
            put("tracking.rows.count", len(tracked))
            put("tracking.tracked_hz.first", tracked[0])
            put("tracking.tracked_hz.last", tracked[-1])
            put("tracking.tracked_hz.min", np.min(tracked))
            put("tracking.tracked_hz.max", np.max(tracked))

        if "stick_slip_events" in summary:
            put("events.all.count", summary["stick_slip_events"])
        if "events" in f:
            ev = f["events"]
            t, joint, to_slip = ev["time"][()], ev["joint"][()], ev["to_slip"][()]
            listed = list(range(min(EVENTS_LISTED, len(t))))
            if len(t) > EVENTS_LISTED:
                listed.append(len(t) - 1)
            for i in listed:
                put(f"events.time.t@{i + 1}", t[i])
                put(f"events.joint.index@{i + 1}", joint[i])
                put(f"events.to_slip.flag@{i + 1}", to_slip[i])
        if "type_events" in summary:
            put("type_events.all.count", summary["type_events"])
        if "type_events" in f:
            ev = f["type_events"]
            t, comp, kind = ev["time"][()], ev["component"][()], ev["kind"][()]
            listed = list(range(min(EVENTS_LISTED, len(t))))
            if len(t) > EVENTS_LISTED:
                listed.append(len(t) - 1)
            for i in listed:
                put(f"type_events.time.t@{i + 1}", t[i])
                put(f"type_events.component.index@{i + 1}", comp[i])
                put(f"type_events.kind.index@{i + 1}", kind[i])
    return out


# ------------------------------------------------------------ file format

def format_value(v):
    return str(v) if isinstance(v, int) else repr(float(v))


ISA_LINE = "# instruction set: "


def build_isa(results):
    """The instruction set of the build that wrote RESULTS, from its boomdyn_version
    attribute ("0.1.0 (commit, x86-64-v3)"); versions without it were generic builds."""
    with h5py.File(results, "r") as f:
        version = _plain(f.attrs.get("boomdyn_version", ""))
    m = re.search(r", ([^,()]+)\)$", version)
    return m.group(1) if m else "generic"


def stored_isa(path):
    for line in Path(path).read_text(encoding="utf-8").splitlines():
        if line.startswith(ISA_LINE):
            return line[len(ISA_LINE):].split()[0]
    return "generic"


def write_digest(path, entries, command, isa):
    rtol, why = SCENE_RTOL.get(Path(path).stem, (RTOL, ""))
    lines = ["# boomdyn regression digest (tests/regression/digest.py; docs/verification.md)",
             f"# made by: {command}",
             f"{ISA_LINE}{isa} (the build's BOOMDYN_ARCH; another instruction set moves results at round-off)",
             f"# compared with rtol {rtol:g}" + (f" ({why})" if why else "") +
             " relative to max(|value|, largest |value| of the key's family);",
             "# integers exactly (the Newton total within 5e-3). Regenerate after an intended change",
             "# with --update, and say in the commit which numbers moved and by how much."]
    lines += [f"{k} {format_value(v)}" for k, v in entries]
    Path(path).write_text("\n".join(lines) + "\n", encoding="utf-8")


def read_digest(path):
    entries = []
    for n, raw in enumerate(Path(path).read_text(encoding="utf-8").splitlines(), start=1):
        line = raw.strip()
        if not line or line.startswith("#"):
            continue
        parts = line.split()
        if len(parts) != 2:
            raise SystemExit(f"digest: {path}:{n}: expected 'key value', found {raw!r}")
        key, text = parts
        try:
            value = int(text) if INT_RE.match(text) else float(text)
        except ValueError:
            raise SystemExit(f"digest: {path}:{n}: key {key}: value {text!r} is not a number")
        entries.append((key, value))
    return entries


# ----------------------------------------------------------------- compare

def family(key):
    return key.split("@")[0].rsplit(".", 1)[0]


def floor_for(key):
    for prefix, atol, _why in FLOORS:
        if key.startswith(prefix):
            return atol
    return 0.0


def compare(stored, new, rtol=RTOL):
    """Mismatch lines (empty when the digests agree)."""
    problems = []
    stored_map, new_map = dict(stored), dict(new)
    scale = family_scales(stored)
    for k, ref in stored:
        if k not in new_map:
            problems.append(f"{k}: stored {format_value(ref)}, absent from the new run")
            continue
        got = new_map[k]
        if isinstance(ref, int) and isinstance(got, int):
            if k in INT_TOLERANCES:
                int_rtol, why = INT_TOLERANCES[k]
                if abs(got - ref) > int_rtol * abs(ref):
                    problems.append(f"{k}: stored {ref}, new {got} (may differ by {int_rtol:g} relative: {why})")
            elif got != ref:
                problems.append(f"{k}: stored {ref}, new {got} (integers must be equal)")
            continue
        ref, got = float(ref), float(got)
        if not (math.isfinite(ref) and math.isfinite(got)):
            if not (ref == got or (math.isnan(ref) and math.isnan(got))):
                problems.append(f"{k}: stored {ref!r}, new {got!r}")
            continue
        tol = tolerance(k, ref, scale, rtol)
        diff = abs(got - ref)
        if diff > tol:
            rel = diff / abs(ref) if ref != 0 else math.inf
            problems.append(f"{k}: stored {ref!r}, new {got!r}, difference {diff:.3e} "
                            f"(relative {rel:.3e}) > tolerance {tol:.3e}")
    for k, v in new:
        if k not in stored_map:
            problems.append(f"{k}: new {format_value(v)}, not in the stored digest")
    return problems


def tolerance(key, ref, scale, rtol=RTOL):
    return rtol * max(abs(ref), scale.get(family(key), 0.0)) + floor_for(key)


def family_scales(stored):
    scale = {}
    for k, v in stored:
        if isinstance(v, float) and math.isfinite(v):
            scale[family(k)] = max(scale.get(family(k), 0.0), abs(v))
    return scale


def largest_change(stored, new, rtol=RTOL):
    """(key, difference / tolerance) of the real value that used most of its tolerance."""
    new_map, scale = dict(new), family_scales(stored)
    best = (None, 0.0)
    for k, ref in stored:
        if isinstance(ref, float) and k in new_map and math.isfinite(ref):
            tol = tolerance(k, ref, scale, rtol)
            used = abs(float(new_map[k]) - ref) / tol if tol > 0 else (0.0 if new_map[k] == ref else math.inf)
            if used > best[1]:
                best = (k, used)
    return best


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("results", type=Path, help="boomdyn results file (.h5)")
    ap.add_argument("digest", type=Path, nargs="?", help="stored digest to compare with (or to write with --update)")
    ap.add_argument("--update", action="store_true", help="write the digest of RESULTS to DIGEST instead of comparing")
    ap.add_argument("--command", default=None,
                    help="the command that made RESULTS, for the digest's header (default: its command_line attribute)")
    ap.add_argument("--boomdyn", type=Path, help="run this boomdyn binary on --scene first, writing RESULTS")
    ap.add_argument("--scene", type=Path, help="the scene file for --boomdyn")
    ap.add_argument("--args", default="", help="extra command-line options for --boomdyn (one string)")
    ap.add_argument("--never-update", action="store_true",
                    help="ignore BOOMDYN_DIGEST_UPDATE (for the tests that compare a deliberately changed run)")
    args = ap.parse_args()
    if os.environ.get("BOOMDYN_DIGEST_UPDATE") == "1" and not args.never_update:
        args.update = True
    if args.boomdyn:
        if not args.scene:
            ap.error("--boomdyn needs --scene")
        args.results.parent.mkdir(parents=True, exist_ok=True)
        cmd = [str(args.boomdyn), str(args.scene), "-o", str(args.results), "-boom_overwrite", "-boom_quiet"]
        cmd += shlex.split(args.args)
        env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
        run = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, env=env)
        if run.returncode != 0:
            print(run.stdout.decode("utf-8", "replace"))
            print(f"digest: {' '.join(shlex.quote(c) for c in cmd)} exited with status {run.returncode}")
            return 1
        if args.command is None:
            # Repository-relative, so that the digest's header does not name one machine's folders.
            root = Path(__file__).resolve().parents[2]
            shown = ["build/boomdyn", os.path.relpath(args.scene.resolve(), root), "-boom_quiet"] + shlex.split(args.args)
            args.command = " ".join(shlex.quote(c) for c in shown)
    new = extract(args.results)
    if args.digest is None:
        for k, v in new:
            print(k, format_value(v))
        return 0
    if args.update:
        command = args.command
        if command is None:
            with h5py.File(args.results, "r") as f:
                command = _plain(f.attrs.get("command_line", "?"))
        write_digest(args.digest, new, command, build_isa(args.results))
        print(f"digest: wrote {args.digest} ({len(new)} values)")
        return 0
    if not args.digest.exists():
        print(f"digest: no stored digest {args.digest}; create it with\n"
              f"  /usr/bin/python3 {Path(__file__).resolve()} {args.results} {args.digest} --update")
        return 1
    stored = read_digest(args.digest)
    rtol = SCENE_RTOL.get(args.digest.stem, (RTOL, ""))[0]
    problems = compare(stored, new, rtol)
    key, used = largest_change(stored, new, rtol)
    if problems:
        print(f"digest: {args.results} differs from {args.digest} in {len(problems)} of {len(stored)} values:")
        for p in problems:
            print("  " + p)
        print("digest: if this change of results is intended, regenerate the stored digest with\n"
              f"  /usr/bin/python3 {Path(__file__).resolve()} {args.results} {args.digest} --update\n"
              "(all scenes: BOOMDYN_DIGEST_UPDATE=1 ctest --test-dir build -L digest)\n"
              "and say in the commit message which numbers moved and by how much (docs/verification.md).")
        made, this = stored_isa(args.digest), build_isa(args.results)
        if made != this:
            # FMA and vector widths round differently; Newton's tolerance lets
            # that grow to about 1e-9 of a value, above RTOL in most scenes.
            print(f"digest: note: the stored digest was made by a {made} build and this binary is a {this} build "
                  "(boomdyn_version): results differ at round-off between instruction sets, which the dynamics "
                  f"amplify; compare with a {made} build (cmake -DBOOMDYN_ARCH={made}) before concluding that "
                  "results changed.")
        return 1
    print(f"digest: {args.results} matches {args.digest} ({len(stored)} values, rtol {rtol:g}; "
          "largest difference " + (f"{used:.1e} of its tolerance, in {key})" if key else "0)"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
