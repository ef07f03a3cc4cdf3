"""Count the outcomes of the fuzz list of ``tests/test_fuzz.py`` with each case in a forked child
that has a timeout and an address-space limit: how the counts of the code before its input
checks were measured (a hang or a memory blow-up counts as a failure; the test's ``BEFORE``).

``python benchmarks/fuzz_counts.py [--timeout S] [--memory-gb G] [--only TEXT] [--json FILE]``
prints the counts and every failure; it writes nothing unless ``--json`` names a file. (Without
forking, ``python tests/test_fuzz.py`` runs the list in one process, as the test does.)
"""

from __future__ import annotations

import json
import os
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))
from test_fuzz import _DYN, _PUSH, _RUN, Case, all_cases, count_cases, run_case  # noqa: E402


def _forked(case: Case, tmp: Path, timeout: float, memory: int) -> tuple[str, str]:
    """``run_case`` in a forked child with a timeout (s) and an address-space limit (bytes)."""
    import resource
    import signal
    import time

    tmp.mkdir(parents=True, exist_ok=True)
    result = tmp / "verdict.json"
    pid = os.fork()
    if pid == 0:  # child
        try:
            resource.setrlimit(resource.RLIMIT_AS, (memory, memory))
            verdict = run_case(case, tmp / "case")
        except BaseException as exc:  # noqa: BLE001
            verdict = ("failed", f"{type(exc).__name__}: {exc}")
        result.write_text(json.dumps(verdict))
        os._exit(0)
    start = time.monotonic()
    while time.monotonic() - start < timeout:
        done, status = os.waitpid(pid, os.WNOHANG)
        if done:
            break
        time.sleep(0.02)
    else:
        os.kill(pid, signal.SIGKILL)
        os.waitpid(pid, 0)
        return "failed", f"hang: killed after {timeout:g} s"
    if not result.exists():
        return "failed", f"the child died (status {status})"
    return tuple(json.loads(result.read_text()))


def main(argv: list[str] | None = None) -> int:
    import argparse

    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--timeout", type=float, default=60.0, help="seconds per case")
    p.add_argument("--memory-gb", type=float, default=6.0,
                   help="address-space limit (GiB) of each forked child")
    p.add_argument("--only", default="", help="run the cases whose id contains this text")
    p.add_argument("--json", help="write every verdict to this file")
    args = p.parse_args(argv)
    os.environ.setdefault("MPLBACKEND", "Agg")
    memory = int(args.memory_gb * 2**30)
    start = time.perf_counter()
    with tempfile.TemporaryDirectory(prefix="upliftlab-fuzz-") as root:
        # compile and import once, so that every child inherits it
        for i, argv in enumerate((_RUN, (*_RUN, "--integrator", "newmark"),
                                  (*_PUSH, "--steps", "3"), _DYN)):
            run_case(Case(f"warm-up {i}", (*argv, "--out", "{out}")), Path(root) / f"w{i}")
        verdicts = count_cases(
            [c for c in all_cases() if args.only in c.id],
            lambda i, case: _forked(case, Path(root) / f"c{i:04d}", args.timeout, memory),
            lambda: time.perf_counter() - start)
    if args.json:
        Path(args.json).write_text(json.dumps(verdicts, indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
