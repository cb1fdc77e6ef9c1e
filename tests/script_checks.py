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
