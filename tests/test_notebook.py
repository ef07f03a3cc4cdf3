"""Results at home in a notebook: the docs gallery's notebook runs in a Jupyter kernel and shows
its tables, plots and progress bar; ``plot()`` draws the result's own arrays, ``_repr_html_``
states its peaks, ``render()`` returns the soil picture without writing a file, and the
progress bars appear where they are asked for (:mod:`upliftlab.progress`).

References: the result's arrays and peaks (computed by the run, not by the plotting code under
test); the notebook's own printed numbers; tqdm's documented bar format ("n/total", "%|").
"""

from __future__ import annotations

import ast
import re
from pathlib import Path

import matplotlib
import nbformat
import numpy as np
import pytest
from nbclient import NotebookClient

from upliftlab.checks import InputError
from upliftlab.continuum import DynamicOptions, build_model, rotation_pushover, run_dynamic
from upliftlab.progress import steps_progress, watched
from upliftlab.reduced import run
from upliftlab.scenes import load_scene

matplotlib.use("Agg")

GALLERY_NOTEBOOK = (Path(__file__).resolve().parents[1] / "docs" / "gallery"
                    / "plot_6_in_a_notebook.py")
COARSE = ["continuum.elements_across=4"]


def notebook_of(script: Path):
    """The notebook of a gallery script, as sphinx-gallery makes it for download: its docstring
    a Markdown cell, each ``# %%`` block's leading comment a Markdown cell and its code a code
    cell."""
    text = script.read_text()
    doc = ast.get_docstring(ast.parse(text))
    body = text.split('"""', 2)[2]
    cells = [nbformat.v4.new_markdown_cell(doc)]
    for block in re.split(r"^# %%\n", body, flags=re.M)[1:]:
        lines = block.splitlines()
        leading = next((i for i, line in enumerate(lines) if not line.startswith("# ")),
                       len(lines))
        comment = [line[2:] for line in lines[:leading]]
        code = "\n".join(lines[leading:]).strip()
        if comment:
            cells.append(nbformat.v4.new_markdown_cell("\n".join(comment)))
        cells.append(nbformat.v4.new_code_cell(code))
    return nbformat.v4.new_notebook(cells=cells)


def _outputs(notebook) -> list:
    return [out for cell in notebook.cells if cell.cell_type == "code" for out in cell.outputs]


def test_the_gallery_notebook_runs_in_a_kernel(tmp_path):
    # Reference: the notebook's printed peaks (its stdout) appear in its tables; tqdm's bar
    # format "1200/1200" and "%|" (std bar) or its widget; every plot a PNG display.
    notebook = notebook_of(GALLERY_NOTEBOOK)
    NotebookClient(notebook, timeout=900, kernel_name="python3",
                   resources={"metadata": {"path": str(tmp_path)}}).execute()
    outputs = _outputs(notebook)
    errors = [o for o in outputs if o.output_type == "error"]
    assert not errors, errors
    stdout = "".join(o.text for o in outputs if o.output_type == "stream" and o.name == "stdout")
    stderr = "".join(o.text for o in outputs if o.output_type == "stream" and o.name == "stderr")
    rich = [o for o in outputs if o.output_type in ("execute_result", "display_data")]
    tables = [o.data["text/html"] for o in rich if "text/html" in o.data]
    pngs = [o for o in rich if "image/png" in o.data]
    widgets = [o for o in rich if "application/vnd.jupyter.widget-view+json" in o.data]
    # two tables (reduced, continuum), three figures (two plots, one render)
    assert len(tables) == 2 and all(t.startswith("<table>") for t in tables)
    assert len(pngs) == 3
    assert not any("<Figure size" in o.data.get("text/plain", "") and "image/png" not in o.data
                   for o in rich)
    reduced_peak = re.search(r"peak θ = (\S+) rad", stdout).group(1)
    continuum_peak = re.search(r"peak \|θ\| = (\S+) rad", stdout).group(1)
    assert f"<td style='text-align:left'>{reduced_peak} rad</td>" in tables[0]
    assert f"<td style='text-align:left'>{continuum_peak} rad</td>" in tables[1]
    assert widgets or ("%|" in stderr and re.search(r"(\d+)/\1 \[", stderr)), stderr[-500:]
    assert not list(tmp_path.iterdir())  # nothing written


# ---------------------------------------------------------------------------------------------
# The reduced model's result
# ---------------------------------------------------------------------------------------------


@pytest.fixture(scope="module")
def wall():
    return run(load_scene("strip_footing_clay"))


def test_the_reduced_plot_draws_the_results_arrays(wall):
    # Reference: the Response's own histories (exact: the plot draws them, no copy changes a bit)
    fig = wall.plot()
    lines = [ax.lines[0] for ax in fig.axes]
    assert [ax.get_ylabel() for ax in fig.axes][0] == "θ [rad]"
    assert np.array_equal(lines[0].get_xdata(), wall.time)
    assert np.array_equal(lines[0].get_ydata(), wall.theta)
    assert np.array_equal(lines[1].get_ydata(), wall.uplift.max(axis=1))
    assert np.array_equal(lines[2].get_ydata(), -wall.V)
    assert np.array_equal(lines[3].get_xdata(), wall.theta)
    assert np.array_equal(lines[3].get_ydata(), wall.overturning_moment)
    assert float(np.max(wall.uplift)) > 0.0  # the footing uplifts: the panel is not empty


def test_the_reduced_plot_takes_variables_and_axes(wall):
    import matplotlib.pyplot as plt

    fig, (a, b) = plt.subplots(2, 1)
    assert wall.plot(["u", "contact"], ax=(a, b)) is fig
    assert np.array_equal(a.lines[0].get_ydata(), wall.u)
    assert np.array_equal(b.lines[0].get_ydata(), wall.contact_length)
    with pytest.raises(InputError, match="variables = 'drift'"):
        wall.plot("drift")
    with pytest.raises(InputError, match="1 axes for 2 panels"):
        wall.plot(["u", "theta"], ax=a)
    plt.close("all")


def test_the_reduced_table_states_the_peaks(wall):
    # Reference: the Response's tracked peaks and its provenance record
    html = wall._repr_html_()
    peaks = wall.peaks
    assert f"{peaks['theta']:.4g} rad" in html
    assert f"{peaks['u']:.4g} m" in html and f"{peaks['uplift_max']:.4g} m" in html
    assert wall.provenance["source_sha256"][:12] in html
    assert "strip_footing_clay" in html and f"{wall.time.size} stored times" in html


# ---------------------------------------------------------------------------------------------
# The continuum's results
# ---------------------------------------------------------------------------------------------


@pytest.fixture(scope="module")
def coarse():
    scene = load_scene("strip_footing_clay", overrides=COARSE + ["motion.duration=0.4"])
    model = build_model(scene)
    result = run_dynamic(model, scene, scene.build_motion(), DynamicOptions(snapshots=3),
                         progress=False)
    return model, result


def test_the_continuum_plot_draws_the_results_arrays(coarse):
    # Reference: the DynamicResult's own histories (exact)
    _, result = coarse
    fig = result.plot()
    lines = [ax.lines[0] for ax in fig.axes]
    assert np.array_equal(lines[0].get_xdata(), result.time)
    assert np.array_equal(lines[0].get_ydata(), result.footing[:, 2])
    assert np.array_equal(lines[1].get_ydata(), -result.footing[:, 1])
    assert np.array_equal(lines[2].get_ydata(), result.gap.max(axis=1))
    assert np.array_equal(lines[3].get_xdata(), result.theta)
    assert np.array_equal(lines[3].get_ydata(), result.M)


def test_the_continuum_table_states_the_peaks(coarse):
    # Reference: the result's histories and provenance
    _, result = coarse
    html = result._repr_html_()
    assert f"{np.max(np.abs(result.theta)):.4g} rad" in html
    assert f"{np.max(-result.footing[:, 1]):.4g} m" in html
    assert f"{np.max(result.N):.4g} kN/m" in html
    assert f"{result.energy_balance_error:.3g}" in html
    assert result.metadata["source_sha256"][:12] in html
    assert f"{result.time.size} rows over" in html


def test_render_returns_the_soil_picture_and_writes_nothing(coarse, tmp_path, monkeypatch):
    # Reference: the result's contact pressure and gap at the chosen snapshot's row, drawn
    # exactly in the picture's contact panel
    monkeypatch.chdir(tmp_path)
    model, result = coarse
    row = int(result.snapshot_step[1])
    fig = result.render(model, 1)
    drawn = [line.get_ydata() for ax in fig.axes for line in ax.lines]
    assert any(np.array_equal(y, result.pressure[row]) for y in drawn)
    assert any(np.array_equal(y, result.gap[row]) for y in drawn)
    assert f"t = {result.time[row]:.3f} s" in fig.get_suptitle()
    assert not list(tmp_path.iterdir())
    with pytest.raises(InputError, match="snapshot = 3"):
        result.render(model, 3)
    with pytest.raises(InputError, match="snapshot = 0.5"):
        result.render(model, 0.5)


def test_a_pushover_plots_renders_and_shows_a_bar(coarse, capsys):
    # Reference: the path's own arrays; tqdm's bar format "5/5", "%|"
    model, _ = coarse
    rotations = np.linspace(0.0, 0.004, 6)[1:]
    path = rotation_pushover(model, 171.39, rotations, record_fields=True, progress=True)
    err = capsys.readouterr().err
    assert "continuum pushover" in err and "5/5" in err and "%|" in err
    assert re.search(r"\[\d\d:\d\d<\d\d:\d\d, ", err)  # elapsed < ETA
    fig = path.plot()
    assert np.array_equal(fig.axes[0].lines[0].get_xdata(), path.theta)
    assert np.array_equal(fig.axes[0].lines[0].get_ydata(), path.M)
    assert f"{np.max(np.abs(path.M)):.4g} kN·m/m" in path._repr_html_()
    picture = path.render(model, -1)
    drawn = [line.get_ydata() for ax in picture.axes for line in ax.lines]
    assert any(np.array_equal(y, path.pressure[-1]) for y in drawn)
    assert "step 5 of 5" in picture.get_suptitle()


# ---------------------------------------------------------------------------------------------
# Progress
# ---------------------------------------------------------------------------------------------


def test_progress_where_asked_and_nowhere_else(coarse, capsys):
    # Reference: the callable's calls (one per step, k = 0…n−1 of n); pytest's captured stderr
    # is not a terminal, so the default shows no bar there
    model, _ = coarse
    assert not watched()
    calls = []
    rotation_pushover(model, 171.39, [0.001, 0.002, 0.003],
                      progress=lambda k, n, state: calls.append((k, n)))
    assert calls == [(0, 3), (1, 3), (2, 3)]
    rotation_pushover(model, 171.39, [0.001, 0.002])
    rotation_pushover(model, 171.39, [0.001, 0.002], progress=False)
    assert capsys.readouterr().err == ""
    with pytest.raises(InputError, match="progress = 'yes'"):
        with steps_progress("yes", "x"):
            pass


def test_a_terminal_shows_a_bar_unless_the_command_line_logs(monkeypatch):
    # Reference: upliftlab.progress's rule: a terminal in the main process shows a bar, unless
    # upliftlab.log.configure (what the command line calls) has set up its log lines
    import io
    import sys

    from upliftlab.log import _Handler, configure, logger

    class Terminal(io.StringIO):
        def isatty(self):
            return True

    monkeypatch.setattr(sys, "stderr", Terminal())
    root = logger()
    saved = (list(root.handlers), root.level, root.propagate)
    for handler in [h for h in root.handlers if isinstance(h, _Handler)]:
        root.removeHandler(handler)
    try:
        assert watched()
        configure(0)
        assert not watched()
    finally:
        root.handlers[:] = saved[0]
        root.setLevel(saved[1])
        root.propagate = saved[2]


def test_a_sweep_reports_by_lines_or_a_bar():
    from upliftlab.comparisons.framework.sweep import StderrProgress
    from upliftlab.comparisons.framework.sweep_bar import BarProgress, sweep_report

    assert isinstance(sweep_report(None, StderrProgress), StderrProgress)  # not in a kernel
    assert isinstance(sweep_report(True, StderrProgress), BarProgress)
    assert sweep_report(False, StderrProgress) is None
    mine = print
    assert sweep_report(mine, StderrProgress) is mine


def test_a_study_result_shows_its_key_numbers():
    # Reference: the record's own numbers (4 significant digits) and digest (12 hex digits)
    from upliftlab.comparisons.framework.study import StudyResult

    result = StudyResult("probe", True, Path("out"), (Path("out/a.nc"),), "",
                         {"points": 3, "largest_error": 0.0123456, "per_case": {"a": 1}},
                         {"source_sha256": "0123456789abcdef" * 4}, 2.04)
    html = result._repr_html_()
    assert "probe (fast)" in html and "out (1 files)" in html and "2.0 s" in html
    assert "<td style='text-align:left'>0.01235</td>" in html and ">3</td>" in html
    assert "per_case" not in html and "code 0123456789ab" in html
