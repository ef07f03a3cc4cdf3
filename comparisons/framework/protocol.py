"""The study protocol: what every study declares, and the one way a study is run.

A study is a :class:`Study` record: a stable ``name`` (it names the output folder, the study's
store keys and the report's section, so it must not change when code moves), its options
record type, ``compute(scene, context) -> result`` and ``write(result, context) ->
StudyResult``. :func:`run_study` resolves the output folder and the store, computes, writes and
returns the result with its :class:`~.study.StudyResult` filled in; ``upliftlab study NAME``
gives a study its command line (:mod:`upliftlab.cli.study`). The report walks
:data:`.registry.STUDIES` through the same two functions.

A result is either labelled data, an :class:`xarray.Dataset` (or an :class:`xarray.DataTree`
of datasets, one per file, for a study whose parts have different axes), which ``write``
writes and summarises (:func:`.study.write_study`: the NetCDF files, and the Markdown of the
study's ``summarise(data)`` with its key numbers, both read from the data alone, so that
:func:`upliftlab.open_study` of the folder gives the same back), and which
:func:`run_study` returns with what ``write`` returned as a :class:`StudyRun`; or a frozen
dataclass with a ``study`` field (None until written): ``compute`` leaves it None,
:func:`run_study` replaces it with what ``write`` returned.
"""

from __future__ import annotations

import dataclasses
import time
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from pathlib import Path

from ... import checks
from ...outdir import probe_folder
from .store import Store

__all__ = ["Study", "Context", "StudyRun", "run_study", "default_out", "CHECKOUT"]

#: The checkout the package runs from (an editable install); a study's kept store is looked
#: for under it (:attr:`Study.kept_store`).
CHECKOUT = Path(__file__).resolve().parents[2]


def default_out(name: str, fast: bool) -> Path:
    """The default output folder of study ``name``: ``results/<name>[-fast]``."""
    return Path("results") / (name + ("-fast" if fast else ""))


@dataclass(frozen=True)
class Context:
    """Where and how a study runs.

    ``fast``: small grids and coarse meshes. ``out``: the output folder (default
    :func:`default_out`); ``store``: the results store, a :class:`~.store.Store` or its folder
    (default ``<out>/store``). ``options`` and ``grid``: the study's records (None: its fast or
    full default). ``executor``, ``scheduler``, ``workers`` and ``progress`` go to the study's
    sweeps (:func:`.sweep.run_sweep`). ``results``: results of studies already run in the same
    report, by name (a study may reuse one instead of computing it again). ``started``: the
    wall clock (``time.perf_counter``, s) the study's elapsed time counts from. ``budget``
    (s of one worker): a study that estimates its runs' cost before it starts them refuses
    above it, when its own options set no budget (None: no limit; the report passes its own).
    """

    fast: bool = False
    out: str | Path | None = None
    store: Store | str | Path | None = None
    options: object = None
    grid: object = None
    executor: object = None
    scheduler: object = None
    workers: int | None = None
    progress: object = None
    results: Mapping = field(default_factory=dict)
    started: float = field(default_factory=time.perf_counter)
    budget: float | None = None

    def elapsed(self) -> float:
        """Seconds since :attr:`started`."""
        return time.perf_counter() - self.started


@dataclass(frozen=True)
class Study:
    """One study.

    ``name``: stable (output folder, store keys, report section). ``title`` and ``intro``: the
    report's heading and first line. ``options``: the options record type (or None).
    ``compute(scene, context)``: the result, labelled data or a record (its ``study`` None);
    ``write(result, context)``: the :class:`~.study.StudyResult` (files, summary, numbers).
    ``scene``: the default scene (None: the study picks its own scenes).
    ``describe(result)``: the lines its command line prints and ``passed(result)``: False
    makes the command line exit 1 (default: always passes); both get what :func:`run_study`
    returns. ``arguments(parser)`` adds the study's own command-line options and
    ``context_from(args, context)`` folds them into the context. ``own_store``: the study keys
    its whole result itself (the verification): the report hands it the report's store and
    does not cache it again. ``kept_store``: the folder, relative to the checkout's root, where
    the points of the study's full build are kept with the repository; the report's full build
    resumes from it when it is there (a run whose points are all kept costs minutes, not the
    hours its continuum runs took).
    """

    name: str
    title: str
    intro: str
    options: type | None
    compute: Callable
    write: Callable
    scene: str | None = None
    describe: Callable = lambda result: ()
    passed: Callable = lambda result: True
    arguments: Callable | None = None
    context_from: Callable | None = None
    own_store: bool = False
    kept_store: str | None = None
    help_fast: str = "small grids and coarse meshes"


@dataclass(frozen=True, eq=False)
class StudyRun:
    """A study's labelled result and what writing it gave: ``data``, the
    :class:`xarray.Dataset` (or :class:`xarray.DataTree`) its ``compute`` returned, and
    ``study``, the :class:`~.study.StudyResult` (files, summary, numbers) of its ``write``."""

    data: object
    study: object

    @property
    def reused(self) -> bool:
        """Whether the data was read from a store instead of computed (its ``reused``
        attribute; False without one)."""
        return bool(self.data.attrs.get("reused", False))

    def __repr__(self) -> str:
        """One line: the study record (name, files, folder, time)."""
        return f"<StudyRun {self.study!r}>"


def _resolved(study: Study, context: Context) -> Context:
    checks.boolean("fast", context.fast)
    out = Path(context.out) if context.out is not None else default_out(study.name, context.fast)
    probe_folder(out, "out")  # a file, or a place nothing can be made: refused before work
    store = context.store
    if not isinstance(store, Store):
        store = Store(probe_folder(store if store is not None else out / "store", "store"))
    return dataclasses.replace(context, out=out, store=store)


def run_study(study: Study, scene=None, context: Context | None = None):
    """Run ``study`` on ``scene`` (default: the study's own) in ``context``: compute, then write.

    Returns a :class:`StudyRun` (the data and its :class:`~.study.StudyResult`) for labelled
    data, else the result record with its ``study`` field set to the StudyResult.
    """
    context = _resolved(study, context or Context())
    scene = study.scene if scene is None else scene
    result = study.compute(scene, context)
    written = study.write(result, context)
    if dataclasses.is_dataclass(result):
        return dataclasses.replace(result, study=written)
    return StudyRun(result, written)
