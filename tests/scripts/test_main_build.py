#!/usr/bin/env python3
"""A fresh clone's scripts/main.sh compiles the boomdyn program and nothing
else: no test program, no boomdyn_schema_docs, no fuzzer, no benchmark; and
it installs the packages to build and run, not the tests' (the fuzzer's
clang, meshio, Google Benchmark: scripts/install-deps.sh --tests).

Runs the real scripts/main.sh and scripts/build.sh in a fresh copy of the
tree (the sources linked, scripts/ copied, a fresh build folder; a
stand-in scripts/install-deps.sh) with a `cmake` first on the PATH that
records its arguments, passes the configure step to the real cmake and turns
every `cmake --build` into a dry run (make -n -k), which writes every
compile command of the build into the build log without running it (the
links stop at the missing objects; -k goes on with the other targets). The
checks read the log: what main.sh compiles is boomdyn's sources and no
other. The same is then done for scripts/build.sh without arguments (what
scripts/test.sh runs), whose log must list the test programs: the check
sees a test target when one is built.

Usage: test_main_build.py SOURCE_DIR WORK_DIR
"""
import os
import re
import shutil
import stat
import subprocess
import sys

source, work = (os.path.abspath(p) for p in sys.argv[1:3])
sys.path.insert(0, os.path.join(source, "tests"))
import script_checks  # noqa: E402

results = []
check = script_checks.checker(results)


def fresh_clone(root):
    """A tree at root that looks like a fresh clone: every top-level entry of
    the source linked, except scripts/ (copied, with a stand-in
    install-deps.sh) and build folders, logs and outputs."""
    if os.path.exists(root):
        shutil.rmtree(root)
    os.makedirs(root)
    for name in os.listdir(source):
        if name in (".git", "scripts", "out") or name.startswith("build"):
            continue
        os.symlink(os.path.join(source, name), os.path.join(root, name))
    shutil.copytree(os.path.join(source, "scripts"), os.path.join(root, "scripts"))
    write_script(os.path.join(root, "scripts", "install-deps.sh"),
                 'echo "install-deps $*" >> "%s"\necho "install-deps: (stand-in)"\n' % install_record(root))


def install_record(root):
    return os.path.join(root, "install_deps_calls.txt")


def write_script(path, body):
    with open(path, "w") as f:
        f.write("#!/bin/sh\n" + body)
    os.chmod(path, os.stat(path).st_mode | stat.S_IXUSR | stat.S_IXGRP | stat.S_IXOTH)


def dry_run_cmake(bindir, record):
    """A cmake that records its arguments and makes every --build a dry run (Makefiles: make -n)."""
    real = shutil.which("cmake")
    os.makedirs(bindir, exist_ok=True)
    write_script(os.path.join(bindir, "cmake"),
                 'echo "$*" >> "%s"\n'
                 'case " $* " in *" --build "*) exec "%s" "$@" -- -n -k ;; esac\n'
                 'exec "%s" "$@"\n' % (record, real, real))


def run(root, command, record):
    env = dict(os.environ, PATH=os.path.join(work, "main_build_bin") + os.pathsep + os.environ["PATH"])
    env.pop("CMAKE_GENERATOR", None)  # the dry run is make's -n
    env.pop("BOOMDYN_BUILD_DIR", None)
    for var in ("CMAKE_CXX_COMPILER_LAUNCHER", "CMAKE_C_COMPILER_LAUNCHER"):
        env.pop(var, None)
    if os.path.exists(record):
        os.remove(record)
    done = subprocess.run(command, cwd=root, env=env, capture_output=True, text=True, timeout=600)
    print("$ %s (exit %d; the dry run stops where a link needs the missing objects)\n%s"
          % (" ".join(command), done.returncode, (done.stdout + done.stderr)[-600:]))
    calls = open(record).read().splitlines() if os.path.exists(record) else []
    log = open(os.path.join(root, "build.log")).read() if os.path.exists(os.path.join(root, "build.log")) else ""
    return calls, log


def compiled(log, root):
    """Sources compiled by the build in the log, relative to root."""
    files = re.findall(r"\s-c\s+(\S+\.(?:cpp|cc|c))\b", log)
    return sorted({os.path.relpath(f, root) for f in files})


def compiled_targets(log):
    """CMake targets whose objects the build in the log compiles (-o CMakeFiles/TARGET.dir/...o)."""
    return sorted(set(re.findall(r"\s-o\s+CMakeFiles/([^/\s]+)\.dir/\S+\.o\b", log)))


def main():
    os.makedirs(work, exist_ok=True)
    root = os.path.join(work, "main_build_clone")
    record = os.path.join(work, "main_build_cmake_calls.txt")
    fresh_clone(root)
    dry_run_cmake(os.path.join(work, "main_build_bin"), record)

    calls, log = run(root, ["scripts/main.sh"], record)
    installs = open(install_record(root)).read().splitlines() if os.path.exists(install_record(root)) else []
    check(installs == ["install-deps "], "main.sh installs the packages to build and run, not the tests' (%s)" % installs)
    test_sh = open(os.path.join(source, "scripts", "test.sh")).read()
    check(re.search(r"^scripts/install-deps\.sh --tests$", test_sh, re.M),
          "test.sh installs the tests' packages too (install-deps.sh --tests)")
    builds = [c for c in calls if "--build" in c.split()]
    check(len(builds) == 1, "main.sh runs one cmake --build (%s)" % builds)
    targets = re.findall(r"--target\s+((?:[^-\s]\S*\s*)+)", builds[0]) if builds else []
    named = targets[0].split() if targets else []
    check(named == ["boomdyn"], "main.sh builds the target boomdyn only (asked for: %s)" % (named or "all"))
    sources = compiled(log, root)
    print("main.sh would compile %d sources of the targets %s" % (len(sources), compiled_targets(log)))
    core = [s for s in sources if s.startswith("src/")]
    check("src/app/main.cpp" in sources and len(core) > 50,
          "the dry run lists boomdyn's compiles (%d under src/, src/app/main.cpp among them)" % len(core))
    others = [s for s in sources if not s.startswith("src/") or s.startswith("src/tools/")]
    check(not others, "main.sh compiles nothing but boomdyn's sources (also: %s)" % others[:8])
    check(compiled_targets(log) == ["boomdyn", "boomdyn_core"],
          "main.sh compiles the targets boomdyn and boomdyn_core only (%s)" % compiled_targets(log))

    # What scripts/test.sh builds: everything, so the checks above would see a test target.
    shutil.rmtree(os.path.join(root, "build"), ignore_errors=True)
    calls, log = run(root, ["scripts/build.sh"], record)
    sources = compiled(log, root)
    tests = [s for s in sources if s.startswith("tests/")]
    targets = compiled_targets(log)
    check(len(tests) > 20 and "unit_tests" in targets and "boomdyn_schema_docs" in targets,
          "build.sh without targets (scripts/test.sh) compiles the tests: %d test sources, targets %s"
          % (len(tests), targets))


sys.exit(script_checks.finish(main, results))
