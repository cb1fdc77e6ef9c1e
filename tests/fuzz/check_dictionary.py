#!/usr/bin/env python3
"""The fuzzer's dictionary (tests/fuzz/scene.dict) names every scene key.

libFuzzer splices dictionary words into its inputs; a key missing there is
reached only by chance, so the reader's checks of that key go unfuzzed. The
keys are those of the generated schema tables in docs/scenes.md and every key
written in inputs/*.yaml and tests/fuzz/seeds/*.yaml (block and flow style).

Usage: check_dictionary.py SOURCE_DIR      exit 0: covered; 1: keys missing (listed)."""
import glob
import os
import re
import sys

source = sys.argv[1]
dictionary = open(os.path.join(source, "tests", "fuzz", "scene.dict")).read()
listed = set(re.findall(r'"([A-Za-z_0-9]+): "', dictionary))

keys = {}  # key -> first file that has it
for line in open(os.path.join(source, "docs", "scenes.md")):
    m = re.match(r"\| `([A-Za-z_0-9]+)`", line)
    if m:
        keys.setdefault(m.group(1), "docs/scenes.md")
scenes = glob.glob(os.path.join(source, "inputs", "*.yaml")) + glob.glob(os.path.join(source, "tests", "fuzz", "seeds",
                                                                                          "*.yaml"))
for scene in sorted(scenes):
    for line in open(scene):
        line = line.split("#", 1)[0]
        for key in re.findall(r"(?:^\s*(?:-\s+)?|[{,]\s*)([A-Za-z_][A-Za-z_0-9]*):(?:\s|$)", line):
            keys.setdefault(key, os.path.relpath(scene, source))

missing = sorted(k for k in keys if k not in listed)
for k in missing:
    print('missing: kw_%s="%s: "   (from %s)' % (k, k, keys[k]))
print("%d scene keys, %d in the dictionary, %d missing" % (len(keys), len(keys) - len(missing), len(missing)))
sys.exit(1 if missing else 0)
