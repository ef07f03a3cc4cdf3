"""What a pool of worker processes inherits from the process that starts it.

Worker pools (the reduced model's batch, the studies' sweeps) run one single-threaded task per
core: :data:`SINGLE_THREAD_ENVIRONMENT` keeps OpenMP, BLAS and numba from starting a thread per
core in every worker, which on a two-core machine would oversubscribe it many times over. A
spawned worker reads these variables when its libraries load, so they are set in the parent
while the pool starts (:func:`inherited_environment`), not in the worker.
"""

from __future__ import annotations

import contextlib
import os
from collections.abc import Iterator, Mapping

__all__ = ["SINGLE_THREAD_ENVIRONMENT", "inherited_environment"]

#: One thread for OpenMP, MKL, OpenBLAS and numba.
SINGLE_THREAD_ENVIRONMENT = {"OMP_NUM_THREADS": "1", "MKL_NUM_THREADS": "1",
                             "OPENBLAS_NUM_THREADS": "1", "NUMBA_NUM_THREADS": "1"}


@contextlib.contextmanager
def inherited_environment(values: Mapping[str, str]) -> Iterator[None]:
    """Set environment variables for the block (processes spawned in it inherit them); the
    earlier values, or their absence, come back when it ends."""
    old = {k: os.environ.get(k) for k in values}
    os.environ.update(values)
    try:
        yield
    finally:
        for k, v in old.items():
            if v is None:
                os.environ.pop(k, None)
            else:
                os.environ[k] = v
