#!/usr/bin/env python3
"""`boomdyn -help` lists every boomdyn option that README.md and docs/options.md document, with
its default; with a scene it also lists the scene's per-body options
(-boom_elements_<body>) and the TS type of the run.
Usage: test_help.py BOOMDYN_EXECUTABLE SOURCE_DIR WORK_DIR"""
import os
import re
import subprocess
import sys

boomdyn, source, work = sys.argv[1:4]
sys.path.insert(0, os.path.join(source, "tests"))
import script_checks  # noqa: E402

results = []


check = script_checks.checker(results)


def main():
    readme = ""
    for doc in ("README.md", "docs/options.md"):
        with open(os.path.join(source, doc)) as f:
            readme += f.read()
    documented = sorted(set(re.findall(r"-boom_[a-z_]+[a-z]", readme)) - {"-boom_elements_"})
    check(len(documented) >= 15, "README.md and docs/options.md document the boomdyn options (%d found)" % len(documented))
    text = subprocess.run([boomdyn, "-help"], capture_output=True, text=True).stdout
    listed = set(re.findall(r"^\s+(-boom_[a-z_]+)\s*[:<]", text, re.M))
    missing = [o for o in documented if o not in listed]
    check(not missing, "boomdyn -help lists every documented -boom_ option with a default (missing: %s)" % missing)
    scene = os.path.join(source, "inputs", "paper_extraction.yaml")
    text = subprocess.run([boomdyn, scene, "-help", "-ts_max_time", "0.002", "-boom_quiet", "-boom_overwrite",
                           "-o", os.path.join(work, "help.h5")], capture_output=True, text=True).stdout
    for body in ("boom1", "boom2", "boom3"):
        check(re.search(r"^\s+-boom_elements_%s <" % body, text, re.M), "with a scene: -boom_elements_%s listed" % body)
    check(re.search(r"^\s+-ts_type <now boomalpha", text, re.M), "with a scene: the TS type boomalpha listed")


sys.exit(script_checks.finish(main, results))
