#!/usr/bin/env python3
"""Checks that dependencies run one way (docs/architecture.md):

    core -> physics (bodies, constraints, forces) -> model (+ registered types)
         -> solvers -> analysis -> io -> simulation -> app

A file may include boomdyn headers of its own layer or a lower one. A
header's layer is the layer of the source file that implements it (same
stem), or the one given in HEADER_LAYERS for header-only concepts. Prints
every backward include and exits 1 if there is one.
"""
import pathlib
import re
import sys

ORDER = ["core", "physics", "model", "solvers", "analysis", "io", "simulation", "app"]
FOLDER_LAYERS = {
    "bodies": "physics", "constraints": "physics", "forces": "physics", "sensors": "model",
    "model": "model", "solvers": "solvers", "analysis": "analysis", "io": "io",
    "simulation": "simulation", "app": "app", "tools": "app",
}
# Plain data and contracts that everything may use.
CORE = {"time_function", "scene", "work_item", "component_spec", "type_schema", "output_channel", "type_event",
        "gather", "lanes", "log_events", "petsc_handle", "body", "spatial_body", "constraint", "vec2", "version"}
# Header-only concepts, by the layer they belong to.
HEADER_LAYERS = {
    "schema": "core", "slack_drive": "physics", "pad_gap": "physics", "physics_type": "model", "model_builder": "model",
    "post_step_hook": "model", "state_archive": "solvers", "monitor": "simulation", "monitors": "simulation",
    "schedule": "simulation",
}
INCLUDE = re.compile(r'^\s*#\s*include\s+"boomdyn/([a-z0-9_]+)\.hpp"', re.M)


def file_layer(path: pathlib.Path, root: pathlib.Path) -> str:
    rel = path.relative_to(root)
    if rel.parts[0] == "src":
        layer = FOLDER_LAYERS.get(rel.parts[1])
        if layer is None:
            sys.exit(f"check_layers: no layer for folder src/{rel.parts[1]} (add it to FOLDER_LAYERS)")
        # A file that defines a registered type is glue: it builds into the
        # Model (its kernel may live in the same file, e.g. distance.cpp).
        text = path.read_text()
        if layer == "physics" and ('"boomdyn/physics_type.hpp"' in text or '"boomdyn/model_builder.hpp"' in text):
            return "model"
        return layer
    return header_layer(path.stem, root)


def header_layer(stem: str, root: pathlib.Path) -> str:
    if stem in CORE:
        return "core"
    if stem in HEADER_LAYERS:
        return HEADER_LAYERS[stem]
    impl = list((root / "src").glob(f"*/{stem}.cpp"))
    if len(impl) == 1:
        return file_layer(impl[0], root)
    # Header-only concept: the layer of the folder that uses it most is not a
    # rule; ask for an explicit entry instead of guessing.
    return "unknown"


def self_test() -> int:
    """The check must see a backward include: a solver that includes an io header."""
    import tempfile
    with tempfile.TemporaryDirectory() as d:
        root = pathlib.Path(d)
        for rel, text in {"src/io/results_writer.cpp": '#include "boomdyn/results_writer.hpp"\n',
                          "src/solvers/newton_solver.cpp": '#include "boomdyn/results_writer.hpp"\n',
                          "include/boomdyn/results_writer.hpp": "", "include/boomdyn/newton_solver.hpp": ""}.items():
            (root / rel).parent.mkdir(parents=True, exist_ok=True)
            (root / rel).write_text(text)
        found = check(root)
    ok = len(found) == 1 and "newton_solver.cpp (solvers) includes boomdyn/results_writer.hpp (io)" in found[0]
    print("self-test:", "ok" if ok else f"FAILED, found {found}")
    return 0 if ok else 1


def check(root: pathlib.Path) -> list:
    files = sorted((root / "src").rglob("*.cpp")) + sorted((root / "src").rglob("*.hpp")) + \
        sorted((root / "include" / "boomdyn").glob("*.hpp"))
    problems = []
    for f in files:
        own = file_layer(f, root)
        if own == "unknown":
            problems.append(f"{f.relative_to(root)}: header-only concept without a layer (add it to CORE or give it a .cpp)")
            continue
        for inc in INCLUDE.findall(f.read_text()):
            layer = header_layer(inc, root)
            if layer == "unknown":
                problems.append(f"{f.relative_to(root)}: includes boomdyn/{inc}.hpp, which has no layer")
            elif ORDER.index(layer) > ORDER.index(own):
                problems.append(f"{f.relative_to(root)} ({own}) includes boomdyn/{inc}.hpp ({layer}): dependency against the direction")
    return problems


def main() -> int:
    if len(sys.argv) > 1 and sys.argv[1] == "--self-test":
        return self_test()
    root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else ".").resolve()
    problems = check(root)
    for p in problems:
        print(p)
    print(f"check_layers: {len(problems)} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
