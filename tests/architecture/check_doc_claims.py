#!/usr/bin/env python3
"""Checks that what docs/architecture.md states about the code is true of the tree:

  - the size limit ("no source file under src/ and include/ is over N
    lines"): no such file is longer;
  - the layer table: its layers, in order, are those of
    tests/architecture/check_layers.py, every src/ folder it names belongs to
    that layer there, every src/ folder of check_layers.py is named under its
    layer, and the core headers it names are core there;
  - the table of registered types: its makers are those of
    src/model/physics_types.cpp, in that order, and each file it names
    defines its maker (`PhysicsType maker()`).

    check_doc_claims.py SOURCE_DIR     # the check; exit 1 on a false claim
    check_doc_claims.py --self-test    # doctored copies of the tree must fail
"""
import pathlib
import re
import shutil
import sys
import tempfile

SIZE_CLAIM = re.compile(r"no source file under src/ and include/ is over\s+(\d+)\s+lines")
SOURCE_SUFFIXES = {".cpp", ".hpp", ".h", ".c"}


def table_after(text, header):
    """Rows (lists of cells) of the Markdown table whose header row starts with `header`."""
    lines = text.splitlines()
    for i, line in enumerate(lines):
        if line.replace(" ", "").startswith(header.replace(" ", "")):
            rows = []
            for row in lines[i + 2:]:
                if not row.startswith("|"):
                    break
                rows.append([c.strip() for c in row.strip().strip("|").split("|")])
            return rows
    return None


def load_check_layers(root):
    """ORDER, FOLDER_LAYERS, CORE, HEADER_LAYERS of root's check_layers.py."""
    namespace = {}
    code = (root / "tests" / "architecture" / "check_layers.py").read_text()
    exec(compile(code.split("\ndef ")[0], "check_layers.py", "exec"), namespace)
    return namespace


def check_sizes(root, doc):
    claim = SIZE_CLAIM.search(doc)
    if not claim:
        return ["docs/architecture.md: no size claim 'no source file under src/ and include/ is over N lines' "
                "(the check reads that sentence; keep it or change the check)"], "no size claim"
    limit = int(claim.group(1))
    sizes = sorted(((len(p.read_text(errors="replace").splitlines()), str(p.relative_to(root)))
                    for top in ("src", "include") for p in (root / top).rglob("*") if p.suffix in SOURCE_SUFFIXES),
                   reverse=True)
    over = ["%s: %d lines, over the %d that docs/architecture.md states" % (f, n, limit) for n, f in sizes if n > limit]
    return over, "%d source files, the longest %s with %d lines (limit %d)" % (len(sizes), sizes[0][1], sizes[0][0],
                                                                                limit)


def check_layers(root, doc):
    rows = table_after(doc, "| layer | folder |")
    if not rows:
        return ["docs/architecture.md: no layer table ('| layer | folder | ...')"], "no layer table"
    rules = load_check_layers(root)
    errors = []
    layers = [r[0] for r in rows]
    if layers != rules["ORDER"]:
        errors.append("layer table: layers %s, check_layers.py has %s" % (layers, rules["ORDER"]))
    named = {}
    for layer, folders, *_ in rows:
        for folder in re.findall(r"src/([a-z_]+)", folders):
            named[folder] = layer
            if rules["FOLDER_LAYERS"].get(folder) != layer:
                errors.append("layer table: src/%s under %s, check_layers.py puts it in %s"
                              % (folder, layer, rules["FOLDER_LAYERS"].get(folder)))
        for group in re.findall(r"include/boomdyn/\{([a-z_,]+)\}\.hpp", folders):
            for header in group.split(","):
                actual = "core" if header in rules["CORE"] else rules["HEADER_LAYERS"].get(header)
                if actual != layer:
                    errors.append("layer table: boomdyn/%s.hpp under %s, check_layers.py puts it in %s"
                                  % (header, layer, actual))
    for folder, layer in rules["FOLDER_LAYERS"].items():
        if folder not in named:
            errors.append("layer table: src/%s (%s in check_layers.py) is not named" % (folder, layer))
    return errors, "%d layers, %d src/ folders" % (len(rows), len(named))


def check_types(root, doc):
    rows = table_after(doc, "| maker | file |")
    if not rows:
        return ["docs/architecture.md: no table of registered types ('| maker | file |')"], "no type table"
    registry = (root / "src" / "model" / "physics_types.cpp").read_text()
    makers = re.findall(r"^\s*X\((\w+)\)", registry, re.M)
    listed = [r[0].strip("`") for r in rows]
    errors = []
    if listed != makers:
        errors.append("type table: makers %s, src/model/physics_types.cpp registers %s" % (listed, makers))
    for maker, path, *_ in ((r[0].strip("`"), r[1]) for r in rows):
        f = root / path
        if not f.is_file():
            errors.append("type table: %s: no file %s" % (maker, path))
        elif not re.search(r"PhysicsType\s+%s\s*\(\s*\)\s*\{?" % maker, f.read_text()):
            errors.append("type table: %s does not define PhysicsType %s()" % (path, maker))
    return errors, "%d registered types" % len(makers)


def check(root):
    doc = (root / "docs" / "architecture.md").read_text()
    errors = []
    for part in (check_sizes, check_layers, check_types):
        found, summary = part(root, doc)
        print("%-12s %s%s" % (part.__name__[6:], summary, "" if found else ": ok"))
        errors += found
    return errors


def self_test(source):
    """Each doctored copy of the tree must be reported."""
    doctorings = {
        "a file over the limit": lambda r: (r / "src" / "model" / "long_file.cpp").write_text("int x;\n" * 1500),
        "a lower size limit": lambda r: edit(r / "docs" / "architecture.md", "is over 1000 lines", "is over 500 lines"),
        "the size claim gone": lambda r: edit(r / "docs" / "architecture.md", "is over 1000 lines", "is small"),
        "a layer renamed": lambda r: edit(r / "docs" / "architecture.md", "| solvers | src/solvers", "| solver | src/solvers"),
        "a folder in the wrong layer": lambda r: edit(r / "docs" / "architecture.md", "| analysis | src/analysis |",
                                                      "| analysis | src/analysis, src/io |"),
        "a type registered but not listed": lambda r: edit(r / "src" / "model" / "physics_types.cpp",
                                                           "X(springType)", "X(springType) \\\n  X(winchType)"),
        "a type in the wrong file": lambda r: edit(r / "docs" / "architecture.md", "| `pinType` | src/constraints/pin_type.cpp",
                                                   "| `pinType` | src/constraints/clamp_type.cpp"),
    }
    failures = 0
    for what, doctor in doctorings.items():
        with tempfile.TemporaryDirectory() as d:
            root = pathlib.Path(d)
            for top in ("src", "include", "docs", "tests/architecture"):
                shutil.copytree(source / top, root / top)
            doctor(root)
            found = check(root)
        seen = bool(found)
        print("self-test: %s: %s %s" % (what, "seen" if seen else "NOT SEEN", found[:2]))
        failures += not seen
    found = check(source)
    print("self-test: the tree as it is: %s" % ("passes" if not found else "FAILS"))
    return 1 if failures or found else 0


def edit(path, old, new):
    text = path.read_text()
    if old not in text:
        raise SystemExit("self-test: '%s' not in %s (update the self-test)" % (old, path))
    path.write_text(text.replace(old, new, 1))


def main(argv):
    if argv[1:2] == ["--self-test"]:
        return self_test(pathlib.Path(argv[2] if len(argv) > 2 else pathlib.Path(__file__).resolve().parents[2]))
    errors = check(pathlib.Path(argv[1]))
    for e in errors:
        print("FAIL " + e)
    print("docs/architecture.md: %s" % ("every checked claim holds" if not errors else "%d false claims" % len(errors)))
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
