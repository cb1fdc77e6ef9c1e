#!/usr/bin/python3
"""Runs boomdyn on every scene in tests/bad_model/ and checks that it is refused cleanly.

    /usr/bin/python3 tests/bad_model/run_bad_models.py [--boomdyn build/boomdyn] [FILE.yaml ...]
    (CTest: bad_model.<case> and bad_input.<case>, one per file; tests/fuzz.cmake)

The scenes in tests/bad_model/ are valid YAML that the scene reader accepts,
but that describe a mechanism the program cannot run: a constraint violated by
the initial configuration, a slider outside its track, redundant or
contradictory constraints, a mechanism without supports, a mesh too large
for memory, bad command-line options, ... Each file starts with header lines

    # expect: <substring>      required, may be repeated: each must appear in the output
    # line: <n>                optional: the output must contain '<file name>:<n>:'
    # args: <options>          optional: extra command-line options for boomdyn
    # file-name: no            optional: the message need not name the scene file
                               (bad command-line options: the file is not at fault)
    # known-issue: <text>      optional: a known shortcoming (see below)

and for each the run must

  1. exit with a non-zero status, not killed by a signal (no crash, no core dump);
  2. print (stdout or stderr) every expected substring and the scene's file name
     (with -boom_quiet, so the banner line naming the scene does not count);
  3. finish within --timeout seconds (default 60);
  4. leave no results file, or one whose /summary/status is not 'completed';
  5. say so in the program's own one-line form, a line 'boomdyn: error: ...'
     (not only a PETSc error traceback).

Every case runs in a scratch folder with its address space limited to
--mem-mb (default 4096 MB), so that a mesh too large for memory fails
inside boomdyn instead of calling the kernel's OOM killer on the machine.

A case with '# known-issue:' documents behaviour that is still unclear or
wrong (docs/reliability.md lists them): its failed checks are printed as
KNOWN and do not fail the run; once all its checks pass, the run says XPASS
so that the header line can be removed.
"""

import argparse
import os
import resource
import shlex
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent


def read_header(path):
    header = {"expect": [], "line": None, "args": [], "known": None, "file_name": True}
    with open(path, encoding="utf-8", errors="replace") as f:  # not_utf8.yaml is Latin-1 after its header
        for raw in f:
            line = raw.strip()
            if not line.startswith("#"):
                break
            body = line[1:].strip()
            key, _, value = body.partition(":")
            value = value.strip()
            if key == "expect":
                header["expect"].append(value)
            elif key == "line":
                header["line"] = int(value)
            elif key == "args":
                header["args"] += shlex.split(value)
            elif key == "file-name":
                header["file_name"] = value.lower() not in ("no", "false", "0")
            elif key == "known-issue":
                header["known"] = value
    if not header["expect"]:
        raise SystemExit(f"{path}: no '# expect:' header line")
    return header


def summary_status(h5path):
    """'absent', the /summary/status string, or 'no status (...)'."""
    if not h5path.exists():
        return "absent"
    try:
        import h5py
    except ImportError:
        return "unreadable (no h5py: use /usr/bin/python3)"
    try:
        with h5py.File(h5path, "r") as f:
            if "summary" not in f or "status" not in f["summary"].attrs and "status" not in f["summary"]:
                return "no /summary/status"
            g = f["summary"]
            value = g.attrs["status"] if "status" in g.attrs else g["status"][()]
            if isinstance(value, bytes):
                value = value.decode()
            if hasattr(value, "tolist"):
                value = value.tolist()
                if isinstance(value, bytes):
                    value = value.decode()
            return str(value)
    except OSError as e:
        return f"unreadable ({e})"


def limit(mem_mb):
    def apply():
        os.setsid()  # own process group: a timeout kills mpiexec/boomdyn and children
        if mem_mb > 0:
            b = mem_mb * 1024 * 1024
            resource.setrlimit(resource.RLIMIT_AS, (b, b))
        resource.setrlimit(resource.RLIMIT_CORE, (0, 0))
    return apply


def run_case(path, boomdyn, timeout, mem_mb, scratch):
    header = read_header(path)
    out = scratch / (path.stem + ".h5")
    cmd = [str(boomdyn), str(path), "-o", str(out), "-boom_overwrite", "-boom_quiet"] + header["args"]
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    start = time.monotonic()
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, cwd=scratch, env=env,
                            preexec_fn=limit(mem_mb))
    timed_out = False
    try:
        output, _ = proc.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        timed_out = True
        os.killpg(proc.pid, signal.SIGKILL)
        output, _ = proc.communicate()
    elapsed = time.monotonic() - start
    text = output.decode("utf-8", "replace")
    problems = []
    rc = proc.returncode
    if timed_out:
        problems.append(f"did not finish within {timeout} s (killed)")
    elif rc < 0:
        problems.append(f"killed by signal {-rc} ({signal.Signals(-rc).name})")
    elif rc == 0:
        problems.append("exit status 0 (the scene was accepted)")
    if not timed_out:
        for s in header["expect"]:
            if s not in text:
                problems.append(f"output lacks {s!r}")
        if header["file_name"] and path.name not in text:
            problems.append(f"output does not name the file {path.name!r}")
        if rc != 0 and not any(l.startswith("boomdyn: error: ") for l in text.splitlines()):
            problems.append("no 'boomdyn: error: ...' line" + (" (a PETSc error traceback instead)" if "PETSC ERROR" in text else ""))
        if header["line"] is not None and f"{path.name}:{header['line']}:" not in text:
            problems.append(f"output does not point at line {header['line']} ('{path.name}:{header['line']}:')")
    cores = [p.name for p in scratch.iterdir() if p.name.startswith("core")]
    if cores:
        problems.append(f"core dump {cores}")
    status = summary_status(out)
    if status == "completed":
        problems.append("results file says /summary/status = 'completed'")
    elif status != "absent" and not status.startswith("failed"):
        problems.append(f"results file left with {status}")
    # The message as the user sees it: the first line naming an error.
    lines = [l for l in text.splitlines() if l.strip()]
    shown = next((l for l in lines if "error" in l.lower()), lines[0] if lines else "(no output)")
    return {"problems": problems, "elapsed": elapsed, "rc": rc, "status": status, "message": shown.strip(),
            "output": text, "known": header["known"], "cmd": cmd}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("files", nargs="*", type=Path, help="scenes (default: every *.yaml beside this script)")
    ap.add_argument("--boomdyn", type=Path, default=HERE.parent.parent / "build" / "boomdyn")
    ap.add_argument("--timeout", type=float, default=60.0, help="seconds per case (default 60)")
    ap.add_argument("--mem-mb", type=int, default=4096, help="address-space limit per case, MB (0: none)")
    ap.add_argument("--verbose", "-v", action="store_true", help="print every case's full output")
    args = ap.parse_args()
    if not args.boomdyn.exists():
        print(f"bad_model: {args.boomdyn} not found (build first)")
        return 1
    files = sorted(args.files) if args.files else sorted(HERE.glob("*.yaml"))
    failed, known, xpass = [], [], []
    with tempfile.TemporaryDirectory(prefix="bad_model_") as tmp:
        for path in files:
            scratch = Path(tmp) / path.stem
            scratch.mkdir()
            r = run_case(path.resolve(), args.boomdyn.resolve(), args.timeout, args.mem_mb, scratch)
            if not r["problems"]:
                verdict = "XPASS" if r["known"] else "ok"
                if r["known"]:
                    xpass.append(path.name)
            else:
                verdict = "KNOWN" if r["known"] else "FAIL"
                (known if r["known"] else failed).append(path.name)
            print(f"{verdict:5} {path.name:42} {r['elapsed']:6.1f} s  exit {r['rc']:>3}  {r['message'][:150]}")
            for p in r["problems"]:
                print(f"        - {p}")
            if r["known"] and r["problems"]:
                print(f"        known issue: {r['known']}")
            if args.verbose or (r["problems"] and not r["known"]):
                print("        command: " + " ".join(shlex.quote(c) for c in r["cmd"]))
                print("        output (last 25 lines):")
                for l in r["output"].splitlines()[-25:]:
                    print("          | " + l)
    print(f"bad_model: {len(files)} cases, {len(files) - len(failed) - len(known)} ok, {len(known)} known issues, "
          f"{len(failed)} failed")
    if xpass:
        print("bad_model: XPASS (known issue no longer shows; remove its '# known-issue:' line): " + ", ".join(xpass))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
