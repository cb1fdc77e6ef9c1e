#!/usr/bin/env python3
"""Command-line values are checked like scene values: a real option that is
inf or nan, or an integer beyond PetscInt's range (which PETSc would wrap:
-boom_elements 4294967297 ran with 1 element), is refused with one line
naming the option and the value, and a non-zero exit (issue 17, classes 1
and 4: -boom_error_wait nan made a lone failing rank wait forever, -ts_dt inf
completed with 0 steps). A good value still runs.
Usage: test_option_values.py BOOMDYN_EXECUTABLE SOURCE_DIR WORK_DIR"""
import os
import subprocess
import sys

boomdyn, source, work = sys.argv[1:4]
sys.path.insert(0, os.path.join(source, "tests"))
import script_checks  # noqa: E402

results = []
scene = os.path.join(source, "inputs", "cantilever_dynamic.yaml")


check = script_checks.checker(results)


def run(name, args):
    out = os.path.join(work, "option_values_%s.h5" % name)
    return subprocess.run([boomdyn, scene, "-o", out, "-boom_overwrite", "-boom_quiet", "-ts_max_time", "0.005", *args],
                          capture_output=True, text=True, timeout=60)


def main():
    refused = [("-ts_dt", "inf", "must be a finite number"), ("-ts_dt", "nan", "must be a finite number"),
               ("-boom_error_wait", "nan", "must be a finite number"),
               ("-boom_state_interval", "-inf", "must be a finite number"),
               ("-boom_elements", "4294967297", "not an integer in"),
               ("-boom_modal_count", "99999999999999999999", "not an integer in")]
    for k, (option, value, reason) in enumerate(refused):
        r = run("bad%d" % k, [option, value])
        line = (r.stdout + r.stderr).strip().splitlines()[-1:] or [""]
        check(r.returncode != 0 and option in line[0] and value in line[0] and reason in line[0],
              "%s %s is refused with one line naming it (exit %d: %s)" % (option, value, r.returncode, line[0]))
    r = run("good", ["-boom_elements", "4", "-ts_dt", "0.001"])
    check(r.returncode == 0, "-boom_elements 4 -ts_dt 0.001 still runs (exit %d)" % r.returncode)


sys.exit(script_checks.finish(main, results))
