"""``upliftlab report [--fast] [--out DIR] [--scheduler ADDR] [--force] [--budget SECONDS]
[--pdf PAPER ...]``: one self-contained HTML report of every study
(:mod:`upliftlab.comparisons.report.build`), and its PDF on each paper asked for
(``report-A4.pdf``, ``report-Letter.pdf``: outputs of the same run, so a file of the user's at
their name is refused before any section runs).

Exit 0 when every section was built and the verification passed, 1 when a section failed
(its error is in the report and on stderr), 2 for bad input before any section ran.
"""

from __future__ import annotations

from .. import checks

from ..extras import need_extra
from ..log import logger
from .common import FORCE_HELP, number
from .exits import EXIT_FAILED, EXIT_OK

__all__ = ["add_report", "report_command"]


def add_report(sub) -> None:
    """The parser of ``upliftlab report``."""
    rp = sub.add_parser("report", help="one self-contained HTML report: verification anchors, "
                                       "convergence orders and every comparison study")
    rp.add_argument("--fast", action="store_true", help="small grids and coarse meshes")
    rp.add_argument("--out", help="output directory (default results/report[-fast])")
    rp.add_argument("--scheduler", help="Dask scheduler address for the studies' sweeps")
    rp.add_argument("--force", action="store_true", help=FORCE_HELP)
    rp.add_argument("--budget", metavar="SECONDS",
                    help="refuse a study whose continuum runs are estimated above this many "
                         "seconds of one worker (default 3600; the Winkler map's kept runs "
                         "cost nothing)")
    rp.add_argument("--pdf", nargs="+", action="extend", metavar="PAPER",
                    choices=("A4", "Letter"),
                    help="also print the report to PDF on A4 and/or Letter (headless Chromium)")


def report_command(args) -> int:
    """Build the report; the exit code of the module docstring."""
    need_extra("upliftlab report", "matplotlib", "skfem", "meshio", "PIL")
    if args.scheduler is not None:
        checks.scheduler_address("--scheduler", args.scheduler, in_process=False)
        need_extra("upliftlab report --scheduler", "distributed")
    from ..comparisons.report.build import REPORT_BUDGET, build_report

    def say(message):
        logger("report").info(f"upliftlab report: {message}")

    budget = number("--budget", args.budget, high=1e9)
    report = build_report(args.fast, out=args.out, scheduler=args.scheduler, progress=say,
                          force=args.force, budget=REPORT_BUDGET if budget is None else budget,
                          papers=args.pdf or ())
    failed = [s for s in report.sections if s.status != "ok"]
    for s in failed:
        say(f"section {s.name}: {s.status}: {s.error.split(chr(10), 1)[0]}")
    verdict = "verification passed" if report.passed else "verification FAILED"
    sections = (f"; {len(failed)} of {len(report.sections)} sections FAILED "
                f"({', '.join(s.name for s in failed)})" if failed else "")
    print(f"upliftlab report: wrote {report.path} in {report.elapsed:.1f} s; {verdict}{sections}")
    for pdf in report.pdfs:
        say(f"wrote {pdf}")
    return EXIT_OK if report.ok else EXIT_FAILED
