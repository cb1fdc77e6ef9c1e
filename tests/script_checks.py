"""Reporting for the script tests: each check is (passed, what was checked);
every one is printed, and the exit status says whether all passed."""


def report(checks):
    """Prints 'ok'/'FAIL' per check and a summary; returns the exit status."""
    failed = 0
    for ok, what in checks:
        print(("ok   " if ok else "FAIL ") + what)
        failed += not ok
    print("%d passed, %d failed" % (len(checks) - failed, failed))
    return 1 if failed else 0


def checker(results):
    """A check(ok, what) for a script test: appends (passed, what) to results
    and prints the 'ok'/'FAIL' line as it goes."""
    def check(ok, what):
        results.append((bool(ok), what))
        print(("ok   " if ok else "FAIL ") + what)
    return check


def finish(main, results):
    """Runs main(), which appends (passed, what) to results (and prints them as
    it goes); a crash counts as a failed check, with its trace. Prints the
    summary and returns the exit status."""
    import traceback
    try:
        main()
    except Exception:  # a crash counts as a failure, with its trace
        traceback.print_exc()
        results.append((False, "test crashed"))
    failed = sum(not ok for ok, _ in results)
    print("%d passed, %d failed" % (len(results) - failed, failed))
    return 1 if failed else 0
