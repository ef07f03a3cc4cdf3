"""Every verification anchor, computed by the library, with its measured error and verdict.

Each row of the table is one number of the verification anchors (``upliftlab/docs/anchors.md``,
the report's appendix; or a closed form the tests name) recomputed through the public APIs of
:mod:`upliftlab.reduced` and :mod:`upliftlab.continuum`: the measured value, the reference, the
error, the tolerance and whether it passes. The observed convergence orders (slopes of
``np.polyfit(log Δt, log
error)`` for the reduced integrators, ``log h`` for the continuum) are a second table.

Reduced model: the two-spring K entries (eq. 6), static reactions, bonded periods against
eig(K, M), the fixed base against Nigam–Jennings (0.01 % in peak u at the default Δt), the
tensionless Winkler pushover with 200 springs (0.5 %), the uplift-onset forces, M_ult and the
yield rotation of the elasto-plastic bed, Ewing's impact damper on a drop mass (anchor §5),
the rigid-block period and restitution (anchor §1), the energy balance of Cases A, B, C on El
Centro (0.1 %) and the integrators' orders on a smooth bonded and an uplifting case.

Continuum: the rocking stiffness K_r = πGB²/(8(1 − ν)) (1 %) and its O(h) convergence with full
integration, the Flamant slope of the vertical compliance (2 %), Prandtl's (2 + π) c_u (2 % on
16 elements across B; **fast mode** uses 8 across with a 5 % tolerance and skips the 16-across
level, the Richardson check and the observed order, each listed as skipped), the uplift-onset
eccentricity B/4 of the elastic half-plane (1 %) and the locking of constant-strain triangles
against Q2.

**Caching.** The whole table is one record of a :class:`.store.Store` under a content key: the
study's inputs (fast or full, the El Centro file's SHA-256), the package version and a SHA-256
of the source files of ``reduced/``, ``continuum/``, ``meshes/``, the core modules (but not the
command line) and this package. A second run with the same key reads the record and recomputes
nothing (the dataset's ``reused`` attribute); editing any of those sources gives a new key,
so a stale table is never shown. A check that raises becomes a failing row that carries the
message.

**Result.** The study's result is an :class:`xarray.Dataset` (:mod:`.dataset`), built after
the store's record is read (the record itself is unchanged): per ``anchor`` (the row's id) the
text fields (group, quantity, reference, unit, kind, tolerance, status, note) and ``measured``,
``expected``, ``error`` (NaN for none); per ``order`` the observed orders (``order_slope``,
``order_low``, ``order_high``, ``order_status``, the fitted ``order_steps``/``order_errors``
over ``level``); ``check_seconds`` per ``check``; attributes ``fast``, ``reused``, ``key``,
``computed_utc``, ``compute_seconds`` and ``inputs_*``. :func:`.summary.summarise` and
:func:`.summary.key_numbers` read it alone; the write step puts ``anchors.csv``,
``orders.csv``, ``verification.nc`` and the summary into the output folder.

``upliftlab study verification [--fast] [--out DIR] [--store DIR]``
(exit 1 if a row fails).
"""

from __future__ import annotations

from .dataset import failures, orders_of, rows_of, status_counts, verification_dataset
from .records import (CheckContext, FAIL, Order, PASS, Row, SKIP, STUDY, absolute_row,
                      bound_row, order_row, relative_row, skipped_row)
from .reduced_statics import drop_mass
from .summary import error_text, fmt, key_numbers, summarise
from .workflow import (CHECKS, DEFINITION, compute, compute_or_read, run,
                       source_digest, write)

__all__ = ["STUDY", "Row", "Order", "DEFINITION", "compute_or_read", "write", "run",
           "source_digest", "drop_mass", "PASS", "FAIL", "SKIP", "CHECKS", "relative_row",
           "absolute_row", "bound_row", "skipped_row", "order_row",
           "compute", "fmt", "error_text", "summarise", "key_numbers", "CheckContext",
           "verification_dataset", "rows_of", "orders_of", "failures", "status_counts"]
