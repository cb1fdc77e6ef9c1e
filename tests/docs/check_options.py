#!/usr/bin/env python3
"""The option tables of README.md and docs/options.md say what is true of
the program: every option they name is one that `boomdyn -help` lists, and
every default they give as a value (a cell that starts with `value`) is the
default that -help prints.

Tables read: those whose header starts with `| option | default |`. Options
are the backticked words that start with '-' in the first cell
(`-boom_elements_<body>` stands for the per-body options of a scene). -help
is asked twice: without a scene (boomdyn's options with their built-in
defaults) and with a dynamic scene (also PETSc's options of the run, and the
defaults of a dynamic run: `-boom_jacobian_reuse`); a default cell that says
"in dynamic runs" is compared with the second.

    check_options.py BOOMDYN SOURCE_DIR WORK_DIR               # the check
    check_options.py --self-test BOOMDYN SOURCE_DIR WORK_DIR   # doctored tables must fail
"""
import os
import re
import subprocess
import sys

DOCS = ("README.md", "docs/options.md")
SCENE = "inputs/paper_extraction.yaml"  # dynamic, three beams, tracking
# PETSc 3.18 prints "-name <now X : formerly Y>: help", "-name <X : Y>: help"
# (reals) or "-name: <X : Y> help" (switches); global options as "-name ...".
HELP_LINE = re.compile(r"^\s+(-[A-Za-z0-9_]+):?\s*<(?:now )?([^<>]*?) : (?:formerly )?[^<>]*>", re.M)
LISTED = re.compile(r"^\s+(-[A-Za-z0-9_]+)", re.M)
TRUE, FALSE = {"1", "true", "yes", "on"}, {"0", "false", "no", "off"}


def option_rows(text):
    """(line number, options, default cell) of every row of the option tables in text."""
    rows, in_table = [], False
    for number, line in enumerate(text.splitlines(), 1):
        if re.match(r"^\|\s*option\s*\|\s*default\s*\|", line):
            in_table, header = True, number
            continue
        if not in_table or number == header + 1:
            continue
        if not line.startswith("|"):
            in_table = False
            continue
        cells = [c.strip() for c in re.split(r"(?<!\\)\|", line.strip())[1:-1]]
        names = [span.split()[0] for span in re.findall(r"`([^`]+)`", cells[0]) if span.startswith("-")]
        rows.append((number, names, cells[1]))
    return rows


def help_defaults(boomdyn, source, work):
    """{option: default} from -help without a scene, and from -help with the dynamic scene."""
    def ask(args):
        done = subprocess.run([boomdyn] + args, capture_output=True, text=True, timeout=300, cwd=work)
        found = {m.group(1): None for m in LISTED.finditer(done.stdout)}
        found.update({m.group(1): m.group(2).strip() for m in HELP_LINE.finditer(done.stdout)})
        if not found:
            raise SystemExit("%s %s printed no options (exit %d):\n%s%s"
                             % (boomdyn, " ".join(args), done.returncode, done.stdout[-1500:], done.stderr[-1500:]))
        return found
    plain = ask(["-help"])
    scene = ask([os.path.join(source, SCENE), "-help", "-ts_max_time", "0.002", "-boom_quiet", "-boom_overwrite",
                 "-o", os.path.join(work, "options_help.h5")])
    return plain, scene


def same_value(claimed, printed):
    a, b = claimed.strip().lower(), printed.strip().lower()
    if a in TRUE | FALSE and b in TRUE | FALSE:
        return (a in TRUE) == (b in TRUE)
    try:
        return float(a) == float(b)
    except ValueError:
        return a == b


def check_text(name, text, plain, scene):
    """Errors of one document's option tables, and (options, defaults checked)."""
    errors, options, defaults = [], 0, 0
    for line, names, default in option_rows(text):
        for option in names:
            options += 1
            if "<" in option:  # -boom_elements_<body>: the scene's per-body options
                stem = option.split("<")[0]
                if not any(o.startswith(stem) and o != stem for o in scene):
                    errors.append("%s:%d: %s: -help with %s lists no %s..." % (name, line, option, SCENE, stem))
            elif option not in plain and option not in scene:
                errors.append("%s:%d: %s: not an option that boomdyn -help lists" % (name, line, option))
        value = re.match(r"`([^`]*)`", default)
        if not value:
            continue  # a description ("the scene's `dynamic.dt`"), not a value
        if len(names) != 1:
            errors.append("%s:%d: a default value for %d options %s: give it one option per row"
                          % (name, line, len(names), names))
            continue
        option, claimed = names[0], value.group(1)
        source = scene if "in dynamic runs" in default or option not in plain else plain
        printed = source.get(option)
        defaults += 1
        if printed is None or not same_value(claimed, printed):
            errors.append("%s:%d: %s: default `%s` in the table, -help%s prints %s"
                          % (name, line, option, claimed, "" if source is plain else " with a dynamic scene", printed))
    return errors, options, defaults


def check(source, plain, scene, texts=None):
    errors, summary = [], []
    for name in DOCS:
        text = texts[name] if texts else open(os.path.join(source, name)).read()
        found, options, defaults = check_text(name, text, plain, scene)
        if options < (10 if name == "README.md" else 40) or defaults < 8:
            found.append("%s: the option tables were not read (%d options, %d defaults found)"
                         % (name, options, defaults))
        summary.append("%s: %d options, %d defaults checked" % (name, options, defaults))
        errors += found
    return errors, summary


def self_test(source, plain, scene):
    """Each doctored table must be reported."""
    real = {name: open(os.path.join(source, name)).read() for name in DOCS}
    doctorings = {
        "an option that does not exist": ("docs/options.md", "`-boom_rho_inf r`", "`-boom_rho_infinity r`"),
        "a wrong default": ("README.md", "| `-boom_rho_inf r` | `0.8`", "| `-boom_rho_inf r` | `0.9`"),
        "a wrong default of a switch": ("docs/options.md", "| `-boom_kink_restart 0\\|1` | `1`",
                                        "| `-boom_kink_restart 0\\|1` | `0`"),
        "a wrong default of a dynamic run": ("README.md", "| `-boom_jacobian_reuse 0\\|1` | `1`",
                                             "| `-boom_jacobian_reuse 0\\|1` | `0`"),
        "a misspelt PETSc option": ("docs/options.md", "`-ts_adapt_dt_max h`", "`-ts_adapt_max_dt h`"),
        "a table without its header": ("README.md", "| option | default | what it does |", "| name | default | what |"),
    }
    failures = 0
    for what, (name, old, new) in doctorings.items():
        if old not in real[name]:
            print("self-test: '%s' not in %s (update the self-test)" % (old, name))
            failures += 1
            continue
        texts = dict(real, **{name: real[name].replace(old, new, 1)})
        found, _ = check(source, plain, scene, texts)
        print("self-test: %s: %s %s" % (what, "seen" if found else "NOT SEEN", found[:1]))
        failures += not found
    found, summary = check(source, plain, scene)
    print("self-test: the tables as they are: %s (%s)" % ("pass" if not found else "FAIL", "; ".join(summary)))
    return 1 if failures or found else 0


def main(argv):
    test = argv[1:2] == ["--self-test"]
    boomdyn, source, work = argv[2:5] if test else argv[1:4]
    os.makedirs(work, exist_ok=True)
    os.environ.setdefault("OMPI_ALLOW_RUN_AS_ROOT", "1")
    os.environ.setdefault("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
    plain, scene = help_defaults(os.path.abspath(boomdyn), os.path.abspath(source), work)
    print("boomdyn -help: %d options; with %s: %d" % (len(plain), SCENE, len(scene)))
    if test:
        return self_test(source, plain, scene)
    errors, summary = check(source, plain, scene)
    for line in summary:
        print(line)
    for e in errors:
        print("FAIL " + e)
    print("option tables: %s" % ("every option exists, every default is -help's" if not errors
                                 else "%d errors" % len(errors)))
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
