"""Every shell command of the README and the docs pages works as written, and is exercised.

The commands are the lines of the ``bash`` code blocks of ``README.md`` and of every page of
``docs/`` (the pages the docs build generates are not read). :data:`EXERCISED` says, for each,
what runs it: ``ci`` (``.ci/run`` runs the README's first two, as written), ``ci-docs``
(``.ci/run`` builds the docs with it, as written), ``here`` (:func:`test_docs_command` runs it
as written, in a scratch working directory so that its ``results/`` land there), ``slow`` (the
same, marked slow: minutes), or the test that runs it with only ``--out`` added. A command added to a page
without an entry here fails :func:`test_every_docs_command_is_exercised`, and so does an entry
whose command left every page. No test here reads the README's prose. Reference: the pages
themselves, ``.ci/run`` and the files the commands are documented to write.
"""

from __future__ import annotations

import ast
import hashlib
import os
import re
import shlex
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from upliftlab.cli import main as cli
from upliftlab.outdir import read_marker

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"
#: Folders of docs/ that the docs build writes (autosummary, sphinx-gallery), not pages.
GENERATED = {"api", "auto_gallery", "_build", "_templates"}

AT2 = ("PEER NGA STRONG MOTION DATABASE RECORD\nan example record\nACCELERATION TIME SERIES IN "
       "UNITS OF G\nNPTS=   6, DT=   .0200 SEC\n0.0 0.05 0.1 -0.1 -0.05 0.0\n")

#: Command of a README or docs ``bash`` block -> how it is exercised, and the files it must leave
#: (relative to its cwd).
EXERCISED = {
    '.venv/bin/python -m pip install -e ".[docs]" && .venv/bin/python -m sphinx -j auto -W '
    '--keep-going -b html docs docs/_build/html': ("ci-docs", ()),
    'python3 -m venv .venv && .venv/bin/python -m pip install ".[plot]" && '
    '.venv/bin/upliftlab paper --out results/paper': ("ci", ()),
    'python3 -m venv .venv && .venv/bin/python -m pip install -e ".[test]" && '
    '.venv/bin/python -m pytest': ("ci", ()),
    "upliftlab run short_period_elcentro --case C":
        ("here", ("results/short_period_elcentro-C/short_period_elcentro-C.nc",
                  "results/short_period_elcentro-C/short_period_elcentro-C.png")),
    "upliftlab run short_period_elcentro --case C --set foundation.springs=40 --json":
        ("here", ()),
    "upliftlab run wall_free --case e07 --csv --out results/wall":
        ("here", ("results/wall/wall_free-e07.nc", "results/wall/wall_free-e07.csv",
                  "results/wall/wall_free-e07.png")),
    "upliftlab run my_scene.toml --motion path/to/record.AT2 --set motion.pga=0.4":
        ("here", ()),
    "upliftlab continuum strip_footing_clay --analysis pushover --out results/clay":
        ("slow", ("results/clay/result.nc", "results/clay/uplift.png",
                  "results/clay/moment_rotation.png", "results/clay/fields.xdmf")),
    "upliftlab continuum strip_footing_clay --analysis dynamic --motion elcentro_1940_ns "
    "--set analysis.duration=2 --out results/clay-ec-2s":
        ("slow", ("results/clay-ec-2s/result.nc", "results/clay-ec-2s/uplift.gif")),
    "upliftlab continuum strip_footing_clay --mesh elements_across=4 --steps 6 --no-render "
    "--out results/clay-coarse && python -c \"from upliftlab.continuum.output import read_xdmf; "
    "f = read_xdmf('results/clay-coarse/footing.xdmf'); print(f['information']['time'], "
    "f['times'][-1])\"":
        ("here", ("results/clay-coarse/result.nc", "results/clay-coarse/fields.xdmf",
                  "results/clay-coarse/footing.xdmf", "results/clay-coarse/footing.h5")),
    "upliftlab report --out results/report":
        ("tests/test_report.py::test_the_readmes_full_build_builds_every_section", ()),
    "upliftlab report --fast": ("tests/test_report.py::test_report_writes_one_self_contained_html",
                                ()),
    "upliftlab advise short_period_elcentro --case B --quantity peak_u --tol 1%": ("slow", ()),
    "upliftlab advise strip_footing_clay --quantity peak_theta --tol 10% --fast "
    "--set motion.period=0.2 --set motion.duration=0.6": ("slow", ()),
    "upliftlab study two_spring_equivalence --fast --out "
    "results/two_spring_equivalence-fast":
        ("slow", ("results/two_spring_equivalence-fast/summary.md",)),
    "upliftlab study winkler_map --fast --out results/winkler_map-fast":
        ("slow", ("results/winkler_map-fast/summary.md", "results/winkler_map-fast/map.nc")),
    "upliftlab study winkler_map --grid elcentro=false --grid "
    "fema_components=0 --store benchmarks/winkler_map_store --out results/winkler_map-pulses":
        ("tests/test_winkler_map.py::test_the_readme_map_commands_are_estimated_before_they_run",
         ()),
    "upliftlab study winkler_map --grid soils=clay --grid periods=0.5 --grid "
    "intensities=3 --grid pulse_periods= --grid fema_components=10 --store "
    "benchmarks/winkler_map_store --out results/winkler_map-clay-records":
        ("tests/test_winkler_map.py::test_the_readme_map_commands_are_estimated_before_they_run",
         ()),
    "upliftlab study winkler_map --grid soils=clay --grid periods=0.5 --grid "
    "intensities=1.5 --grid pulse_periods= --grid fema_components=10 --store "
    "benchmarks/winkler_map_store --out results/winkler_map-clay-records-1.5":
        ("tests/test_winkler_map.py::test_the_readme_map_commands_are_estimated_before_they_run",
         ()),
    "upliftlab study winkler_map --grid soils=clay --grid periods=0.2 --grid "
    "intensities=3 --grid pulse_periods= --grid fema_components=10 --store "
    "benchmarks/winkler_map_store --out results/winkler_map-clay-records-0.2s":
        ("tests/test_winkler_map.py::test_the_readme_map_commands_are_estimated_before_they_run",
         ()),
    "upliftlab study winkler_map --grid soils=clay --grid periods=0.2 --grid "
    "intensities=1.5 --grid pulse_periods= --grid fema_components=10 --store "
    "benchmarks/winkler_map_store --out results/winkler_map-clay-records-0.2s-1.5":
        ("tests/test_winkler_map.py::test_the_readme_map_commands_are_estimated_before_they_run",
         ()),
    "upliftlab study winkler_map --grid soils=clay --store "
    "benchmarks/winkler_map_store --out results/winkler_map-clay":
        ("tests/test_winkler_map.py::test_the_readme_map_commands_are_estimated_before_they_run",
         ()),
    "upliftlab study winkler_map --grid soils=sand --grid periods=0.5 --grid "
    "intensities=3 --grid pulse_periods= --grid fema_components=10 --store "
    "benchmarks/winkler_map_store --out results/winkler_map-sand-records":
        ("tests/test_winkler_map.py::test_the_readme_map_commands_are_estimated_before_they_run",
         ()),
    "upliftlab study winkler_map --grid soils=sand --grid periods=0.5 --grid "
    "intensities=1.5 --grid pulse_periods= --grid fema_components=10 --store "
    "benchmarks/winkler_map_store --out results/winkler_map-sand-records-1.5":
        ("tests/test_winkler_map.py::test_the_readme_map_commands_are_estimated_before_they_run",
         ()),
    "upliftlab study winkler_map --grid soils=sand --grid periods=0.2 --grid "
    "intensities=1.5 --grid pulse_periods= --grid fema_components=10 --store "
    "benchmarks/winkler_map_store --out results/winkler_map-sand-records-0.2s-1.5":
        ("tests/test_winkler_map.py::test_the_readme_map_commands_are_estimated_before_they_run",
         ()),
    "upliftlab study winkler_map --grid soils=sand --grid periods=0.2 --grid "
    "intensities=3 --grid pulse_periods= --grid fema_components=10 --store "
    "benchmarks/winkler_map_store --out results/winkler_map-sand-records-0.2s":
        ("tests/test_winkler_map.py::test_the_readme_map_commands_are_estimated_before_they_run",
         ()),
    "upliftlab study winkler_map --energy --grid h_over_B=1.5 --grid "
    "periods=0.5 --grid intensities=3 --grid pulse_periods= --grid fema_components=10 --store "
    "benchmarks/winkler_map_store --out results/winkler_map-energy-records":
        ("tests/test_winkler_map.py::test_the_readme_map_commands_are_estimated_before_they_run",
         ()),
    "upliftlab study winkler_map --store benchmarks/winkler_map_store "
    "--out results/winkler_map":
        ("tests/test_winkler_map.py::test_the_readme_map_commands_are_estimated_before_they_run",
         ()),
    "upliftlab continuum strip_footing_clay --analysis impedance --set soil.model=elastic "
    "--json": ("here", ()),
    "upliftlab opensees short_period_elcentro --case A --out results/opensees-A && "
    "python results/opensees-A/model.py":
        ("slow", ("results/opensees-A/model.py", "results/opensees-A/motion.txt")),
    "upliftlab opensees short_period_elcentro --case B --run --out results/opensees-B":
        ("slow", ("results/opensees-B/comparison.md",)),
    "upliftlab opensees three_story_frame --set foundation.restitution=1 --run --json":
        ("slow", ()),
    "upliftlab continuum strip_footing_clay --analysis dynamic --error-estimate --out "
    "results/clay-estimate":
        ("slow", ("results/clay-estimate/error_estimate.nc",
                  "results/clay-estimate/error_estimate.json")),
    "upliftlab continuum strip_footing_clay --analysis dynamic --error-estimate=3 --out "
    "results/clay-estimate-3":
        ("slow", ("results/clay-estimate-3/error_estimate.nc",
                  "results/clay-estimate-3/error_estimate.json")),
}


def pages() -> list[Path]:
    """The README and every Markdown page of the docs (not what the docs build generates)."""
    found = [p for p in sorted(DOCS.rglob("*.md"))
             if not GENERATED & set(p.relative_to(DOCS).parts)]
    return [ROOT / "README.md", *found]


def block_commands(text: str) -> list[str]:
    """The commands of a page's ``bash`` code blocks, one per line, comments removed."""
    commands = []
    for block in re.findall(r"```bash\n(.*?)```", text, flags=re.S):
        for line in block.splitlines():
            command = line.split(" #", 1)[0].strip() if not line.lstrip().startswith("#") else ""
            if command:
                commands.append(command)
    return commands


def docs_commands() -> dict[str, list[str]]:
    """Command -> the pages (relative to the repository) that show it."""
    shown: dict[str, list[str]] = {}
    for page in pages():
        for command in block_commands(page.read_text(encoding="utf-8")):
            shown.setdefault(command, []).append(str(page.relative_to(ROOT)))
    return shown


def test_every_docs_command_is_exercised():
    shown = docs_commands()
    assert len(shown) >= 10
    missing = {c: where for c, where in shown.items() if c not in EXERCISED}
    assert not missing, f"commands of the docs that no test or CI runs: {missing}"
    stale = [c for c in EXERCISED if c not in shown]
    assert not stale, f"entries for commands no page shows any more: {stale}"
    ci = (ROOT / ".ci" / "run").read_text()
    for command, (how, _) in EXERCISED.items():
        if how == "ci-docs":
            assert command in ci, command  # .ci/run builds the docs with it, as written
        elif "::" in how:
            path, name = how.split("::")
            tree = ast.parse((ROOT / path).read_text())
            assert name in {n.name for n in ast.walk(tree) if isinstance(n, ast.FunctionDef)}
            argv = shlex.split(command)[1:] + ["--out"]  # the test adds only --out
            fragment = ", ".join(f'"{a}"' for a in argv)
            if fragment not in (ROOT / path).read_text():  # else built there: its table holds it
                function = next(n for n in ast.walk(tree)
                                if isinstance(n, ast.FunctionDef) and n.name == name)
                assert "README_MAP_COMMANDS" in ast.unparse(function), (how, fragment)
                assert argv in _built_argvs(ROOT / path), (how, fragment)


def test_ci_runs_the_readmes_first_two_commands():
    """``.ci/run`` runs the README's first two commands (``.ci/readme_commands.py README.md 2``),
    the main job first, and they are the two the table marks ``ci``."""
    ci = (ROOT / ".ci" / "run").read_text()
    assert "readme_commands.py README.md 2" in ci
    first_two = subprocess.run([sys.executable, str(ROOT / ".ci" / "readme_commands.py"),
                                str(ROOT / "README.md"), "2"], capture_output=True, text=True,
                               check=True).stdout.splitlines()
    marked = [c for c, (how, _) in EXERCISED.items() if how == "ci"]
    assert first_two == marked
    assert "upliftlab paper" in first_two[0] and "pytest" in first_two[1]


def test_the_readme_is_the_front_door():
    """At most 200 lines (the design's limit), and neither it nor a docs page sends a reader to
    a folder of the machine that built it (the El Centro record is the user's to supply)."""
    assert len((ROOT / "README.md").read_text().splitlines()) <= 200
    for page in pages():
        text = page.read_text(encoding="utf-8")
        for pattern in ("/work/shared", "../shared", "shared/data"):
            assert pattern not in text, f"{page}: {pattern}"


def _built_argvs(path: Path) -> list[list[str]]:
    """The argv of the docs' commands a test module builds rather than writes out (its
    ``README_MAP_COMMANDS`` table: argv, the count, the grid)."""
    import importlib.util

    spec = importlib.util.spec_from_file_location(f"_docs_{path.stem}", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return [list(row[0]) for row in getattr(module, "README_MAP_COMMANDS", ())]


def test_ci_reads_the_record_from_the_environment_when_set():
    """``.ci/run`` works from any clone: $UPLIFTLAB_MOTIONS first, ../shared beside it else."""
    script = (ROOT / ".ci" / "run").read_text()
    line = next(x for x in script.splitlines() if x.startswith("export UPLIFTLAB_MOTIONS="))
    for env, expected in (({"UPLIFTLAB_MOTIONS": "/somewhere/motions"}, "/somewhere/motions"),
                          ({}, str(ROOT.parent / "shared" / "data" / "motions"))):
        env = {"PATH": os.environ["PATH"], **env}
        out = subprocess.run(["bash", "-c", f"{line}; echo $UPLIFTLAB_MOTIONS"], cwd=ROOT,
                             env=env, capture_output=True, text=True, check=True).stdout
        assert out.strip() == expected


def _prepare(cwd: Path) -> None:
    """The files the docs' examples name: ``my_scene.toml`` (a scene of the user's: here a
    copy of a packaged one) and ``path/to/record.AT2``."""
    shutil.copy(ROOT / "scenes" / "short_period_free.toml", cwd / "my_scene.toml")
    (cwd / "path" / "to").mkdir(parents=True)
    (cwd / "path" / "to" / "record.AT2").write_text(AT2)


def _run(command: str, cwd: Path, monkeypatch) -> None:
    """Run a docs command as written: ``upliftlab ...`` in this process, ``python ...`` in a
    child, commands joined by ``&&`` one after the other."""
    monkeypatch.chdir(cwd)
    monkeypatch.setenv("MPLBACKEND", "Agg")
    for part in command.split(" && "):
        argv = shlex.split(part)
        if argv[0] == "upliftlab":
            assert cli(argv[1:]) == 0, part
            continue
        assert argv[0] == "python", part
        result = subprocess.run([sys.executable, *argv[1:]], cwd=cwd, capture_output=True,
                                text=True, timeout=3600)
        assert result.returncode == 0, result.stderr[-2000:]


def _check_files(command: str, files, cwd: Path) -> None:
    """The files exist; a folder written by ``upliftlab`` holds its completion marker (a study
    run by ``python -m`` writes its summary last instead)."""
    for name in files:
        assert (cwd / name).is_file(), f"{command}: {name} was not written"
    if command.startswith("upliftlab "):
        for folder in {(cwd / f).parent for f in files}:
            assert (read_marker(folder) or {}).get("complete"), folder


@pytest.mark.parametrize("command", [c for c, (how, _) in EXERCISED.items() if how == "here"])
def test_docs_command(command, tmp_path, monkeypatch, elcentro):
    _prepare(tmp_path)
    _run(command, tmp_path, monkeypatch)
    _check_files(command, EXERCISED[command][1], tmp_path)


@pytest.mark.slow
@pytest.mark.parametrize("command", [c for c, (how, _) in EXERCISED.items() if how == "slow"])
def test_docs_command_slow(command, tmp_path, monkeypatch, elcentro):
    _prepare(tmp_path)
    _run(command, tmp_path, monkeypatch)
    _check_files(command, EXERCISED[command][1], tmp_path)


def test_python_m_upliftlab_from_the_repository_root_uses_the_checkout():
    """``python -m upliftlab`` from the root of a checkout with the editable install (the
    README's test command): the core comes from the root's ``upliftlab/`` folder and the
    subpackages through the editable install's mapping, so every module is the checkout's own,
    with no path added by the package itself. Reference: the checkout's files."""
    code = ("import upliftlab.reduced, upliftlab.continuum, upliftlab.comparisons\n"
            "from upliftlab.scenes import packaged_scenes\n"
            "print(upliftlab.__file__, upliftlab.reduced.__file__, "
            "upliftlab.comparisons.__file__, len(packaged_scenes()))\n")
    result = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True,
                            text=True)
    assert result.returncode == 0, result.stderr[-2000:]
    core, reduced, comparisons, count = result.stdout.split()
    assert core == str(ROOT / "upliftlab" / "__init__.py")
    assert reduced == str(ROOT / "reduced" / "__init__.py")
    assert comparisons == str(ROOT / "comparisons" / "__init__.py")
    assert int(count) == len(list((ROOT / "scenes").glob("*.toml")))


def test_compiled_kernels_are_cached_outside_the_installed_package(tmp_path):
    """The README's first command (a non-editable install) ran the kernels, numba cached them
    in site-packages/upliftlab, ``pip uninstall`` left that folder, and the README's test
    command then imported it as an empty namespace package. The cache now goes to
    $XDG_CACHE_HOME/upliftlab/numba/<digest of the kernels' sources: reduced/kernels/ and the
    reduced laws' compiled forms in reduced/laws/, which the kernels inline>, also when numba was
    imported first. The digest also covers the continuum's compiled kernels, whose soil
    models' point returns (one module each in continuum/materials/) are compiled into the element
    loops of dynamics/kernels.py, and the explicit time loop (dynamics/explicit_loop.py), cached
    on disk, that inlines those loops and the contact steps (contact/). Reference: hashlib over
    (name, bytes) of those files."""
    code = ("import numba, os, upliftlab\n"
            "print(os.environ['NUMBA_CACHE_DIR'], numba.config.CACHE_DIR)\n")
    env = {k: v for k, v in os.environ.items() if k != "NUMBA_CACHE_DIR"}
    env["XDG_CACHE_HOME"] = str(tmp_path)
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True,
                         check=True).stdout.split()
    root = Path(__file__).resolve().parents[1]
    kernels = [(f"upliftlab.reduced/kernels/{p.name}", p)
               for p in sorted((root / "reduced" / "kernels").glob("*.py"))]
    kernels += [(f"upliftlab.reduced/laws/{p.relative_to(root / 'reduced' / 'laws').as_posix()}",
                 p) for p in sorted((root / "reduced" / "laws").rglob("*.py"))]
    kernels += [(f"upliftlab.continuum/dynamics/{name}", root / "continuum" / "dynamics" / name)
                for name in ("kernels.py", "explicit_loop.py")]
    for folder in ("materials", "contact"):
        base = root / "continuum" / folder
        kernels += [(f"upliftlab.continuum/{folder}/{p.relative_to(base).as_posix()}", p)
                    for p in sorted(base.rglob("*.py")) if "__pycache__" not in p.parts]
    digest = hashlib.sha256(b"".join(name.encode() + b"\0" + p.read_bytes() + b"\0"
                                     for name, p in sorted(kernels))).hexdigest()[:16]
    assert out == [str(tmp_path / "upliftlab" / "numba" / digest)] * 2
    env["NUMBA_CACHE_DIR"] = str(tmp_path / "mine")  # a user's own choice is kept
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True,
                         check=True).stdout.split()
    assert out == [str(tmp_path / "mine")] * 2
