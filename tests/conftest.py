"""Shared fixtures. Tests run with --import-mode=importlib; there is no tests/__init__.py.

A test that needs the El Centro record asks for the ``elcentro`` fixture: it finds the file on
``UPLIFTLAB_MOTIONS``; when the file is missing the test fails and says where it looked, so
that no run can pass by leaving the record's tests out.
"""

from __future__ import annotations


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
