"""The verification's protocol: the list of checks, the content key of its sources, compute or
read from the store, run, its definition and its command line."""

from __future__ import annotations

import dataclasses
import time
from collections.abc import Callable
from pathlib import Path

from .... import __version__
from ....checks import InputError
from ....motions import ELCENTRO, find_motion, load_motion
from ....provenance import MODEL_SOURCES, code_digest, provenance
from ....workers import single_threaded
from ...framework.protocol import Context, Study, StudyRun, run_study
from ...framework.store import Store, point_key
from ...framework.study import StudyResult, file_sha256, write_study
from .continuum_checks import flamant, prandtl, rocking_stiffness, uplift_eccentricity
from .dataset import verification_dataset
from .records import FAIL, STUDY, C, CheckContext, Order, R, Row
from .reduced_dynamics import energy_balance, orders_smooth, orders_uplift, rigid_block
from .reduced_statics import (bonded_periods, fixed_base, impact_damper, reduced_uplift_onset,
                              static_reactions, stiffness_entries, ultimate_moment,
                              winkler_pushover)
from .summary import key_numbers, summarise
from .tables import write_tables

# ---------------------------------------------------------------------------------------------
# The study
# ---------------------------------------------------------------------------------------------

#: (group, title, check): each check returns rows, orders, or (rows, orders).
CHECKS: tuple[tuple[str, str, Callable], ...] = (
    (R, "two-spring K (eq. 6)", stiffness_entries),
    (R, "static reactions", static_reactions),
    (R, "bonded periods", bonded_periods),
    (R, "fixed base vs Nigam–Jennings", fixed_base),
    (R, "Winkler pushover", winkler_pushover),
    (R, "uplift onset", reduced_uplift_onset),
    (R, "elasto-plastic bed", ultimate_moment),
    (R, "impact damper", impact_damper),
    (R, "rigid block", rigid_block),
    (R, "energy balance", energy_balance),
    (R, "orders, smooth case", orders_smooth),
    (R, "orders, uplifting case", orders_uplift),
    (C, "rocking stiffness", rocking_stiffness),
    (C, "Flamant slope", flamant),
    (C, "Prandtl and locking", prandtl),
    (C, "uplift-onset eccentricity", uplift_eccentricity),
)


def elcentro_record() -> tuple[object | None, str | None, str]:
    """(motion, SHA-256 of its file, note): El Centro from UPLIFTLAB_MOTIONS, or None."""
    try:
        path = find_motion(ELCENTRO)
    except InputError as exc:
        return None, None, f"El Centro record not found: {exc}"
    return load_motion(ELCENTRO), file_sha256(path), ""


#: This package's sources as :func:`upliftlab.provenance.package_files` names them (the checks
#: moved under ``studies/`` with issue 34's layout; the old prefix matched no file, so an edit
#: to a check left the stored table looking current).
OWN_SOURCES = "upliftlab.comparisons/studies/verification/"


def source_digest() -> str:
    """The code digest of the sources that decide the verification's numbers: the models'
    (:data:`upliftlab.provenance.MODEL_SOURCES`) and this package's checks
    (:data:`OWN_SOURCES`)."""
    return code_digest(MODEL_SOURCES + (OWN_SOURCES,))


def compute(fast: bool, progress=None) -> dict:
    """Run every check (no store): {"rows": [...], "orders": [...], "seconds": {...}}."""
    with single_threaded():
        return compute_checks(fast, progress)


def compute_checks(fast: bool, progress=None) -> dict:
    say = progress or (lambda message: None)
    record, _, note = elcentro_record()
    ctx = CheckContext(fast, record, note)
    rows, orders, seconds = [], [], {}
    for group, title, check in CHECKS:
        start = time.perf_counter()
        try:
            out = check(ctx)
        except Exception as exc:  # a crashing check is a failing row with its message
            out = [Row(group, f"error_{check.__name__.strip('_')}", f"{title}: the check "
                       "raised", "", None, None, None, "", "", FAIL,
                       f"{type(exc).__name__}: {exc}")]
        rs, os_ = out if isinstance(out, tuple) else (out, [])
        for item in rs:
            (orders if isinstance(item, Order) else rows).append(item)
        orders += list(os_)
        seconds[title] = time.perf_counter() - start
        say(f"{title}: {seconds[title]:.1f} s")
    return {"rows": [dataclasses.asdict(r) for r in rows],
            "orders": [dataclasses.asdict(o) for o in orders], "seconds": seconds}


def compute_or_read(scene: None, ctx: Context):
    """Every anchor as the study's :class:`xarray.Dataset` (:func:`.dataset.verification_dataset`),
    its checks computed or read from ``ctx.store`` under the content key of the module
    docstring (``scene`` must be None: the checks build their own). The store keeps the checks'
    record as before; the dataset is built from it after reading."""
    if scene is not None:
        raise InputError(f"scene = {scene!r}: the verification builds its own scenes; pass "
                         "scene=None")
    fast, store = ctx.fast, ctx.store
    _, record_sha, _ = elcentro_record()
    params = {"fast": bool(fast), "elcentro_sha256": record_sha, "source": source_digest()}
    key = point_key(STUDY, "upliftlab.comparisons.verification:compute", params)
    entry = store.get(key)
    reused = entry is not None
    if entry is None:
        t0 = time.perf_counter()
        entry = compute(fast, ctx.progress)
        entry["compute_seconds"] = time.perf_counter() - t0
        entry["computed_utc"] = provenance()["created_utc"]
        store.put(key, entry, {"study": STUDY, "params": params, "version": __version__})
    return verification_dataset(entry, {
        "fast": bool(fast), "reused": reused, "key": key,
        "computed_utc": entry["computed_utc"], "compute_seconds": entry["compute_seconds"],
        "inputs": params})


def write(ds, ctx: Context) -> StudyResult:
    """``anchors.csv``, ``orders.csv``, the dataset (``verification.nc``) and the summary into
    ``ctx.out``."""
    a = ds.attrs
    inputs = {"fast": bool(a["inputs_fast"]), "elcentro_sha256": a.get("inputs_elcentro_sha256"),
              "source": a["inputs_source"]}
    prov = provenance(study=STUDY, fast=ctx.fast, key=a["key"], store=str(ctx.store.root),
                      computed_utc=a["computed_utc"], reused=bool(a["reused"]), inputs=inputs)
    files = write_tables(ds, Path(ctx.out))
    return write_study(STUDY, ds, ctx, summarise=summarise, numbers=key_numbers,
                       provenance=prov, files=files)


def run(fast: bool = False, *, out: str | Path | None = None,
        store: Store | str | Path | None = None, progress=None, **_ignored) -> StudyRun:
    """Compute (or read from ``store``) every anchor; write ``anchors.csv``, ``orders.csv``,
    ``verification.nc``, ``summary.md`` and ``summary.json`` into ``out`` (default
    ``results/verification[-fast]``). Returns the dataset (``.data``) and what was written
    (``.study``).

    ``store`` defaults to ``<out>/store``. Keyword arguments other studies take (``scheduler``)
    are accepted and ignored: the checks run in this process.
    """
    return run_study(DEFINITION, None, Context(fast=fast, out=out, store=store,
                                               progress=progress))


def _context_from(args, ctx: Context, say) -> Context:
    return dataclasses.replace(ctx, progress=say)


DEFINITION = Study(STUDY, "Verification anchors",
                   "Every verification anchor (closed forms, published values and converged "
                   "runs, listed in the table with their references) recomputed through the "
                   "library, with its measured error against its tolerance.", None,
                   compute_or_read, write, describe=lambda run: [run.study.summary],
                   passed=lambda run: bool(run.study.numbers["passed"]), context_from=_context_from,
                   own_store=True, help_fast="skip the costly continuum levels")
