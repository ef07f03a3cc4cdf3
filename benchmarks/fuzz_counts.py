"""Count the outcomes of the fuzz list of ``tests/test_fuzz.py`` with each case in a forked child
that has a timeout and an address-space limit: how the counts of the code before its input
checks were measured (a hang or a memory blow-up counts as a failure; the test's ``BEFORE``).

``python benchmarks/fuzz_counts.py [--timeout S] [--memory-gb G] [--only TEXT] [--quick]
[--out DIR] [--json FILE]`` prints the counts and every failure. Every 100 cases are a section
(``bench_output``): ``FUZZ_COUNTS.md`` (the counts) and ``fuzz_counts.json`` (every verdict so
far) are rewritten in ``--out`` (default ``results/bench/fuzz_counts``) as each ends; ``--json``
also writes the verdicts to that file at the end. It has no committed table. ``--quick``: every
40th case (a smoke check, about a minute). (Without forking, ``python tests/test_fuzz.py`` runs
the list in one process, as the test does.)
"""

from __future__ import annotations

import json
import os
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))
sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_output import (Section, add_output_arguments, incomplete_note,  # noqa: E402
                          output_folder, run_sections, write_text)
from test_fuzz import _DYN, _PUSH, _RUN, Case, all_cases, count_cases, run_case  # noqa: E402

NAME = "fuzz_counts"
#: Cases per section; ``--quick`` takes every QUICK_STRIDE-th case.
CHUNK, QUICK_STRIDE = 100, 40


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


def document(verdicts: dict, planned: int, missing: dict, command: str) -> str:
    """FUZZ_COUNTS.md: the counts of the cases run so far and every failure."""
    counts = {k: sum(v[0] == k for v in verdicts.values()) for k in ("refused", "ran",
                                                                       "failed")}
    lines = ["# Fuzz list: outcomes per case", "", f"`{command}`; what a verdict means: "
             "`tests/test_fuzz.py`.", ""]
    if missing:
        lines += [incomplete_note(missing).strip(), ""]
    lines += ["| cases run | of | refused | ran | failed |", "|---|---|---|---|---|",
              f"| {len(verdicts)} | {planned} | {counts['refused']} | {counts['ran']} | "
              f"{counts['failed']} |", ""]
    lines += [f"- FAILED {k}: {v[1]}" for k, v in verdicts.items() if v[0] == "failed"]
    return "\n".join(lines) + "\n"


def main(argv: list[str] | None = None) -> int:
    import argparse

    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--timeout", type=float, default=60.0, help="seconds per case")
    p.add_argument("--memory-gb", type=float, default=6.0,
                   help="address-space limit (GiB) of each forked child")
    p.add_argument("--only", default="", help="run the cases whose id contains this text")
    p.add_argument("--quick", action="store_true",
                   help=f"every {QUICK_STRIDE}th case (a smoke check)")
    p.add_argument("--json", help="also write every verdict to this file at the end")
    add_output_arguments(p, NAME, committed=False)
    args = p.parse_args(argv)
    out = output_folder(args, NAME)
    os.environ.setdefault("MPLBACKEND", "Agg")
    memory = int(args.memory_gb * 2**30)
    cases = [c for c in all_cases() if args.only in c.id]
    if args.quick:
        cases = cases[::QUICK_STRIDE]
    command = " ".join(["python benchmarks/fuzz_counts.py", *(argv or sys.argv[1:])])
    verdicts: dict[str, tuple[str, str]] = {}
    start = time.perf_counter()
    with tempfile.TemporaryDirectory(prefix="upliftlab-fuzz-") as root:
        def warm_up() -> None:
            """Compile and import once, so that every child inherits it."""
            for i, argv_ in enumerate((_RUN, (*_RUN, "--integrator", "newmark"),
                                       (*_PUSH, "--steps", "3"), _DYN)):
                run_case(Case(f"warm-up {i}", (*argv_, "--out", "{out}")),
                         Path(root) / f"w{i}")

        def chunk(first: int) -> dict:
            for i in range(first, min(first + CHUNK, len(cases))):
                verdicts[cases[i].id] = _forked(cases[i], Path(root) / f"c{i:04d}",
                                                args.timeout, memory)
                if verdicts[cases[i].id][0] == "failed":
                    print(f"FAILED {cases[i].id}: {verdicts[cases[i].id][1]}", flush=True)
            return dict(verdicts)

        sections = [Section("warm-up", warm_up)]
        sections += [Section(f"cases {first + 1}-{min(first + CHUNK, len(cases))}",
                             lambda first=first: chunk(first))
                     for first in range(0, len(cases), CHUNK)]

        def publish(folder: Path, done: dict, missing: dict) -> None:
            write_text(folder / "fuzz_counts.json", json.dumps(verdicts, indent=1) + "\n")
            write_text(folder / "FUZZ_COUNTS.md",
                       document(verdicts, len(cases), missing, command))

        status = run_sections(NAME, sections, publish, out)
    if status == 0:
        count_cases(cases, lambda i, case: verdicts[case.id],
                    lambda: time.perf_counter() - start)
        if args.json:
            write_text(Path(args.json), json.dumps(verdicts, indent=1))
    return status


if __name__ == "__main__":
    sys.exit(main())
