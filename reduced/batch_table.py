"""A reduced batch's result as a table (:meth:`BatchTable.to_dataframe`), and the interruption
that keeps its finished runs (:class:`BatchInterrupted`)."""

from __future__ import annotations

from .batch_chunks import NOT_RUN, STATUS_NAMES

__all__ = ["BatchTable", "BatchInterrupted", "COLUMN_UNITS", "RESUME"]

#: Each peak column's unit, as a dimension of the scene's system (``length``, ``force``) or
#: itself (``rad``, ``s``, ``1``).
COLUMN_UNITS = {"u": "length", "theta": "rad", "uplift_left": "length",
                "weighted_plastic_settlement": "length", "final_vertical_position": "length",
                "base_shear": "force", "energy_balance_error": "1", "dt": "s"}
#: How to resume an interrupted batch, in the line it ends with.
RESUME = ("run_batch(scenes, <the same options>, resume=sys.last_value.partial) "
          "integrates only the runs not done")


class BatchTable:
    """The table view of :class:`~.batch.BatchResult` (its fields: the columns of
    :data:`COLUMN_UNITS`, ``status``, ``names``, ``cases``, ``overrides``, ``units``,
    ``info``)."""

    def to_dataframe(self):
        """The batch as a :class:`pandas.DataFrame`, one row per run in the order given
        (index ``run``): the scene's ``scene``, ``case``, ``overrides`` (``;``-joined) and
        ``units`` (its system), its peaks, and ``status`` by name. ``attrs["units"]`` gives
        each column's unit (the scenes' length and force when they share one system, else
        ``length`` and ``force`` of each row's ``units``); ``attrs["info"]`` the batch's
        ``info``."""
        import pandas as pd

        n = len(self.status)
        table = {"scene": list(self.names) or [""] * n,
                 "case": [c if c is not None else "" for c in self.cases] or [""] * n,
                 "overrides": [";".join(o) for o in self.overrides] or [""] * n,
                 "units": [u[0] for u in self.units] or [""] * n}
        table.update({name: getattr(self, name) for name in COLUMN_UNITS})
        table["status"] = [STATUS_NAMES.get(int(s), str(int(s))) for s in self.status]
        frame = pd.DataFrame(table, index=pd.RangeIndex(n, name="run"))
        systems = set(self.units)
        length, force = next(iter(systems))[1:] if len(systems) == 1 else ("length", "force")
        dims = {"length": length, "force": force}
        frame.attrs["units"] = {k: dims.get(v, v) for k, v in COLUMN_UNITS.items()}
        frame.attrs["info"] = dict(self.info)
        return frame


class BatchInterrupted(KeyboardInterrupt):
    """A batch interrupted (Ctrl-C, SIGTERM): one line saying how many runs were done and how
    to resume, and ``partial``, the :class:`~.batch.BatchResult` with the finished runs (the
    others ``NOT_RUN``). Still a KeyboardInterrupt (a script stops; the ``upliftlab`` command
    prints its one line and exit code 130); a notebook (IPython) shows the line alone, not a
    traceback."""

    def __init__(self, partial, why: str = "Ctrl-C"):
        done = int((partial.status != NOT_RUN).sum())
        self.partial = partial
        self.line = (f"run_batch interrupted ({why}): {done} of {len(partial.status)} runs "
                     f"done; resume with: {RESUME}")
        super().__init__(why)
        self.add_note(f"run_batch: {done} of {len(partial.status)} runs done")

    def __reduce__(self):
        """Pickled with its partial result (a worker's interruption reaches its caller)."""
        return type(self), (self.partial, str(self))

    def __str__(self) -> str:
        return self.args[0] if self.args else "Ctrl-C"

    def _render_traceback_(self) -> list[str]:
        """IPython's hook: the lines it shows instead of a traceback."""
        return [self.line]
