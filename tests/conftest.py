"""Shared fixtures. Tests run with --import-mode=importlib; there is no tests/__init__.py.

A test that needs the El Centro record asks for the ``elcentro`` fixture: it finds the file on
``UPLIFTLAB_MOTIONS``; when the file is missing the test fails and says where it looked, so
that no run can pass by leaving the record's tests out.
"""

from __future__ import annotations

import os
import shutil
import tempfile
from pathlib import Path

import pytest

from upliftlab.checks import InputError
from upliftlab.motions import ELCENTRO, find_motion, load_motion


@pytest.fixture(scope="session")
def elcentro():
    """The El Centro 1940 N-S record (g, 0.02 s), from UPLIFTLAB_MOTIONS."""
    try:
        find_motion(ELCENTRO)
    except InputError as exc:
        pytest.fail(f"the tests need the El Centro record: {exc}")
    return load_motion(ELCENTRO)


@pytest.fixture(scope="session")
def cf_failures():
    """A function: the checks of the CF-1.10 conventions that a NetCDF file fails, as the IOOS
    compliance checker (``compliance-checker --test cf:1.10``, with its CF standard-name table
    and UDUNITS) finds them: ``(required, errors)``, the failing high-priority checks as
    ``section: messages`` lines and the checks that raised instead of running."""
    from compliance_checker.base import BaseCheck
    from compliance_checker.suite import CheckSuite

    CheckSuite.load_all_available_checkers()

    def failures(path) -> tuple[list[str], list[str]]:
        suite = CheckSuite()
        ds = suite.load_dataset(str(path))
        try:
            groups, errors = suite.run_all(ds, ["cf:1.10"])["cf:1.10"]
        finally:
            ds.close()
        required = [f"{g.name}: {g.msgs or [m for c in g.children for m in c.msgs]}"
                    for g in groups if g.weight >= BaseCheck.HIGH and g.value[0] != g.value[1]]
        return required, [f"{name}: {exc}" for name, (exc, _) in errors.items()]

    return failures


class FastStores:
    """Stores of the points of fast studies that this test session has made, shared by its
    worker processes. A module that makes a fast study publishes its store (:meth:`publish`);
    a module that needs the same study's results but does not test their making seeds its own
    store from it first (:meth:`seed`) and reads those points back: the path a resumed run
    takes. Nothing waits: a study not yet published is made, so which path a reader takes
    depends on the order the workers meet the modules, and both give the same numbers."""

    def __init__(self, root: Path):
        self.root = root

    def seed(self, name: str, store: Path) -> None:
        """Copy the published store of study ``name`` into the folder ``store``, when one is
        published."""
        if (self.root / name).is_dir():
            shutil.copytree(self.root / name, store, dirs_exist_ok=True)

    def publish(self, name: str, store: Path) -> None:
        """Publish the folder ``store`` as study ``name``'s, unless one is published already
        (a copy, renamed into place whole: a reader never sees half of it)."""
        self.root.mkdir(parents=True, exist_ok=True)
        if (self.root / name).exists() or not store.is_dir():
            return
        staging = Path(tempfile.mkdtemp(prefix=f".{name}.", dir=self.root))
        shutil.copytree(store, staging / "store")
        try:
            (staging / "store").rename(self.root / name)
        except OSError:  # another worker published it first
            pass
        shutil.rmtree(staging, ignore_errors=True)


@pytest.fixture(scope="session")
def fast_stores(tmp_path_factory):
    """The session's :class:`FastStores`: under pytest-xdist in the folder the workers'
    temporary folders share (one per session), else in this session's own."""
    base = tmp_path_factory.getbasetemp()
    return FastStores((base.parent if os.environ.get("PYTEST_XDIST_WORKER") else base)
                      / "fast-stores")


@pytest.fixture
def fifo(tmp_path):
    """A function: a named pipe at ``tmp_path / name`` with a writer waiting for a reader.

    Code that opens the pipe to read it then reads an empty file at once instead of waiting
    forever for a writer (so a test of a pipe fails, and never hangs, where it is opened); at
    the end of the test the waiting writer is released by opening the pipe without waiting."""
    import threading

    made = []

    def make(name: str) -> Path:
        path = tmp_path / name
        path.parent.mkdir(parents=True, exist_ok=True)
        os.mkfifo(path)

        def write_nothing():
            os.close(os.open(path, os.O_WRONLY))  # waits until someone opens it to read

        writer = threading.Thread(target=write_nothing, daemon=True)
        writer.start()
        made.append((path, writer))
        return path

    yield make
    for path, writer in made:
        reader = os.open(path, os.O_RDONLY | os.O_NONBLOCK)  # lets a waiting writer go on
        writer.join()
        os.close(reader)
