#!/usr/bin/python3
"""Checks of the comparison in tests/regression/digest.py on hand-made digests
(no boomdyn run): what must pass passes and what must fail fails.
Usage: test_digest.py (CTest digest.script)"""
import os
import sys
import tempfile
from pathlib import Path

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.dirname(HERE))
import digest  # noqa: E402
import script_checks  # noqa: E402

results = []


check = script_checks.checker(results)


STORED = [("run.steps.count", 1000), ("state.q.norm", 6.0),
          ("sensor.tip.velocity.x@1", 1e-6), ("sensor.tip.velocity.y@1", 2.0),
          ("violation.max.value", 1e-20), ("energy.balance.excess_J", -1.0), ("energy.balance.involved_J", 100.0)]


def changed(key, value):
    return [(k, value if k == key else v) for k, v in STORED]


def main():
    check(digest.compare(STORED, STORED) == [], "a digest matches itself")
    check(digest.compare(STORED, changed("state.q.norm", 6.0 * (1 + 1e-12))) == [],
          "a 1e-12 relative change passes")
    p = digest.compare(STORED, changed("state.q.norm", 6.0 * (1 + 1e-8)))
    check(len(p) == 1 and p[0].startswith("state.q.norm: stored 6.0, new 6.00000006"),
          "a 1e-8 relative change fails, naming the key and both values: %s" % p)
    # velocity.x is 1e-6 of its family (velocity.y = 2): compared at 1e-9 * 2.
    check(digest.compare(STORED, changed("sensor.tip.velocity.x@1", 1e-6 + 1e-9)) == [],
          "a component near zero is compared at its family's scale (1e-9 of 2 m/s passes)")
    check(len(digest.compare(STORED, changed("sensor.tip.velocity.x@1", 1e-6 + 1e-8))) == 1,
          "... and 1e-8 m/s on a 2 m/s family fails")
    check(len(digest.compare(STORED, changed("run.steps.count", 1001))) == 1, "integers must be equal")
    newton = [("run.newton.total", 19683)] + STORED  # first, as in a digest: its tolerance must not leak
    check(digest.compare(newton, [("run.newton.total", 19697)] + STORED) == [],
          "the Newton iteration total may move by roundoff (19683 -> 19697, as on 2 ranks)")
    check(len(digest.compare(newton, [("run.newton.total", 19900)] + STORED)) == 1,
          "... but not by 1 %")
    p = digest.compare(newton, [("run.newton.total", 19697)] + changed("state.q.norm", 6.0 * (1 + 1e-8)))
    check(len(p) == 1 and p[0].startswith("state.q.norm"),
          "the Newton total's tolerance applies to it alone (a 1e-8 change after it still fails): %s" % p)
    check(len(digest.compare(STORED, changed("state.q.norm", 6.0 * (1 + 1e-8)), rtol=1e-5)) == 0
          and len(digest.compare(STORED, changed("state.q.norm", 6.0 * (1 + 1e-4)), rtol=1e-5)) == 1,
          "a scene's own rtol (1e-5) replaces the default")
    check(digest.compare(STORED, changed("violation.max.value", 3e-15)) == [],
          "the constraint violation may move within roundoff (floor 1e-10)")
    check(len(digest.compare(STORED, changed("violation.max.value", 1e-9))) == 1,
          "a constraint violation of 1e-9 fails")
    check(len(digest.compare(STORED, changed("energy.balance.excess_J", -1.0 + 5e-8))) == 0,
          "the energy excess is compared at 1e-9 of the energy involved")
    check(len(digest.compare(STORED, STORED[:-1])) == 1, "a key missing from the new run fails")
    check(len(digest.compare(STORED[:-1], STORED)) == 1, "a key not in the stored digest fails")
    check(len(digest.compare(STORED, changed("state.q.norm", float("nan")))) == 1, "NaN fails")
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "x.digest"
        digest.write_digest(path, STORED, "build/boomdyn inputs/x.yaml -boom_quiet", "x86-64-v3")
        back = digest.read_digest(path)
        check(back == STORED and all(type(a[1]) is type(b[1]) for a, b in zip(back, STORED)),
              "write then read gives the same keys, values and integer/real kinds")
        check("# made by: build/boomdyn inputs/x.yaml -boom_quiet" in path.read_text(),
              "the header names the command")
        check(digest.stored_isa(path) == "x86-64-v3", "the header names the build's instruction set")
        old = Path(tmp) / "old.digest"
        old.write_text("# boomdyn regression digest\nrun.steps.count 1000\n")
        check(digest.stored_isa(old) == "generic", "a digest without the line was made by a generic build")
        import h5py
        for version, isa in (("0.1.0 (abc1234, x86-64-v3)", "x86-64-v3"), ("0.1.0 (abc1234-dirty, generic)", "generic"),
                             ("0.1.0 (abc1234)", "generic")):
            h5 = Path(tmp) / "r.h5"
            with h5py.File(h5, "w") as f:
                f.attrs["boomdyn_version"] = version
            check(digest.build_isa(h5) == isa, f"boomdyn_version {version!r} is a {isa} build")


if __name__ == "__main__":
    sys.exit(script_checks.finish(main, results))
