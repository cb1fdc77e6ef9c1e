#!/usr/bin/env python3
"""benchmarks/plot_performance.py: draws the two plots of docs/performance.md
from benchmarks/results/performance.csv and from rows written the way
benchmarks/run_scaling.py --csv writes them, and refuses a malformed CSV with
the file and line.

Run: python3 tests/postprocess/test_plot_performance.py  (exit code 1 on any failure)
"""

import csv
import os
import subprocess
import sys
import tempfile
from pathlib import Path

import matplotlib
matplotlib.use("Agg")
import matplotlib.image as mpimg  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "benchmarks"))
sys.path.insert(0, str(ROOT / "tests"))
import run_scaling  # noqa: E402  (needs the path above)
from script_checks import checker, finish  # noqa: E402

PLOT = ROOT / "benchmarks" / "plot_performance.py"
RESULTS = ROOT / "benchmarks" / "results" / "performance.csv"
PLOTS = ["performance_elements.png", "performance_ranks.png"]
results = []
check = checker(results)


def plot(csv_path, out):
    return subprocess.run([sys.executable, str(PLOT), "--csv", str(csv_path), "--out", str(out)],
                          capture_output=True, text=True)


def images_written(out, what):
    for name in PLOTS:
        path = Path(out) / name
        ok = path.is_file() and path.stat().st_size > 0
        check(ok, "%s: %s written" % (what, name))
        if ok:
            h, w = mpimg.imread(str(path)).shape[:2]
            check((w, h) == (700, 480), "%s: %s is 700 x 480 pixels (got %d x %d)" % (what, name, w, h))


def main():
    with open(RESULTS, newline="") as f:
        rows = list(csv.DictReader(f))
        header = list(rows[0].keys()) if rows else []
    check(header == run_scaling.CSV_COLUMNS,
          "benchmarks/results/performance.csv has the columns run_scaling.py --csv writes")
    check(all(r["source"].strip() for r in rows), "every row of benchmarks/results/performance.csv names its source")
    check({(r["scene"], r["elements"]) for r in rows if r["ranks"] == "2"} <=
          {(r["scene"], r["elements"]) for r in rows if r["ranks"] == "1"},
          "every two-rank row has its one-rank counterpart (the ranks plot pairs them)")

    with tempfile.TemporaryDirectory() as tmp:
        r = plot(RESULTS, tmp)
        check(r.returncode == 0, "plots of benchmarks/results/performance.csv (exit %d: %s)" % (r.returncode, r.stderr[-300:]))
        images_written(tmp, "recorded figures")

        fresh = os.path.join(tmp, "fresh.csv")
        for n, ranks, ms in ((1000, 1, 0.4), (10000, 1, 4.0), (1000, 2, 0.25), (10000, 2, 2.2)):
            run_scaling.append_csv(fresh, dict(scene="benchmarks/scenes/long_boom.yaml", elements=n, ranks=ranks,
                                               options="default", steps=50, timed="steps", per_step_ms=ms,
                                               per_element_step_us=1e3 * ms / n, source="test"))
        with open(fresh) as f:
            lines = f.read().splitlines()
        check(len(lines) == 5 and lines[0] == ",".join(run_scaling.CSV_COLUMNS),
              "run_scaling.append_csv writes the header once, then one row per run (%d lines)" % len(lines))
        out = os.path.join(tmp, "fresh")
        r = plot(fresh, out)
        check(r.returncode == 0, "plots of a CSV in run_scaling.py's format (exit %d: %s)" % (r.returncode, r.stderr[-300:]))
        images_written(out, "run_scaling.py rows")

        bad = os.path.join(tmp, "bad.csv")
        with open(bad, "w") as f:
            f.write(",".join(run_scaling.CSV_COLUMNS) + "\n")
            f.write("benchmarks/scenes/long_boom.yaml,1000,1,default,50,steps,fast,,,,,,,,,,test\n")
        r = plot(bad, os.path.join(tmp, "bad"))
        check(r.returncode != 0 and "bad.csv, line 2" in r.stderr and "per_step_ms" in r.stderr,
              "a non-number in per_step_ms is refused naming the file, line and column: %r" % r.stderr.strip()[-200:])
        check(not os.path.exists(os.path.join(tmp, "bad", PLOTS[0])), "no plot is written from a malformed CSV")


if __name__ == "__main__":
    sys.exit(finish(main, results))
