#!/usr/bin/env python3
"""docs/tutorial.md is a test (issue 39 item 3): its scene, commands and printed
numbers cannot drift from what the program does.

1. The ```yaml blocks of the page, in order, are the committed scene
   docs/tutorial/boom.yaml, byte for byte.
2. Every ```sh block runs, command by command, and every ```python block as
   one script, in a scratch folder that mirrors the source tree (docs/ and
   postprocess/ link to the sources, build/boomdyn to this build's binary),
   so the commands run exactly as printed; each must exit 0.
   `/usr/bin/python3` is replaced by this test's Python (BOOMDYN_PYTHON);
   `mpiexec` may run as root (OMPI_ALLOW_RUN_AS_ROOT) and oversubscribe.
3. A ```text block right after a ```sh or ```python block is what it prints:
   each of its lines must appear in the output, in order (`...` lines stand
   for output not shown). Words must match exactly, except that a number
   must agree to 0.1 % or one unit in its last digit shown, whichever is
   larger; `< X` stands for a number below X (round-off, which differs from
   machine to machine) and `*` for one or more words (wall times).
4. The closed form that the page's numbers are checked against is itself
   right: the tip stiffness of docs/tutorial/boom_results.py's
   telescope_compliance (Euler-Bernoulli) against a static boomdyn run of
   the tutorial's two booms under a small tip load, rigid joints, no gravity.
   And plot_run.py's contact forces of the padded joints peak at the run's
   design numbers (the pad forces, not another constraint's multiplier).
5. The page has no other kind of block (a ```bash block would escape the
   test) and runs each step of the tutorial: one and two ranks, the Python
   reader, the plots and the mesh study.
Usage: test_tutorial.py BOOMDYN SOURCE_DIR BINARY_DIR"""
import os
import re
import shutil
import subprocess
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import script_checks  # noqa: E402

RTOL = 1e-3
# A number standing alone, not part of a name (j2, x86-64) or a version (0.1.0).
TOKEN = re.compile(r"(?<![\w.])([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)(?![\w.])")


def blocks(markdown):
    """The fenced blocks of the page: [(info string, text, first line number)]."""
    found, lines = [], markdown.splitlines(keepends=True)
    k = 0
    while k < len(lines):
        m = re.match(r"^```(\S*)\s*$", lines[k])
        if m:
            start, body = k + 1, []
            k += 1
            while not lines[k].startswith("```"):
                body.append(lines[k])
                k += 1
            found.append((m.group(1), "".join(body), start + 1))
        k += 1
    return found


def commands(text):
    """The commands of a sh block: comment and blank lines dropped, `\\` joins lines."""
    out, current = [], ""
    for line in text.splitlines():
        if not current and (not line.strip() or line.lstrip().startswith("#")):
            continue
        current += line.rstrip()
        if current.endswith("\\"):
            current = current[:-1] + " "
            continue
        out.append(current)
        current = ""
    return out


def number(text):
    """(value, unit of its last digit) of a number as printed."""
    mantissa, _, exponent = text.lower().partition("e")
    decimals = len(mantissa.split(".")[1]) if "." in mantissa else 0
    return float(text), 10.0 ** ((int(exponent) if exponent else 0) - decimals)


def word_matches(expected, actual, bound=None):
    """One whitespace-separated word: the same text around the same numbers
    (within RTOL or one unit in the last digit shown), or, with `bound`, a
    number below it in place of the expected one."""
    e_parts, a_parts = TOKEN.split(expected), TOKEN.split(actual)
    if len(e_parts) != len(a_parts):
        return False
    for k, (e, a) in enumerate(zip(e_parts, a_parts)):
        if k % 2 == 0:  # text between numbers
            if e != a:
                return False
        elif bound is not None:
            if not float(a) < bound:
                return False
        else:
            value, unit = number(e)
            if abs(float(a) - value) > max(RTOL * abs(value), unit):
                return False
    return True


def line_matches(expected, actual):
    """Whether `actual` is `expected` within the rules of the docstring."""
    e, a = expected.split(), actual.split()

    def match(i, j):
        if i == len(e):
            return j == len(a)
        if e[i] == "*":  # one or more words
            return any(match(i + 1, k) for k in range(j + 1, len(a) + 1))
        if e[i] == "<" and i + 1 < len(e):
            return j < len(a) and word_matches(e[i + 1], a[j], number(TOKEN.findall(e[i + 1])[0])[0]) \
                and match(i + 2, j + 1)
        return j < len(a) and word_matches(e[i], a[j]) and match(i + 1, j + 1)
    return match(0, 0)


def check_output(expected_block, output, check, where):
    actual = [line for line in output.splitlines() if line.strip()]
    position = 0
    for line in expected_block.splitlines():
        if not line.strip() or line.strip() == "...":
            continue
        for k in range(position, len(actual)):
            if line_matches(line, actual[k]):
                position = k + 1
                check(True, "%s: '%s'" % (where, line.strip()))
                break
        else:
            check(False, "%s: '%s' not printed" % (where, line.strip()))


def mirror(source, build_binary, work):
    """A folder in which the page's relative paths (docs/, postprocess/, build/boomdyn) work."""
    if os.path.isdir(work):
        shutil.rmtree(work)
    os.makedirs(os.path.join(work, "build"))
    for name in ("docs", "postprocess"):
        os.symlink(os.path.join(source, name), os.path.join(work, name))
    os.symlink(os.path.abspath(build_binary), os.path.join(work, "build", "boomdyn"))


STIFFNESS_SCENE = """name: tutorial-tip-stiffness
analysis: static
bodies:
  - {name: base, length: 5.0, elements: 10, origin: [0, 0], section: {E: 2.1e11, A: 7.744e-3, I: 9.8770005e-5, rho: 7850}}
  - {name: fly, length: 5.0, elements: 10, origin: [0.5, 0], section: {E: 2.1e11, A: 4.896e-3, I: 4.6226432e-5, rho: 7850}}
constraints:
  - {type: clamp, name: root, body: base, at: start, angle: 0}
  - {type: sliding_joint, name: front, body: base, at: end, track: fly}
  - {type: sliding_joint, name: rear, body: fly, at: start, track: base}
  - {type: extraction_drive, name: held, joint: rear, displacement: 0}
loads:
  - {type: point_force, body: fly, at: end, force: [0, -100]}
output:
  sensors:
    - {name: tip, body: fly, at: end}
"""


def check_tip_stiffness(boomdyn, source, work, check):
    """telescope_compliance against boomdyn: 100 N at the tip of the tutorial's booms."""
    import h5py
    sys.path.insert(0, os.path.join(source, "docs", "tutorial"))
    import boom_results
    scene = os.path.join(work, "tip_stiffness.yaml")
    with open(scene, "w") as f:
        f.write(STIFFNESS_SCENE)
    out = os.path.join(work, "tip_stiffness.h5")
    subprocess.run([boomdyn, scene, "-o", out, "-boom_quiet", "-boom_overwrite"], check=True)
    with h5py.File(out, "r") as f:
        deflection = -f["sensors/tip/position"][-1, 1]
    E = 2.1e11
    compliance, _, _ = boom_results.telescope_compliance({"length": 5.0, "EI": E * 9.8770005e-5},
                                                         {"length": 5.0, "EI": E * 4.6226432e-5, "origin": 0.5})
    error = abs(deflection / 100 - compliance) / compliance
    # The elements are exact at their nodes for point loads there (the pads,
    # the tip), so only the geometric nonlinearity of a 0.25 mm deflection is
    # left (measured 1.5e-9).
    check(error < 1e-6, "tip stiffness: boomdyn %.6g N/m, telescope_compliance %.6g N/m (%.1e apart, < 1e-6)"
          % (100 / deflection, 1 / compliance, error))


def check_pad_forces(source, work, check):
    """plot_run.py's contact-force plot shows the pads' forces (a padded
    sliding joint has one multiplier row, so its 'second row' would be the
    next constraint's): the peaks are the design numbers of the run."""
    import h5py
    sys.path.insert(0, os.path.join(source, "postprocess"))
    import plot_run
    with h5py.File(os.path.join(work, "tutorial_out", "boom.h5"), "r") as f:
        for joint, force in plot_run.normal_forces(f).items():
            peak = f["summary"].attrs["design.joint_resultants.%s.peak_normal_force_N" % joint]
            check(abs(np.abs(force).max() - peak) <= 1e-9 * peak,
                  "plot_run.py: pad '%s' peaks at %.1f N, its design number %.1f N" % (joint, np.abs(force).max(), peak))


def main():
    boomdyn, source, binary = sys.argv[1:4]
    page = open(os.path.join(source, "docs", "tutorial.md")).read()
    found = blocks(page)
    check = script_checks.checker(RESULTS)

    scene = "".join(text for info, text, _ in found if info == "yaml")
    committed = open(os.path.join(source, "docs", "tutorial", "boom.yaml")).read()
    check(scene == committed, "the page's yaml blocks, in order, are docs/tutorial/boom.yaml")

    work = os.path.join(binary, "test_output", "tutorial")
    mirror(source, boomdyn, work)
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
               OMPI_MCA_rmaps_base_oversubscribe="1")
    start = time.time()
    for k, (info, text, line) in enumerate(found):
        if info == "sh":
            runs = [(command, ["bash", "-c", re.sub(r"(^|\s)/usr/bin/python3(?=\s)",
                                                   lambda m: m.group(1) + sys.executable, command)], None)
                    for command in commands(text)]
        elif info == "python":
            runs = [("the Python block", [sys.executable, "-"], text)]
        else:
            continue
        output = ""
        for what, argv, stdin in runs:
            t0 = time.time()
            done = subprocess.run(argv, cwd=work, env=env, input=stdin, stdout=subprocess.PIPE,
                                  stderr=subprocess.STDOUT, text=True)
            output += done.stdout
            check(done.returncode == 0, "line %d: '%s' exits 0 (%d, %.1f s)" % (line, what, done.returncode,
                                                                               time.time() - t0))
            if done.returncode != 0:
                print(done.stdout[-3000:])
        if k + 1 < len(found) and found[k + 1][0] == "text":
            check_output(found[k + 1][1], output, check, "line %d" % found[k + 1][2])
    check_tip_stiffness(boomdyn, source, work, check)
    check_pad_forces(source, work, check)
    kinds = sorted({info for info, _, _ in found} - {"yaml", "sh", "python", "text"})
    check(not kinds, "the page's blocks are yaml, sh, python or text (others: %s)" % (kinds or "none"))
    for step, pattern in (("a run", r"^build/boomdyn docs/tutorial/boom\.yaml"),
                          ("a run on 2 ranks", r"^mpiexec -n 2 build/boomdyn docs/tutorial/boom\.yaml"),
                          ("the results script", r"docs/tutorial/boom_results\.py"),
                          ("the plots", r"postprocess/plot_run\.py"),
                          ("the mesh study", r"postprocess/study\.py docs/tutorial/boom\.yaml --elements")):
        present = any(re.search(pattern, c) for info, text, _ in found if info == "sh" for c in commands(text))
        check(present, "the page runs %s" % step)
    print("commands took %.1f s" % (time.time() - start))


RESULTS = []
if __name__ == "__main__":
    sys.exit(script_checks.finish(main, RESULTS))
