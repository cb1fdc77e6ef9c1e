#!/usr/bin/env python3
"""Time stepping through PETSc TS (issue 12): the -ts_ options a PETSc user
knows do what PETSc documents, and those that cannot apply are refused.
1. -ts_monitor prints PETSc's monitor line per step ("N TS dt H time T");
2. -ts_view names the TS type boomalpha and its TSAdapt boomalpha;
3. -ts_max_steps 5 stops after 5 steps (exit 0);
4. -ts_exact_final_time: matchstep ends on max_time, stepover passes it;
5. -ts_max_snes_failures 1 ends a run at its first Newton failure;
6. -ts_type bdf, -ts_adapt_type basic, -ts_exact_final_time interpolate,
   -ts_rtol, and -ts_adapt_type none with -boom_adaptive_tol are refused
   with a message.
Usage: test_ts_options.py BOOMDYN_EXECUTABLE SOURCE_DIR WORK_DIR"""
import os
import re
import subprocess
import sys

import h5py
import numpy as np
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import script_checks  # noqa: E402

boomdyn, source, work = sys.argv[1:4]
work = os.path.join(work, "test_output", "ts_options")
os.makedirs(work, exist_ok=True)
pendulum = os.path.join(source, "inputs", "flexible_pendulum.yaml")  # dt = 1 ms
two_beams = os.path.join(source, "inputs", "two_beams_pinned.yaml")  # dt = 1 ms
results = []


check = script_checks.checker(results)


def run(scene, name, args):
    out = os.path.join(work, name + ".h5")
    r = subprocess.run([boomdyn, scene, "-o", out, "-boom_overwrite", "-boom_quiet"] + args,
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    return r.returncode, r.stdout, out


def times(path):
    with h5py.File(path) as f:
        return np.array(f["steps/time"])


def main():
    code, text, _ = run(pendulum, "monitor", ["-ts_max_time", "0.01", "-ts_monitor"])
    lines = re.findall(r"^\s*(\d+) TS dt (\S+) time (\S+)$", text, re.M)
    check(code == 0, "-ts_monitor: run exits 0 (got %d)" % code)
    check([int(n) for n, _, _ in lines] == list(range(11)),
          "-ts_monitor: one PETSc monitor line per step, steps 0..10 (got %s)" % [n for n, _, _ in lines])
    check(lines and abs(float(lines[-1][2]) - 0.01) < 1e-12, "-ts_monitor: the last line is at t = 0.01 s")

    code, text, _ = run(pendulum, "view", ["-ts_max_time", "0.002", "-ts_view"])
    check(code == 0 and re.search(r"TS Object:.*\n\s+type: boomalpha", text),
          "-ts_view names the TS type boomalpha")
    check(re.search(r"TSAdapt Object:.*\n\s+type: boomalpha", text), "-ts_view names the TSAdapt type boomalpha")

    code, text, out = run(pendulum, "max_steps", ["-ts_max_steps", "5"])
    t = times(out)
    check(code == 0, "-ts_max_steps 5: exits 0 (got %d: %s)" % (code, text.strip()[-200:]))
    check(len(t) == 6 and abs(t[-1] - 0.005) < 1e-12,
          "-ts_max_steps 5: 5 steps after the initial row, last at 0.005 s (got %d rows, last %s)" % (len(t), t[-1:]))
    with h5py.File(out) as f:
        status = f["summary"].attrs["status"]
        status = status.decode() if isinstance(status, bytes) else str(status)
    check("-ts_max_steps" in status, "-ts_max_steps 5: /summary/status says the step limit ended the run (got %r)" % status)

    code, _, out = run(pendulum, "matchstep", ["-ts_max_time", "0.0105"])
    t = times(out)
    check(code == 0 and abs(t[-1] - 0.0105) < 1e-15 and abs(t[-1] - t[-2] - 0.0005) < 1e-12,
          "-ts_exact_final_time matchstep (default): a last half step ends on 0.0105 s (got %s)" % t[-2:])
    code, _, out = run(pendulum, "stepover", ["-ts_max_time", "0.0105", "-ts_exact_final_time", "stepover"])
    t = times(out)
    check(code == 0 and abs(t[-1] - 0.011) < 1e-12,
          "-ts_exact_final_time stepover: full steps, the last ends past max_time at 0.011 s (got %s)" % t[-1:])

    # -snes_max_it 2 makes Newton fail now and then; the default controller cuts and goes on.
    code, text, _ = run(two_beams, "cuts", ["-ts_max_time", "0.05", "-snes_max_it", "2"])
    check(code == 0 and "rejected" in text, "-snes_max_it 2: steps are cut and the run completes")
    code, text, _ = run(two_beams, "max_snes_failures", ["-ts_max_time", "0.05", "-snes_max_it", "2",
                                                         "-ts_max_snes_failures", "1"])
    check(code != 0 and "-ts_max_snes_failures 1 reached" in text,
          "-ts_max_snes_failures 1: the first Newton failure ends the run with a message")

    refused = [
        (["-ts_type", "bdf"], "-ts_type bdf is not supported"),
        (["-ts_adapt_type", "basic"], "-ts_adapt_type basic is not supported"),
        (["-ts_exact_final_time", "interpolate"], "-ts_exact_final_time interpolate is not supported"),
        (["-ts_rtol", "1e-3"], "-ts_rtol does not apply"),
        (["-ts_adapt_type", "none", "-boom_adaptive_tol", "1e-6"], "-boom_adaptive_tol needs -ts_adapt_type boomalpha"),
    ]
    for i, (args, message) in enumerate(refused):
        code, text, _ = run(pendulum, "refused%d" % i, ["-ts_max_time", "0.01"] + args)
        check(code != 0 and message in text and "boomdyn: error:" in text,
              "%s: refused with '%s' (exit %d)" % (" ".join(args), message, code))
    code, text, _ = run(pendulum, "none", ["-ts_max_time", "0.01", "-ts_adapt_type", "none"])
    check(code == 0, "-ts_adapt_type none: fixed steps, run completes")


sys.exit(script_checks.finish(main, results))
