#!/usr/bin/env python3
"""Old against new binary, whole processes, in alternating runs (issue 18).

For each case (a scene and options) the two binaries run one after the other,
`--repeat` times, so that a change of the machine's load hits both alike. Per
run: wall time, user+sys CPU time of the process (getrusage of the child) and,
from -log_view, the time in the time steps (BoomStep), the eigen-analyses
(BoomEigen), the state snapshots (BoomOutput), the factorizations (PCSetUp) and the residual evaluations
(SNESFunctionEval). The table gives the median and the range of each.

  /usr/bin/python3 benchmarks/compare_binaries.py --old /work/main/build/boomdyn --new build/boomdyn \\
      [--repeat 3] [--cases paper paper_notrack cantilever startup] [--elements 8 32 128 512 2048]
      [--cantilever-variants defaults reuse full] [--out FILE.md]

Cases: `paper` (inputs/paper_extraction.yaml with its tracking every 10 ms),
`paper_notrack` (the same, -boom_tracking_interval 0), `pads` and
`rope_pair` (inputs/paper_extraction_pads.yaml, paper_extraction_rope_pair.yaml,
as they are), `interval` (the paper scene with tracking every 1, 10 and 100 ms),
`cantilever` (the 2 m cantilever inputs/cantilever_dynamic.yaml, 1000 steps, N
elements; default options of each binary, both with -boom_jacobian_reuse 1 and
both with -boom_jacobian_reuse 0), `startup` (the cantilever with 8 elements,
one step).
"""
import argparse
import os
import re
import resource
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
EVENTS = ["BoomStep", "BoomEigen", "BoomOutput", "PCSetUp", "SNESFunctionEval"]


def log_times(path):
    out = {}
    try:
        text = open(path).read()
    except OSError:
        return out
    for e in EVENTS:
        m = re.search(r"^%s\s+(\d+)\s+\S+\s+(\S+)" % e, text, re.M)
        out[e] = (int(m.group(1)), float(m.group(2))) if m else (0, 0.0)
    return out


def run_once(binary, args, tmp):
    log = os.path.join(tmp, "log.txt")
    if os.path.exists(log):
        os.remove(log)
    cmd = [binary] + args + ["-o", os.path.join(tmp, "out.h5"), "-boom_overwrite", "-boom_quiet", "-log_view", ":" + log]
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return wall, cpu, log_times(log)


def cases(names, elements, variants=("defaults", "reuse", "full")):
    paper = os.path.join(ROOT, "inputs", "paper_extraction.yaml")
    cantilever = os.path.join(ROOT, "inputs", "cantilever_dynamic.yaml")
    out = []
    if "startup" in names:
        out.append(("1 step, cantilever 8 el.", [cantilever, "-boom_elements", "8", "-ts_max_steps", "1"], []))
    if "paper" in names:
        out.append(("paper extraction, tracking 10 ms", [paper], []))
    if "paper_notrack" in names:
        out.append(("paper extraction, no tracking", [paper, "-boom_tracking_interval", "0"], []))
    for name in ("pads", "rope_pair"):
        if name in names:
            scene = os.path.join(ROOT, "inputs", "paper_extraction_%s.yaml" % name)
            out.append(("paper extraction with %s" % name.replace("_", " "), [scene], []))
    if "interval" in names:
        for interval in ("0.001", "0.01", "0.1"):
            out.append(("paper extraction, tracking every %g ms" % (1000 * float(interval)),
                        [paper, "-boom_tracking_interval", interval], []))
    if "cantilever" in names:
        for n in elements:
            base = [cantilever, "-boom_elements", str(n), "-boom_state_interval", "0"]
            if "defaults" in variants:
                out.append(("cantilever %d el., defaults" % n, base, []))
            if "reuse" in variants:
                out.append(("cantilever %d el., both with reuse" % n, base + ["-boom_jacobian_reuse", "1"], []))
            if "full" in variants:
                out.append(("cantilever %d el., both full Newton" % n, base + ["-boom_jacobian_reuse", "0"], []))
    return out


def fmt(values, digits=3):
    med = statistics.median(values)
    return "%.*f (%.*f–%.*f)" % (digits, med, digits, min(values), digits, max(values))


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--old", default="/work/main/build/boomdyn")
    p.add_argument("--new", default=os.path.join(ROOT, "build", "boomdyn"))
    p.add_argument("--repeat", type=int, default=3)
    p.add_argument("--cases", nargs="+", default=["startup", "paper", "paper_notrack", "cantilever"])
    p.add_argument("--elements", type=int, nargs="+", default=[8, 32, 128, 512, 2048])
    p.add_argument("--cantilever-variants", nargs="+", default=["defaults", "reuse", "full"],
                   choices=["defaults", "reuse", "full"], help="which option sets the cantilever case runs")
    p.add_argument("--out", help="append the markdown table to this file")
    a = p.parse_args()
    env_load = os.getloadavg()
    rows = ["| case | binary | wall [s] | user+sys [s] | time steps [s] | eigen [s] | output [s] | factorizations | residuals | new/old wall |",
            "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|"]
    with tempfile.TemporaryDirectory() as tmp:
        for label, args, _ in cases(a.cases, a.elements, a.cantilever_variants):
            res = {"old": [], "new": []}
            for _ in range(a.repeat):
                for which in ("old", "new"):
                    res[which].append(run_once(getattr(a, which), args, tmp))
            med_old = statistics.median(r[0] for r in res["old"])
            for which in ("old", "new"):
                rs = res[which]
                ev = rs[-1][2]
                ratio = statistics.median(r[0] for r in rs) / med_old
                rows.append("| %s | %s | %s | %s | %s | %s | %s | %d | %d | %s |" % (
                    label, which, fmt([r[0] for r in rs]), fmt([r[1] for r in rs]),
                    fmt([r[2].get("BoomStep", (0, 0))[1] for r in rs]),
                    fmt([r[2].get("BoomEigen", (0, 0))[1] for r in rs]),
                    fmt([r[2].get("BoomOutput", (0, 0))[1] for r in rs]), ev.get("PCSetUp", (0, 0))[0],
                    ev.get("SNESFunctionEval", (0, 0))[0], "%.2f" % ratio if which == "new" else ""))
                print(rows[-1], flush=True)
    text = "\n".join(rows) + "\n\nLoad average at the start: %.1f %.1f %.1f (2 cores).\n" % env_load
    print(text)
    if a.out:
        with open(a.out, "a") as f:
            f.write(text)


if __name__ == "__main__":
    sys.exit(main())
