"""The declared dependencies are enough: what ``pyproject.toml`` names installs everything that a
command needs, and a command that needs an optional extra says so in one line.

A fresh install is simulated in a child process: the distributions ``pyproject.toml`` declares
(for the core, or the core and some extras) are followed through the installed packages'
own requirements (``importlib.metadata``, markers evaluated), and every top-level module of an
installed distribution outside that closure is made unimportable. The child then runs the
command. Reference: ``pyproject.toml`` and the installed packages' metadata; ``.ci/run`` does
the same with real fresh virtual environments.
"""

from __future__ import annotations

import importlib.metadata as metadata
import json
import os
import re
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest
from packaging.markers import default_environment
from packaging.requirements import Requirement
from packaging.utils import canonicalize_name

ROOT = Path(__file__).resolve().parents[1]


def declared(extras: frozenset[str] = frozenset()) -> list[Requirement]:
    """The requirements ``pyproject.toml`` declares for the core and ``extras``, with the
    project's own extras (``upliftlab[plot,...]``) expanded."""
    project = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]
    optional, wanted, seen = project.get("optional-dependencies", {}), set(extras), set()
    out = [Requirement(r) for r in project["dependencies"]]
    while wanted - seen:
        extra = (wanted - seen).pop()
        seen.add(extra)
        for text in optional[extra]:
            req = Requirement(text)
            if canonicalize_name(req.name) == "upliftlab":
                wanted |= req.extras
            else:
                out.append(req)
    return out


def closure(requirements: list[Requirement]) -> set[str]:
    """The canonical names of the installed distributions that ``requirements`` pull in,
    transitively, as pip would resolve them here (markers evaluated with each extra)."""
    found: set[str] = set()
    todo = [(r, frozenset(r.extras)) for r in requirements]
    while todo:
        req, extras = todo.pop()
        name = canonicalize_name(req.name)
        key = f"{name}[{','.join(sorted(extras))}]"
        if key in found:
            continue
        found.add(key)
        found.add(name)
        try:
            children = metadata.requires(req.name) or []
        except metadata.PackageNotFoundError:
            continue  # declared but not installed: the import will fail and say so
        for text in children:
            child = Requirement(text)
            if child.marker is None or any(
                    child.marker.evaluate({**default_environment(), "extra": e})
                    for e in (extras or {""})):
                todo.append((child, frozenset(child.extras)))
    return {n for n in found if "[" not in n}


def site_of(allowed: set[str], folder: Path) -> Path:
    """A folder that holds links to the top-level files of the installed distributions in
    ``allowed`` (and of upliftlab): a site-packages as a fresh install of them would have."""
    folder.mkdir(parents=True, exist_ok=True)
    for dist in metadata.distributions():
        if canonicalize_name(dist.metadata["Name"]) not in allowed | {"upliftlab"}:
            continue
        for file in dist.files or ():
            top = file.parts[0]
            source = Path(dist.locate_file(top))
            if top not in ("..", "__pycache__") and source.exists() \
                    and not (folder / top).exists():
                (folder / top).symlink_to(source)
    return folder


CHILD = """
import sys, site
packages = set(site.getsitepackages())
sys.path[:] = [p for p in sys.path if p not in packages] + [sys.argv[1]]
from upliftlab.cli import main
sys.exit(main(sys.argv[2:]))
"""


def run_installed(extras: frozenset[str], argv: list[str], cwd: Path):
    """Run ``upliftlab argv`` as if only the core and ``extras`` were installed (a child whose
    site-packages holds only those distributions; upliftlab's editable finder stays)."""
    site = site_of(closure(declared(extras)), cwd.parent / f"site-{'-'.join(sorted(extras))}")
    env = {**os.environ, "MPLBACKEND": "Agg"}
    return subprocess.run([sys.executable, "-c", CHILD, str(site), *argv], cwd=cwd,
                          capture_output=True, text=True, timeout=1800, env=env)


def test_the_closure_follows_markers_and_extras():
    """The core closure has h5py because pyproject.toml names it, whatever h5netcdf requires;
    an h5netcdf that names h5py only under its extra "h5py" (since 1.4) does not bring it alone
    (reference: the installed h5netcdf's metadata)."""
    assert "h5py" in closure(declared())
    assert "h5py" in {r.split(";")[0].split(">")[0].split("=")[0].split("<")[0].strip()
                      for r in (metadata.requires("upliftlab") or []) if "extra" not in r}
    requires = metadata.requires("h5netcdf") or []
    optional = any(r.startswith("h5py") and "extra" in r for r in requires)
    assert ("h5py" in closure([Requirement("h5netcdf")])) is not optional
    assert "h5py" in closure([Requirement("h5netcdf[h5py]")])
    assert "matplotlib" not in closure(declared())
    assert "matplotlib" in closure(declared(frozenset({"plot"})))


#: The extras that hold the developers' tools, not something a user runs: the docs build and
#: the test command.
DEVELOPER_EXTRAS = {"docs", "test"}


def test_the_all_extra_installs_every_users_extra():
    """``upliftlab[all]`` declares every requirement of every other extra a user can use (all
    but the docs and test tools), and each of them by name (reference: pyproject.toml itself;
    an extra added later and not named in ``all`` fails this)."""
    optional = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"][
        "optional-dependencies"]
    users = set(optional) - DEVELOPER_EXTRAS - {"all"}
    assert users >= {"plot", "continuum", "render", "opensees", "records", "dask"}
    named = set().union(*(Requirement(r).extras for r in optional["all"]
                          if canonicalize_name(Requirement(r).name) == "upliftlab"))
    assert named == users
    everything = {str(r) for r in declared(frozenset({"all"}))}
    for extra in users:
        assert {str(r) for r in declared(frozenset({extra}))} <= everything, extra
    # every extra that a command's refusal names (upliftlab.extras) is a user's extra
    from upliftlab.extras import EXTRAS

    assert set(EXTRAS.values()) <= users


def test_the_core_install_writes_a_result(tmp_path):
    """The writer stack (xarray, h5netcdf, h5py) comes with the core dependencies: a reduced
    run without its figure writes its NetCDF file; its peak reads back."""
    out = tmp_path / "wall"
    done = run_installed(frozenset(), ["run", "wall_free", "--case", "e07", "--no-figure",
                                       "--csv", "--json", "--out", str(out)], tmp_path)
    assert done.returncode == 0, done.stderr[-3000:]
    summary = json.loads(done.stdout)
    import xarray as xr

    with xr.open_dataset(out / "wall_free-e07.nc", engine="h5netcdf") as data:
        assert data.sizes["time"] > 10
    assert summary["peak_u"] > 0


def test_a_command_that_needs_an_extra_says_which_in_one_line(tmp_path):
    """Without the extras, the figure and the continuum are refused with one line that names
    the extra to install, exit 2, nothing written."""
    cases = ((["run", "wall_free", "--case", "e07", "--out", "a"], "plot"),
             (["continuum", "strip_footing_clay", "--out", "b"], "continuum"))
    for argv, extra in cases:
        done = run_installed(frozenset(), argv, tmp_path)
        lines = done.stderr.strip().splitlines()
        assert done.returncode == 2 and len(lines) == 1, done.stderr[-2000:]
        assert re.search(rf"upliftlab\[[a-z,]*{extra}", lines[0]), lines[0]
    assert not any(tmp_path.iterdir())


def _readme_install_commands() -> list[str]:
    """The README's first two commands (its first two ``bash`` blocks)."""
    text = (ROOT / "README.md").read_text()
    return [b.strip() for b in re.findall(r"```bash\n(.*?)```", text, flags=re.S)[:2]]


def test_the_readmes_main_job_needs_only_what_its_install_names(tmp_path, elcentro):
    """The README's first command installs ``.[EXTRAS]`` and runs ``upliftlab ...``: that
    command, with only the core and those extras importable, finishes (exit 0) and writes the
    paper's eight figures (reference: the README's own command and the figures it promises)."""
    first = _readme_install_commands()[0]
    extras = re.search(r'install "\.\[([a-z,]*)\]"', first)
    command = re.search(r"\.venv/bin/upliftlab (.+)$", first)
    assert extras and command, first
    done = run_installed(frozenset(extras.group(1).split(",")), command.group(1).split(),
                         tmp_path)
    assert done.returncode == 0, done.stderr[-3000:]
    figures = sorted(p.name for p in (tmp_path / "results" / "paper").glob("fig*.png"))
    assert len(figures) == 8, figures
