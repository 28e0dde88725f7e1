"""Shared by the end-to-end checks: named pass/fail lines and the exit code."""
import sys

_failures = []


def check(name, ok, detail="", show=False):
    """Prints `name: ok` (with the detail if show) or `name: FAILED detail`
    and records a failure."""
    shown = f" ({detail})" if show and detail else ""
    print(f"{name}: {'ok' + shown if ok else 'FAILED ' + str(detail)}")
    if not ok:
        _failures.append(name)


def finish():
    """Prints the verdict and exits 1 if any check failed."""
    print("all checks passed" if not _failures else
          f"CHECKS FAILED: {', '.join(_failures)}")
    sys.exit(1 if _failures else 0)
