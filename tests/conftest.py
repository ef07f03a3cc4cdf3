"""Shared fixtures. Tests run with --import-mode=importlib; there is no tests/__init__.py.

A test that needs the El Centro record asks for the ``elcentro`` fixture: it finds the file on
``UPLIFTLAB_MOTIONS``; when the file is missing it skips on a developer's machine and *fails*
under CI (``CI=true``), so that a CI run can never pass by skipping the record's tests.
"""

from __future__ import annotations

import os

import pytest

from upliftlab.checks import InputError
from upliftlab.motions import ELCENTRO, find_motion, load_motion


@pytest.fixture(scope="session")
def elcentro():
    """The El Centro 1940 N-S record (g, 0.02 s), from UPLIFTLAB_MOTIONS."""
    try:
        find_motion(ELCENTRO)
    except InputError as exc:
        if os.environ.get("CI", "").lower() in ("1", "true", "yes"):
            pytest.fail(f"CI needs the El Centro record: {exc}")
        pytest.skip(f"El Centro record not available: {exc}")
    return load_motion(ELCENTRO)
