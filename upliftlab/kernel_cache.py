"""Where numba keeps upliftlab's compiled kernels: a folder named by the kernels' place in the
package (``upliftlab.reduced_kernels``), not by where the package is installed.

numba's own locator for ``NUMBA_CACHE_DIR`` names a source's folder ``<folder name>_<sha1 of its
absolute path>``, so that the same kernels installed in another place (a second virtual
environment, ``pip install .`` beside ``pip install -e .``, a CI clone at a new path) are
compiled again, although numba checks a cached function against its source's content (a
SHA-256 of the file) and its bytecode, not its path. :class:`PackageLocator` keeps numba's
checks and drops the path: the README's two commands share their kernels (the tests read those
that the main job compiled), and a reinstall reads those of the last. The folder of every
kernel is inside ``NUMBA_CACHE_DIR``, which upliftlab keys by the kernels' sources' digest
(:data:`upliftlab.KERNEL_SOURCES`). A function outside upliftlab's packages is left to numba's
own locators. Chosen through ``NUMBA_CACHE_LOCATOR_CLASSES``
(:data:`upliftlab.KERNEL_LOCATORS`), which a numba without it ignores: it caches by path as
before.
"""

from __future__ import annotations

import functools
import os
from pathlib import Path

from numba.core import config
from numba.core.caching import UserProvidedCacheLocator


def package_subpath(py_file: str | os.PathLike) -> str | None:
    """The cache folder's name of a source of upliftlab's packages: its folder as
    :func:`upliftlab.provenance.package_files` names it, ``/`` written ``_``
    (``upliftlab.reduced/kernels/events.py`` → ``upliftlab.reduced_kernels``); None for a file
    outside them."""
    return _folders().get(Path(py_file).resolve())


@functools.cache
def _folders() -> dict[Path, str]:
    from .provenance import package_files

    return {path.resolve(): name.rsplit("/", 1)[0].replace("/", "_")
            for name, path in package_files().items() if name.endswith(".py")}


class PackageLocator(UserProvidedCacheLocator):
    """numba's locator for ``NUMBA_CACHE_DIR`` (its source-content stamp, its bytecode key)
    with the folder :func:`package_subpath` names."""

    def __init__(self, py_func, py_file):
        super().__init__(py_func, py_file)
        self._cache_path = os.path.join(config.CACHE_DIR, package_subpath(py_file))

    @classmethod
    def from_function(cls, py_func, py_file):
        if not config.CACHE_DIR or package_subpath(py_file) is None:
            return None
        return super().from_function(py_func, py_file)
