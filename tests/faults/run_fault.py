#!/usr/bin/env python3
"""Faults injected for real into boomdyn runs (issue 17): schedules that
cannot spin, signals on one and two ranks, two runs on one output file,
outputs that are inputs, a full file system, damaged or mismatched
checkpoints, stray arguments and unused options. One case per call, so that
each is its own CTest (tests/faults/CMakeLists part of tests/fuzz.cmake).

Usage: run_fault.py BOOMDYN SOURCE_DIR WORK_DIR CASE [MPIEXEC...]
Exit 0: passed; 1: failed; 77: skipped (said why)."""
import os
import re
import shutil
import signal
import subprocess
import sys
import time

boomdyn, source, work, case = sys.argv[1:5]
mpiexec = sys.argv[5:]
sys.path.insert(0, os.path.join(source, "tests"))
import script_checks  # noqa: E402

results = []
check = script_checks.checker(results)
SKIP = 77
scene = os.path.join(source, "inputs", "cantilever_dynamic.yaml")
static_scene = os.path.join(source, "inputs", "cantilever_static.yaml")
scratch = os.path.join(work, "faults", case)
shutil.rmtree(scratch, ignore_errors=True)
os.makedirs(scratch)
env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")


def path(name):
    return os.path.join(scratch, name)


def run(args, timeout=30, scene_file=scene, **kw):
    """A run that must end by itself within timeout (a hang is killed and fails)."""
    cmd = [boomdyn, scene_file, *args]
    try:
        r = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout, env=kw.pop("env", env), **kw)
        return r.returncode, r.stdout + r.stderr
    except subprocess.TimeoutExpired as e:
        out = (e.stdout or b"").decode(errors="replace") + (e.stderr or b"").decode(errors="replace")
        return "hang", out


def last_line(out):
    lines = out.strip().splitlines()
    return lines[-1] if lines else ""


def status(h5):
    """/summary/status and the number of /steps rows of a results file (None if unreadable)."""
    try:
        import h5py
        with h5py.File(h5, "r") as f:
            s = f["summary"].attrs.get("status")
            s = s.decode() if isinstance(s, bytes) else s
            return s, f["steps/time"].shape[0], (f["state/time"].shape[0] if "state/time" in f else 0)
    except Exception as e:  # noqa: BLE001 (any failure to read is the finding)
        return None, str(e), 0


def summary_status(h5):
    """/summary/status alone (a file may have no /steps), or why there is none."""
    try:
        import h5py
        with h5py.File(h5, "r") as f:
            s = f["summary"].attrs.get("status") if "summary" in f else None
            return (s.decode() if isinstance(s, bytes) else s) or "no /summary/status"
    except Exception as e:  # noqa: BLE001 (an unreadable file is the finding)
        return "unreadable: %s" % e


def quick(*extra):
    return ["-o", path("r.h5"), "-boom_overwrite", "-boom_quiet", *extra]


# ---------------------------------------------------------------- hangs
def interval_tiny(option, extra=()):
    # 1e-90 s: within the magnitudes boomdyn accepts, far below the resolution of t
    rc, out = run(quick("-ts_max_time", "0.01", option, "1e-90", *extra))
    check(rc == 0, "%s 1e-90 ends (exit %s, not a hang)" % (option, rc))
    check("shorter than the step" in out, "and says it fires at every step: " + out.strip().splitlines()[0][:120]
          if out.strip() else "no warning")
    return rc


def case_state_interval_tiny():
    if interval_tiny("-boom_state_interval") == 0:
        s, steps, states = status(path("r.h5"))
        check(s == "completed" and states == steps, "a snapshot at every step (%s snapshots, %s rows)" % (states, steps))


def case_checkpoint_interval_tiny():
    interval_tiny("-boom_checkpoint_interval", ["-boom_checkpoint", path("c.chk.h5")])


def case_tracking_interval_tiny():
    interval_tiny("-boom_tracking_interval")


def case_too_many_steps():
    rc, out = run(quick("-ts_dt", "1e-12"), timeout=20)
    check(rc == 1 and "1e+12 steps" in last_line(out), "1e12 steps are refused with the number: " + last_line(out)[:160])


def signal_static(sig, name):
    out = path("s.h5")
    p = subprocess.Popen([boomdyn, static_scene, "-o", out, "-boom_overwrite", "-boom_quiet", "-boom_load_steps",
                          "1000000"], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, env=env)
    time.sleep(2.0)
    wait_for_handler([p.pid], sig)
    p.send_signal(sig)
    try:
        text, _ = p.communicate(timeout=20)
    except subprocess.TimeoutExpired:
        p.kill()
        text, _ = p.communicate()
        check(False, "%s: the static run ignores %s (killed after 20 s)" % (name, name))
        return
    check(p.returncode == 128 + sig, "static run ends on %s with exit %d (got %d)" % (name, 128 + sig, p.returncode))
    check("interrupted" in last_line(text), "and says so: " + last_line(text)[:140])
    s, rows, _ = status(out)
    check(s == "interrupted", "its results file says 'interrupted' (%s, %s rows)" % (s, rows))


def case_static_sigterm():
    signal_static(signal.SIGTERM, "SIGTERM")


def case_static_sigint():
    signal_static(signal.SIGINT, "SIGINT")


# ----------------------------------------------- signals in an eigen-solve
def signal_modal(sig, name):
    """SIGINT/SIGTERM while SLEPc iterates (issue 40): the modal run stops within
    an iteration, not after the solve. 2000 elements, 300 modes and a subspace
    of only 302 vectors keep Krylov-Schur restarting far longer than the 5 s
    allowed (281 restarts, 76 s on a busy 2-core machine; 8 s of CPU); the
    signal goes out at the first line of SLEPc's monitor, i.e. inside EPSSolve.
    Before issue 40 the run ignored it and ended with exit 0 and its modes."""
    out = path("m.h5")
    cmd = [boomdyn, os.path.join(source, "inputs", "cantilever_modal.yaml"), "-o", out, "-boom_overwrite",
           "-boom_quiet", "-boom_elements", "2000", "-boom_modal_count", "300", "-modal_eps_ncv", "302",
           "-modal_eps_monitor"]
    p = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, env=env,
                         start_new_session=True)
    first = ""
    deadline = time.time() + 120
    while time.time() < deadline:
        line = p.stdout.readline()
        if not line:
            break
        if "EPS nconv" in line:
            first = line
            break
    check(first != "", "the eigen-solve started (a line of -modal_eps_monitor)")
    sent = time.time()
    p.send_signal(sig)
    try:
        text, _ = p.communicate(timeout=30)
    except subprocess.TimeoutExpired:
        os.killpg(p.pid, signal.SIGKILL)
        p.communicate()
        check(False, "%s during the eigen-solve: the run did not end within 30 s" % name)
        return
    took = time.time() - sent
    check(took < 5.0, "%s during the eigen-solve ends the run within 5 s (%.2f s)" % (name, took))
    check(p.returncode == 128 + sig, "with exit %d (got %s)" % (128 + sig, p.returncode))
    check("interrupted" in last_line(text), "and says so: " + last_line(text)[:140])
    try:
        import h5py
        with h5py.File(out, "r") as f:
            s = f["summary"].attrs.get("status")
            s = s.decode() if isinstance(s, bytes) else s
            modal = "modal" in f
    except Exception as e:  # noqa: BLE001 (an unreadable file is the finding)
        s, modal = "unreadable: %s" % e, None
    check(s == "interrupted", "its results file is readable and says 'interrupted' (%s)" % s)
    check(modal is False, "and holds no modes (a partial solve is not reported)")


def case_tracking_sigterm():
    """SIGTERM inside the first full eigen-solve of a frequency tracking (at
    t = 0, before any step): the analysis stops within an iteration, writes
    no row, and the run ends after its first step as interrupted. 3000
    elements, 100 tracked modes (150 asked for) and a subspace of 152: the
    solve takes about 8 s here; before issue 40 it ran to its end and wrote
    its row."""
    tracked = path("tracked.yaml")
    with open(scene) as f:
        text = f.read()
    with open(tracked, "w") as f:
        f.write(text + "\ntracking: {interval: 0.01, count: 100}\n")
    out = path("t.h5")
    cmd = [boomdyn, tracked, "-o", out, "-boom_overwrite", "-boom_quiet", "-boom_elements", "3000",
           "-ts_dt", "5e-4", "-modal_eps_ncv", "152", "-modal_eps_monitor"]
    p = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, env=env,
                         start_new_session=True)
    started = False
    deadline = time.time() + 120
    while time.time() < deadline:
        line = p.stdout.readline()
        if not line or "EPS nconv" in line:
            started = bool(line)
            break
    check(started, "the tracking's eigen-solve started (a line of -modal_eps_monitor)")
    sent = time.time()
    p.send_signal(signal.SIGTERM)
    try:
        text, _ = p.communicate(timeout=30)
    except subprocess.TimeoutExpired:
        os.killpg(p.pid, signal.SIGKILL)
        p.communicate()
        check(False, "SIGTERM during the tracking's eigen-solve: the run did not end within 30 s")
        return
    took = time.time() - sent
    check(took < 5.0, "SIGTERM during the tracking's eigen-solve ends the run within 5 s (%.2f s)" % took)
    check(p.returncode == 128 + signal.SIGTERM, "with exit 143 (got %s)" % p.returncode)
    s, rows, _ = status(out)
    check(s == "interrupted", "its results file is readable and says 'interrupted' (%s, %s rows)" % (s, rows))
    try:
        import h5py
        with h5py.File(out, "r") as f:
            analyses = f["tracking/tracked_hz"].shape[0] if "tracking/tracked_hz" in f else 0
    except Exception as e:  # noqa: BLE001
        analyses = "unreadable: %s" % e
    check(analyses == 0, "and no tracking row from the stopped analysis (%s rows)" % analyses)


def case_modal_sigint():
    signal_modal(signal.SIGINT, "SIGINT")


def case_modal_sigterm():
    signal_modal(signal.SIGTERM, "SIGTERM")


# --------------------------------------------------------------- signals
# A run that is still going when the signal comes 3 s after its start: 10^7
# steps of the cantilever (10^5 steps, 100 s, took 2.75 s on one rank after the
# eighth round of issue 18, and then ended before the signal).
def long_run(extra=(), ranks=1, stdout=subprocess.PIPE):
    cmd = ([*mpiexec] if ranks > 1 else []) + [boomdyn, scene, "-o", path("r.h5"), "-boom_overwrite", "-ts_max_time",
                                               "10000", "-boom_checkpoint", path("r.chk.h5"), *extra]
    return subprocess.Popen(cmd, stdout=stdout, stderr=subprocess.STDOUT, text=True, env=env, start_new_session=True)


def rank_pids(p, ranks):
    """The boomdyn processes of a run (the launcher's children on several ranks)."""
    if ranks == 1:
        return [p.pid]
    out = subprocess.run(["pgrep", "-s", str(p.pid), "-f", boomdyn], capture_output=True, text=True).stdout.split()
    return [int(x) for x in out if int(x) != p.pid]


def interrupted_like_sigterm(p, sig, name, ranks, text=None):
    try:
        text_out, _ = p.communicate(timeout=30)
    except subprocess.TimeoutExpired:
        os.killpg(p.pid, signal.SIGKILL)
        p.communicate()
        check(False, "%s on %d rank(s): the run did not end within 30 s" % (name, ranks))
        return
    text = text if text is not None else text_out
    check(p.returncode == 128 + sig, "%s on %d rank(s): exit %d like SIGTERM's 128 + signal (got %s)"
          % (name, ranks, 128 + sig, p.returncode))
    check("PETSC ERROR" not in (text or ""), "no PETSc signal handler traceback")
    s, rows, _ = status(path("r.h5"))
    check(s == "interrupted", "results file closed as 'interrupted' (%s, %s rows)" % (s, rows))
    check(os.path.exists(path("r.chk.h5")), "a checkpoint was written")


def catches(pid, sig):
    """Whether process pid has installed a handler for sig (/proc/PID/status, SigCgt)."""
    try:
        with open("/proc/%d/status" % pid) as f:
            for line in f:
                if line.startswith("SigCgt:"):
                    return (int(line.split()[1], 16) >> (sig - 1)) & 1 == 1
    except OSError:
        pass
    return False


def wait_for_handler(pids, sig, limit=30.0):
    """On a loaded machine a process can still be starting (MPI, PETSc) after the
    fixed wait; a signal before boomdyn installs its handler kills it outright,
    which is not what these cases test. Wait until every rank catches sig."""
    end = time.time() + limit
    while time.time() < end and not all(catches(pid, sig) for pid in pids):
        time.sleep(0.1)


def signal_run(sig, name, ranks):
    if ranks > 1 and not mpiexec:
        print("skipped: no mpiexec given")
        sys.exit(SKIP)
    p = long_run(["-boom_quiet"], ranks)
    time.sleep(3.0)
    pids = rank_pids(p, ranks)
    wait_for_handler(pids, sig)
    check(len(pids) == ranks, "found the %d boomdyn process(es): %s" % (ranks, pids))
    if pids:
        os.kill(pids[0], sig)  # one rank only: the others learn it through the run's reduction
    interrupted_like_sigterm(p, sig, name, ranks)


def case_sighup_1():
    signal_run(signal.SIGHUP, "SIGHUP", 1)


def case_sighup_2():
    signal_run(signal.SIGHUP, "SIGHUP", 2)


def case_sigpipe_2():
    signal_run(signal.SIGPIPE, "SIGPIPE", 2)


def case_sigpipe_1():
    """boomdyn ... | head -1: the reader goes away after the first line."""
    out = open(path("stdout.txt"), "w")
    cmd = [boomdyn, scene, "-o", path("r.h5"), "-boom_overwrite", "-ts_max_time", "10000", "-boom_checkpoint",
           path("r.chk.h5"), "-boom_progress_interval", "0.1"]
    shell = subprocess.Popen("%s | head -1" % " ".join(cmd), shell=True, stdout=out, stderr=subprocess.STDOUT, env=env,
                             executable="/bin/bash")
    try:
        shell.wait(timeout=40)
    except subprocess.TimeoutExpired:
        subprocess.run(["pkill", "-KILL", "-s", str(shell.pid)])
        check(False, "boomdyn | head -1 did not end within 40 s")
        return
    # the exit status of boomdyn itself: PIPESTATUS is not visible here, so ask the results and the checkpoint.
    s, rows, _ = status(path("r.h5"))
    check(s == "interrupted", "boomdyn | head -1: results closed as 'interrupted' (%s, %s rows)" % (s, rows))
    check(os.path.exists(path("r.chk.h5")), "and a checkpoint was written")
    rc = subprocess.run("set -o pipefail; %s | head -1 > /dev/null" % " ".join(cmd), shell=True,
                        executable="/bin/bash", env=env, timeout=40).returncode
    check(rc == 128 + signal.SIGPIPE, "exit %d like SIGTERM's 128 + signal (got %d)" % (128 + signal.SIGPIPE, rc))


# --------------------------------------------------------- files destroyed
def case_output_is_scene():
    copy = path("scene.yaml")
    shutil.copy(scene, copy)
    before = open(copy, "rb").read()
    os.symlink(copy, path("link.h5"))
    for spelling in [os.path.join(scratch, ".", "scene.yaml"), path("link.h5")]:
        rc, out = run(["-o", spelling, "-boom_overwrite", "-boom_quiet", "-ts_max_time", "0.01"], scene_file=copy)
        check(rc == 1 and "is the scene file" in last_line(out), "-o %s is refused: %s" % (spelling, last_line(out)[:120]))
    check(open(copy, "rb").read() == before, "the scene file is unchanged")


def case_output_is_checkpoint_or_restart():
    rc, out = run(quick("-ts_max_time", "0.02", "-boom_checkpoint_interval", "0.01", "-boom_checkpoint",
                        path("c.chk.h5")))
    check(rc == 0 and os.path.exists(path("c.chk.h5")), "a checkpoint to restart from (exit %s)" % rc)
    before = open(path("c.chk.h5"), "rb").read()
    rc, out = run(["-o", path("c.chk.h5"), "-boom_overwrite", "-boom_quiet", "-boom_restart", path("c.chk.h5"),
                   "-boom_checkpoint", path("other.chk.h5")])
    check(rc == 1 and "is the restart file" in last_line(out), "-o = restart file is refused: " + last_line(out)[:120])
    rc, out = run(["-o", path("x.h5"), "-boom_overwrite", "-boom_quiet", "-boom_checkpoint", path("x.h5")])
    check(rc == 1 and "is the checkpoint file" in last_line(out), "-o = checkpoint is refused: " + last_line(out)[:120])
    check(open(path("c.chk.h5"), "rb").read() == before, "the checkpoint is unchanged")


def file_kind(p):
    """What is at p, without following a last symbolic link: 'chr', 'fifo', 'sock', 'dir', 'link', 'file', 'none'."""
    import stat
    try:
        m = os.lstat(p).st_mode
    except FileNotFoundError:
        return "none"
    for kind, test in [("link", stat.S_ISLNK), ("chr", stat.S_ISCHR), ("fifo", stat.S_ISFIFO), ("sock", stat.S_ISSOCK),
                       ("dir", stat.S_ISDIR), ("file", stat.S_ISREG)]:
        if test(m):
            return kind
    return "other"


def special_files():
    """A FIFO, a socket, a folder, a link to /dev/null and (as root) a character
    device made here with /dev/null's numbers: never /dev/null itself."""
    import socket
    made = {}
    os.mkfifo(path("fifo.h5"))
    made["fifo.h5"] = "a FIFO"
    sock = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    sock.bind(path("sock.h5"))  # the socket file stays after close
    sock.close()
    made["sock.h5"] = "a socket"
    os.mkdir(path("dir.h5"))
    made["dir.h5"] = "is a folder"
    os.symlink("/dev/null", path("devnull_link.h5"))
    made["devnull_link.h5"] = "a character device"
    if os.geteuid() == 0:
        try:
            os.mknod(path("chr.h5"), 0o666 | __import__("stat").S_IFCHR, os.makedev(1, 3))
            made["chr.h5"] = "a character device"
        except OSError as e:
            print("no character device made here (%s); the link to /dev/null stands for it" % e)
    return made


def case_special_file_outputs():
    """Outputs, checkpoints and restart files that are not regular files are
    refused before anything is written; none of them is replaced."""
    made = special_files()
    devnull = os.stat("/dev/null")
    kinds = {name: file_kind(path(name)) for name in made}
    for name, said in made.items():
        for option, extra in [("-o", ["-boom_checkpoint", path("c.chk.h5")]),
                              ("-boom_checkpoint", ["-o", path("r.h5"), "-boom_checkpoint_interval", "0.005"])]:
            rc, out = run([option, path(name), "-boom_overwrite", "-boom_quiet", "-ts_max_time", "0.01", *extra])
            check(rc == 1 and option + " " + path(name) in last_line(out) and said in last_line(out),
                  "%s %s (%s) is refused naming it: %s" % (option, name, said, last_line(out)[:160]))
        rc, out = run(["-o", path("r.h5"), "-boom_overwrite", "-boom_quiet", "-boom_restart", path(name),
                       "-ts_max_time", "0.01"], timeout=20)
        expected = "is a folder" if name == "dir.h5" else said
        check(rc == 1 and "-boom_restart" in last_line(out) and expected.replace("is a folder", "a folder") in last_line(out),
              "-boom_restart %s is refused, no hang (exit %s): %s" % (name, rc, last_line(out)[:160]))
    # The XDMF file next to the results is replaced by rename at every snapshot.
    os.mkfifo(path("x.xmf"))
    rc, out = run(["-o", path("x.h5"), "-boom_overwrite", "-boom_quiet", "-ts_max_time", "0.01"], timeout=20)
    check(rc == 1 and "XDMF file" in last_line(out) and "a FIFO" in last_line(out),
          "an XDMF path that is a FIFO is refused (exit %s): %s" % (rc, last_line(out)[:160]))
    after = {name: file_kind(path(name)) for name in made}
    check(after == kinds, "every special file is still what it was: %s" % after)
    check(file_kind(path("x.xmf")) == "fifo", "the FIFO at the XDMF path too")
    now = os.stat("/dev/null")
    check(file_kind("/dev/null") == "chr" and (now.st_ino, now.st_rdev) == (devnull.st_ino, devnull.st_rdev),
          "/dev/null is untouched")
    left = sorted(n for n in os.listdir(scratch) if ".tmp" in n or n in ("r.h5", "x.h5"))
    check(left == [], "nothing was created for the refused runs: %s" % left)
    # A symbolic link to a regular file is written through: the link stays.
    target = path("target.h5")
    open(target, "w").close()
    os.symlink(target, path("link.h5"))
    rc, out = run(["-o", path("link.h5"), "-boom_overwrite", "-boom_quiet", "-ts_max_time", "0.01", "-boom_checkpoint",
                   path("c.chk.h5")])
    s, rows, _ = status(target)
    check(rc == 0 and file_kind(path("link.h5")) == "link" and s == "completed",
          "-o LINK to a regular file writes the file, the link stays (exit %s, %s, %s rows)" % (rc, s, rows))


def concurrent(extra_env):
    e = dict(env, **extra_env)
    shared = path("shared.h5")
    first = subprocess.Popen([boomdyn, scene, "-o", shared, "-boom_quiet", "-ts_max_time", "8", "-boom_checkpoint",
                              path("a.chk.h5")], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, env=e)
    for _ in range(400):  # until the first run has created its file
        if os.path.exists(shared) or first.poll() is not None:
            break
        time.sleep(0.025)
    # Stopped while the second run starts and ends, so that the first is still
    # writing whatever the machine's speed (CI once saw it finish first: the
    # run takes under 2 s since the Jacobian reuse).
    running = first.poll() is None
    if running:
        first.send_signal(signal.SIGSTOP)
    check(running, "the first run is still writing when the second starts")
    try:
        rc, out = run(["-o", shared, "-boom_overwrite", "-boom_quiet", "-ts_max_time", "0.01", "-boom_checkpoint",
                       path("b.chk.h5")], env=e)
    finally:
        if running:
            first.send_signal(signal.SIGCONT)
    text, _ = first.communicate(timeout=120)
    return first.returncode, text, rc, out, shared


def case_concurrent_overwrite():
    rc1, text1, rc2, out2, shared = concurrent({})
    check(rc2 == 1 and "being written by another run" in last_line(out2),
          "the second run (-boom_overwrite) is refused: " + last_line(out2)[:120])
    check(rc1 == 0, "the first run completes (exit %s)" % rc1)
    s, rows, _ = status(shared)
    check(s == "completed" and rows == 8001, "its file is whole: %s, %s rows of 8001" % (s, rows))


def case_concurrent_overwrite_unlocked():
    """Without HDF5's file locks the second run replaces the file (by rename,
    never by truncation); the first must not exit 0 with its results gone."""
    rc1, text1, rc2, out2, shared = concurrent({"HDF5_USE_FILE_LOCKING": "FALSE"})
    check(rc2 == 0, "the second run (-boom_overwrite) completes (exit %s)" % rc2)
    check(rc1 == 1 and "removed or replaced by another process" in last_line(text1),
          "the first run fails, saying its file was taken: " + last_line(text1)[:120])
    s, rows, _ = status(shared)
    check(s == "completed" and rows == 11, "the file is the second run's, readable (%s, %s rows)" % (s, rows))


# ------------------------------------------------------------- full disk
def mounted_small_fs(size):
    """A tmpfs of this size, or None (not root, or no mounts allowed)."""
    mnt = path("fs")
    os.makedirs(mnt)
    if os.geteuid() != 0 or not shutil.which("mount"):
        return None
    r = subprocess.run(["mount", "-t", "tmpfs", "-o", "size=%s" % size, "tmpfs", mnt], capture_output=True, text=True)
    return mnt if r.returncode == 0 else None


def with_small_fs(size, body, shim_only=False):
    """A small file system: a tmpfs where the test may mount one, otherwise
    (or with shim_only) a folder that the preloaded small_disk_shim makes look
    like one (statvfs and ENOSPC on write); skipped with a message without both."""
    global env
    mnt = None if shim_only else mounted_small_fs(size)
    if mnt:
        try:
            body(mnt)
        finally:
            subprocess.run(["umount", "-l", mnt])
        return
    shim = os.environ.get("BOOMDYN_SMALL_DISK_SHIM", "")
    if not os.path.exists(shim):
        print("skipped: cannot mount a small tmpfs here, and no small_disk_shim (BOOMDYN_SMALL_DISK_SHIM) was built")
        sys.exit(SKIP)
    folder = path("fs")
    os.makedirs(folder, exist_ok=True)
    print("small file system: %s preloaded on %s" % (os.path.basename(shim), folder))
    env = dict(env, LD_PRELOAD=shim, BOOMDYN_SMALL_DISK_DIR=folder,
               BOOMDYN_SMALL_DISK_BYTES=str(int(size.rstrip("m")) * 1024 * 1024))
    body(folder)


def full_disk_results(shim_only):
    def body(mnt):
        out = os.path.join(mnt, "r.h5")
        rc, text = run(["-o", out, "-boom_quiet", "-ts_max_time", "10", "-boom_state_interval", "0.001"], timeout=60)
        check(rc == 1, "a full file system ends the run with exit 1, no crash (got %s)" % rc)
        check(last_line(text).startswith("boomdyn: error:") and "file system is full" in last_line(text),
              "with one line: " + last_line(text)[:140])
        s, rows, _ = status(out)
        check(s is not None and s.startswith("failed"), "the results are readable with a status (%s, %s rows)" % (s, rows))
        left = sorted(os.listdir(mnt))
        check(left == ["r.h5", "r.xmf"] and os.path.getsize(os.path.join(mnt, "r.xmf")) > 0,
              "no temporary file, no empty XDMF: %s" % left)
    with_small_fs("3m", body, shim_only)


def full_disk_checkpoint(shim_only):
    def body(mnt):
        with open(os.path.join(mnt, "filler"), "wb") as f:  # leaves about 100 kB
            f.write(b"\0" * (3 * 1024 * 1024 - 100 * 1024))
        chk = os.path.join(mnt, "r.chk.h5")
        rc, text = run(quick("-ts_max_time", "1", "-boom_checkpoint_interval", "0.2", "-boom_checkpoint", chk))
        check(rc == 1 and "file system is full" in last_line(text), "exit 1 with one line (exit %s): %s"
              % (rc, last_line(text)[:140]))
        s, rows, _ = status(path("r.h5"))
        check(s is not None and s.startswith("failed"), "the results say the run failed (%s, %s rows)" % (s, rows))
        check(sorted(os.listdir(mnt)) == ["filler"], "no half-written checkpoint or .tmp left: %s" % os.listdir(mnt))
    with_small_fs("3m", body, shim_only)


def case_full_disk_status_shim():
    """A file system that is (nearly) full when the run starts: a results file
    is only started with 256 kB free, and one that was started always ends with
    /summary/status = failed: ... (with 260 kB free the file was left without
    /summary: its first flush failed and it was closed as it was)."""
    def body(folder):
        for left_kb in [8, 200, 260, 300, 400]:
            for name in os.listdir(folder):
                os.remove(os.path.join(folder, name))
            with open(os.path.join(folder, "filler"), "wb") as f:
                f.write(b"\0" * (3 * 1024 * 1024 - left_kb * 1024))
            out = os.path.join(folder, "r.h5")
            rc, text = run(["-o", out, "-boom_quiet", "-ts_max_time", "1", "-boom_checkpoint", path("c.chk.h5")],
                           timeout=60)
            check(rc == 1 and "file system is full" in last_line(text),
                  "%d kB free: exit 1 saying the file system is full (exit %s): %s" % (left_kb, rc, last_line(text)[:150]))
            s = summary_status(out) if os.path.exists(out) else "no file"
            check(s == "no file" or s.startswith("failed"),
                  "%d kB free: no results file, or one that says it failed (%s)" % (left_kb, s))
            left = [n for n in os.listdir(folder) if ".tmp" in n]
            check(left == [], "no temporary file left: %s" % left)
    with_small_fs("3m", body, True)


def case_full_disk_results():
    full_disk_results(False)


def case_full_disk_checkpoint():
    full_disk_checkpoint(False)


def case_full_disk_results_2():
    """Two ranks, the shim's small file system (rank 0 writes; every rank stops)."""
    if not mpiexec:
        print("skipped: no mpiexec given")
        sys.exit(SKIP)

    def body(folder):
        out = os.path.join(folder, "r.h5")
        cmd = [*mpiexec, "-x", "LD_PRELOAD", "-x", "BOOMDYN_SMALL_DISK_DIR", "-x", "BOOMDYN_SMALL_DISK_BYTES", boomdyn,
               scene, "-o", out, "-boom_quiet", "-ts_max_time", "10", "-boom_state_interval", "0.001"]
        try:
            r = subprocess.run(cmd, capture_output=True, text=True, timeout=90, env=env)
            rc, text = r.returncode, r.stdout
        except subprocess.TimeoutExpired:
            rc, text = "hang", ""
        check(rc == 1, "two ranks end with exit 1 (got %s)" % rc)
        check("file system is full" in last_line(text), "with one line: " + last_line(text)[:140])
        s, rows, _ = status(out)
        check(s is not None and s.startswith("failed"), "results readable with a status (%s, %s rows)" % (s, rows))
    with_small_fs("3m", body, True)


def case_full_disk_results_shim():
    full_disk_results(True)


def case_full_disk_checkpoint_shim():
    full_disk_checkpoint(True)


# ----------------------------------------------------------- checkpoints
def checkpoint():
    chk = path("c.chk.h5")
    rc, out = run(quick("-ts_max_time", "0.05", "-boom_checkpoint_interval", "0.03", "-boom_checkpoint", chk))
    check(rc == 0 and os.path.exists(chk), "a checkpoint at t = 0.03 s (exit %s)" % rc)
    return chk


def edit_checkpoint(chk, edit):
    import h5py
    damaged = path("damaged.chk.h5")
    shutil.copy(chk, damaged)
    with h5py.File(damaged, "r+") as f:
        edit(f)
    return damaged


def fnv1a(data, h=14695981039346656037):
    for byte in data:
        h = ((h ^ byte) * 1099511628211) & 0xFFFFFFFFFFFFFFFF
    return h


def rewrite_checksum(f):
    """The checksum of src/io/checkpoint.cpp (contentChecksum), recomputed after
    an edit: FNV-1a 64 over the scene text, then the scalars, arrays and vectors
    by sorted name, each name and sequence preceded by its length (8 bytes)."""
    import numpy as np
    text = lambda b: len(b).to_bytes(8, "little") + b  # noqa: E731
    nums = lambda v: len(v).to_bytes(8, "little") + np.asarray(v, dtype="<f8").tobytes()  # noqa: E731
    names = lambda d: [n.decode() if isinstance(n, bytes) else n for n in f[d][:]]  # noqa: E731
    scene_text = f["scene_text"][()]
    data = text(scene_text if isinstance(scene_text, bytes) else scene_text.encode())
    scalars = dict(zip(names("scalar_names"), f["scalar_values"][:]))
    for n in sorted(k for k in scalars if k != "none"):
        data += text(n.encode()) + nums([scalars[n]])
    for n in sorted(k for k in names("array_names") if k != "none"):
        v = f["arrays/" + n][:]
        data += text(n.encode()) + nums(v[1:1 + int(v[0])])
    for n in sorted(k for k in names("vector_names") if k != "none"):
        data += text(n.encode()) + nums(f["vectors/" + n][:])
    del f["checksum"]
    f["checksum"] = "%016x" % fnv1a(data)


def restart(chk, *extra):
    return run(["-o", path("restarted.h5"), "-boom_overwrite", "-boom_quiet", "-boom_restart", chk, "-boom_checkpoint",
                path("next.chk.h5"), "-ts_max_time", "0.06", *extra])


def case_restart_nan_time():
    def nan_t(f):
        names = [n.decode() if isinstance(n, bytes) else n for n in f["scalar_names"][:]]
        v = f["scalar_values"][:]
        v[names.index("t")] = float("nan")
        f["scalar_values"][:] = v
    rc, out = restart(edit_checkpoint(checkpoint(), nan_t))
    check(rc == 1 and "'t' is not finite" in last_line(out), "t = nan is refused: " + last_line(out)[:140])


def case_restart_violated_state():
    """An edit that also rewrites the checksum (a forgery) still meets the constraint check."""
    def move_clamped_node(f):
        q = f["vectors/q"][:]
        q[0] += 0.05
        f["vectors/q"][:] = q
        rewrite_checksum(f)
    rc, out = restart(edit_checkpoint(checkpoint(), move_clamped_node))
    check(rc == 1 and "violates the constraints by 0.05" in last_line(out),
          "a state 5 cm off its clamp is refused: " + last_line(out)[:140])


def case_restart_edited_state():
    """A free coordinate moved by 5 cm satisfies every constraint: only the
    checksum of the saved contents finds it."""
    chk = checkpoint()
    import h5py
    with h5py.File(chk, "r") as f:
        q = f["vectors/q"][:]
    tip_x = len(q) - 4  # the tip node's x of the cantilever (4 coordinates per node, clamped at the start)

    def move_free_coordinate(f):
        q = f["vectors/q"][:]
        q[tip_x] += 0.05
        f["vectors/q"][:] = q
    rc, out = restart(edit_checkpoint(chk, move_free_coordinate))
    check(rc == 1 and "do not match the checksum" in last_line(out) and "damaged.chk.h5" in last_line(out),
          "the tip moved by 5 cm is refused, naming the file: " + last_line(out)[:160])

    def rewrite_only(f):  # the checksum as Python computes it matches the program's: the test's edit is the cause
        old = f["checksum"][()]
        rewrite_checksum(f)
        check(f["checksum"][()] == old, "the checksum recomputed here equals the stored one (%s)" % old)
    rc, out = restart(edit_checkpoint(chk, rewrite_only))
    check(rc == 0, "an unedited checkpoint restarts (exit %s): %s" % (rc, last_line(out)[:120]))

    def change_scalar(f):
        names = [n.decode() if isinstance(n, bytes) else n for n in f["scalar_names"][:]]
        v = f["scalar_values"][:]
        v[names.index("t")] += 1e-3
        f["scalar_values"][:] = v
    rc, out = restart(edit_checkpoint(chk, change_scalar))
    check(rc == 1 and "do not match the checksum" in last_line(out), "a time moved by 1 ms is refused: "
          + last_line(out)[:140])
    rc, out = restart(edit_checkpoint(chk, lambda f: f.__delitem__("checksum")))
    check(rc == 1 and "holds no checksum" in last_line(out), "a checkpoint without a checksum is refused: "
          + last_line(out)[:140])


def case_restart_formulation_mismatch():
    """Every option that changes the equations or the step sequence is held by
    the checkpoint; options that only change how they are solved may differ."""
    chk = checkpoint()
    for option, value, named in [("-boom_axial_integration", "full", "-boom_axial_integration (beam 'boom') = assumed, "
                                  "this run has full"),
                                 ("-boom_axial_integration", "reduced", "this run has reduced"),
                                 ("-boom_filtered_start", "0", "-boom_filtered_start = 1, this run has 0"),
                                 ("-boom_kink_restart", "0", "-boom_kink_restart = 1, this run has 0"),
                                 ("-boom_elements", "17", "-boom_elements (elements of beam 'boom') = 16, this run has 17")]:
        rc, out = restart(chk, option, value)
        check(rc == 1 and named in last_line(out) and "restart with the options" in last_line(out),
              "%s %s is refused naming it: %s" % (option, value, last_line(out)[:160]))
    for option, value in [("-boom_acceleration_predictor", "0"), ("-boom_jacobian_reuse", "0"),
                          ("-boom_energy_tolerance", "0.1")]:
        rc, out = restart(chk, option, value)
        check(rc == 0, "%s %s (the same equations, solved otherwise) restarts (exit %s): %s"
              % (option, value, rc, last_line(out)[:120]))
    # Two beams with their element counts swapped: the same number of unknowns, another mesh.
    two = os.path.join(source, "inputs", "two_beams_pinned.yaml")
    chk2 = path("two.chk.h5")
    rc, out = run(quick("-ts_max_time", "0.02", "-boom_checkpoint_interval", "0.01", "-boom_checkpoint", chk2),
                  scene_file=two)
    check(rc == 0 and os.path.exists(chk2), "a checkpoint of two_beams_pinned (exit %s)" % rc)
    rc, out = run(["-o", path("restarted.h5"), "-boom_overwrite", "-boom_quiet", "-boom_restart", chk2,
                   "-boom_checkpoint", path("next.chk.h5"), "-ts_max_time", "0.03", "-boom_elements_inner", "6",
                   "-boom_elements_outer", "8"], scene_file=two)
    check(rc == 1 and "beam 'inner') = 8, this run has 6" in last_line(out),
          "8 + 6 elements swapped to 6 + 8 are refused: " + last_line(out)[:160])


def case_restart_options_mismatch():
    chk = checkpoint()
    rc, out = restart(chk)
    check(rc == 0, "the same options restart (exit %s)" % rc)
    for option, value, named in [("-ts_dt", "0.002", "-ts_dt"), ("-boom_rho_inf", "0.5", "-boom_rho_inf"),
                                 ("-boom_adaptive_tol", "1e-6", "-boom_adaptive_tol")]:
        rc, out = restart(chk, option, value)
        check(rc == 1 and named in last_line(out) and "restart with the options" in last_line(out),
              "%s %s is refused naming it: %s" % (option, value, last_line(out)[:140]))
    rc, out = run(["-o", path("restarted.h5"), "-boom_overwrite", "-boom_quiet", "-boom_restart", chk,
                   "-ts_max_time", "0.02"])
    check(rc == 1 and "not before the end time" in last_line(out),
          "an end time before the checkpoint's is refused: " + last_line(out)[:140])


# ---------------------------------------------------------- out of memory
def case_out_of_memory():
    """A mesh that passes the estimate against the machine's memory but not the
    address-space limit (ulimit -v): the allocation fails at different places
    for different limits (here: the Jacobian pattern's std::bad_alloc, which
    ended in std::terminate, exit 134; PETSc's allocator, a PETSc-internal
    message; KLU's analysis, reported as a singular matrix). Every one is one
    line saying out of memory."""
    # 3e5 elements: 2.4 GB by the estimate (8 kB per element), so a machine with 3 GB or more lets it start.
    for elements, limit_mb in [(300000, 800), (100000, 600), (100000, 700)]:
        out_file = path("oom.h5")
        cmd = "ulimit -v %d && exec %s %s -o %s -boom_overwrite -boom_quiet -boom_elements %d -ts_max_time 0.002" % (
            limit_mb * 1000, boomdyn, scene, out_file, elements)
        try:
            r = subprocess.run(["/bin/bash", "-c", cmd], capture_output=True, text=True, timeout=120, env=env)
            rc, text = r.returncode, r.stdout + r.stderr
        except subprocess.TimeoutExpired:
            rc, text = "hang", ""
        line = last_line(text)
        check(rc == 1, "%d elements under ulimit -v %d MB: exit 1, no abort (got %s)" % (elements, limit_mb, rc))
        check(line.startswith("boomdyn: error:") and "out of memory" in line and "ulimit -v" in line
              and "singular" not in line, "with one line saying so: " + line[:220])
        s, rows, _ = status(out_file)
        check(s != "completed", "no completed results (%s)" % s)


def peak_kib(scene_file, elements, extra):
    """Peak resident memory (KiB, /usr/bin/time) of one run with this many elements."""
    rss = path("rss.txt")
    cmd = ["/usr/bin/time", "-f", "%M", "-o", rss, boomdyn, scene_file, "-o", path("mem.h5"), "-boom_overwrite",
           "-boom_quiet", "-boom_elements", str(elements), *extra]
    subprocess.run(cmd, capture_output=True, text=True, timeout=300, env=env)
    with open(rss) as f:
        return int(f.read().split()[-1])


def case_memory_estimate():
    """The mesh-size guard's estimate (kB per element, in its message) covers
    the peak memory per element measured here from 10^4 to 3*10^4 elements
    (one rank), of a dynamic run and of a modal run."""
    modal_scene = os.path.join(source, "inputs", "cantilever_modal.yaml")
    for scene_file, extra, kind in [(scene, ["-ts_max_time", "0.002"], "dynamic"), (modal_scene, [], "modal")]:
        rc, out = run(["-boom_quiet", "-boom_elements", "10000000"], scene_file=scene_file)
        m = re.search(r"mesh too large for this machine's memory: .*\(([0-9.]+) kB per element", last_line(out))
        check(rc == 1 and m is not None, "%s: 10^7 elements refused with the estimate per element: %s"
              % (kind, last_line(out)[:200]))
        if not m:
            continue
        estimate = float(m.group(1)) * 1e3
        small, large = peak_kib(scene_file, 10000, extra), peak_kib(scene_file, 30000, extra)
        measured = (large - small) * 1024.0 / 20000
        check(measured < estimate, "%s: measured %.0f bytes per element (%d -> %d KiB) < the estimate %.0f"
              % (kind, measured, small, large, estimate))


# --------------------------------------------------------------- messages
def case_second_scene():
    rc, out = run([static_scene, *quick("-ts_max_time", "0.01")])
    check(rc == 1 and "unexpected argument" in last_line(out) and "cantilever_static.yaml" in last_line(out),
          "a second scene file is refused: " + last_line(out)[:140])


def case_unused_option():
    rc, out = run(quick("-ts_max_time", "0.005", "-ksp_typo", "3"))
    check(rc == 0 and "options not used by this run: -ksp_typo" in out, "-ksp_typo is reported as unused (exit %s): %s"
          % (rc, last_line(out)[:140]))
    rc, out = run(["-o", path("s.h5"), "-boom_overwrite", "-boom_quiet", "-ts_dt", "0.1", "-boom_allow_unused"],
                  scene_file=static_scene)
    check(rc == 0 and "warning: -ts_dt does not apply to the static analysis" in out,
          "-boom_allow_unused: -ts_dt on a static scene is a warning (exit %s)" % rc)


def case_private_session_dir():
    """A run without mpiexec keeps Open MPI's session directories in a private
    $TMPDIR/boomdyn-mpi-XXXXXX (src/app/singleton_start.cpp), removed at the
    end: the shared $TMPDIR/ompi.<host>.<uid>/jf.0 of isolated singletons made
    runs started side by side fail in MPI_Init now and then."""
    tmp = path("tmp")
    os.makedirs(tmp)
    e = dict(env, TMPDIR=tmp)
    e.pop("OMPI_MCA_orte_tmpdir_base", None)
    p = subprocess.Popen([boomdyn, scene, "-o", path("r.h5"), "-boom_overwrite", "-boom_quiet", "-ts_max_time", "8"],
                         stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, env=e)
    def session_made():  # a folder in $TMPDIR with something in it (Open MPI's tree)
        names = os.listdir(tmp)
        return any(os.path.isdir(os.path.join(tmp, n)) and os.listdir(os.path.join(tmp, n)) for n in names)
    for _ in range(400):
        try:
            if session_made() or p.poll() is not None:
                break
        except FileNotFoundError:  # a folder removed while looked at
            pass
        time.sleep(0.01)
    seen = []
    if p.poll() is None:
        p.send_signal(signal.SIGSTOP)  # hold it there while we look
        seen = sorted(os.listdir(tmp))
        inside = sorted(os.listdir(os.path.join(tmp, seen[0]))) if len(seen) == 1 else []
        p.send_signal(signal.SIGCONT)
    else:
        inside = []
    text, _ = p.communicate(timeout=120)
    check(p.returncode == 0, "the run completes (exit %s): %s" % (p.returncode, last_line(text)[:120]))
    check(len(seen) == 1 and seen[0].startswith("boomdyn-mpi-"),
          "while it runs, $TMPDIR holds only its private base: %s" % seen)
    check(any(n.startswith("ompi.") for n in inside), "with Open MPI's session tree inside it: %s" % inside)
    check(os.listdir(tmp) == [], "and nothing is left after the run: %s" % os.listdir(tmp))


CASES = {name[len("case_"):]: f for name, f in globals().items() if name.startswith("case_")}

if case not in CASES:
    print("unknown case %s; cases: %s" % (case, " ".join(sorted(CASES))))
    sys.exit(2)
sys.exit(script_checks.finish(CASES[case], results))
