"""``upliftlab store``: look after a folder of kept results
(:mod:`upliftlab.comparisons.framework.store`)::

    upliftlab store verify DIR [--sample N]   check the records made by earlier code: N of
                                              each point function's made again (seeded), the
                                              store accepted if they reproduce (exit 0), the
                                              moved points named if not (exit 3)
    upliftlab store migrate DIR               re-key the records of an older upliftlab (keys
                                              with its code, version and machine paths) by what
                                              was asked; their results are kept as they are
    upliftlab store pack DIR --name NAME      move the loose records into one compressed pack
"""

from __future__ import annotations

import argparse
from pathlib import Path

__all__ = ["add_store", "store"]


def add_store(sub) -> None:
    """The ``store`` subcommand and its three actions."""
    s = sub.add_parser("store", help="check, migrate or pack a folder of kept results")
    actions = s.add_subparsers(dest="action", required=True, parser_class=type(s))
    s.formatter_class = argparse.RawDescriptionHelpFormatter
    v = actions.add_parser("verify", help="make a sample of the records of earlier code again "
                                          "and accept the store if they reproduce")
    v.add_argument("folder", help="the store's folder")
    v.add_argument("--sample", default="3", help="records made again per point function "
                                                  "(default 3)")
    m = actions.add_parser("migrate", help="re-key an older store by what was asked")
    m.add_argument("folder", help="the store's folder")
    p = actions.add_parser("pack", help="move the loose records into one compressed pack")
    p.add_argument("folder", help="the store's folder")
    p.add_argument("--name", required=True, help="the pack's name (packs/NAME.jsonl.gz)")
    for parser in (s, v, m, p):
        parser.formatter_class = argparse.RawDescriptionHelpFormatter


def _folder(text: str) -> Path:
    from ..checks import InputError

    folder = Path(text).expanduser()
    if not folder.is_dir():
        raise InputError(f"store {text!r}: not a folder")
    return folder


def _declare_point_functions() -> None:
    """Import every study, so that their point functions are declared."""
    import importlib

    from ..comparisons.studies.registry import STUDIES

    for module in STUDIES:
        importlib.import_module(f"upliftlab.comparisons.studies.{module}")


def store(args) -> int:
    """Run ``upliftlab store ACTION``; 0 done, 3 when stale records moved."""
    from .common import number
    from ..comparisons.framework.freshness import verify_store
    from ..comparisons.framework.migrate import migrate
    from ..comparisons.framework.store import Store

    folder = _folder(args.folder)
    _declare_point_functions()
    if args.action == "verify":
        sample = number("--sample", args.sample, integer=True, low=1, high=1000)
        checks = verify_store(Store(folder), sample=sample)
        print(f"upliftlab store verify: {folder}: "
              + (f"the records of {len(checks)} point functions checked and accepted" if checks
                 else "every record was made by today's code or accepted for it"))
        return 0
    if args.action == "migrate":
        moved, kept = migrate(Store(folder))
        print(f"upliftlab store migrate: {folder}: {moved} records re-keyed by what was asked, "
              f"{kept} already so")
        return 0
    from ..paths import path_component

    path = Store(folder).pack(path_component(args.name, "--name"))
    print(f"upliftlab store pack: wrote {path}")
    return 0
