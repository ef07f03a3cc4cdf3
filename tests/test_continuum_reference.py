"""benchmarks/continuum_reference.py: its Richardson estimates and table on synthetic runs whose
error is a closed form, continuum_elcentro's choice of reference, and the quick run end to end.

The synthetic runs follow f(h) = f₀ + c h^p exactly (h = 1/n, n elements across): the peak
|θ|, the peak edge uplift, the residual settlement and the two histories' differences of a run
on n across are then closed forms, and Richardson extrapolation from three meshes recovers p and
f₀ exactly (to rounding), so the estimated error of each mesh must equal c h^p over f₀.
"""

from __future__ import annotations

import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

# benchmarks/ is on the tests' path (pyproject.toml: pythonpath)
import bench_output
import continuum_elcentro as ec
import continuum_reference as cr

BENCH = Path(__file__).resolve().parents[1] / "benchmarks"


#: The closed form's limits f₀ (peak θ [rad], peak edge uplift [m], residual settlement [m])
#: and coefficients c of h^p, one order for all.
LIMITS, COEFFS = (2e-3, 5e-3, 4e-2), (-3e-3, 8e-3, -0.1)
T = np.linspace(0.0, np.pi, 2001)  # holds π/2 (the peak of sin) and ends at π


def synthetic(n: float | None, p: float, sign: float = 1.0) -> dict:
    """A run on ``n`` across (None: the limit h → 0) whose quantities are f₀ + c h^p (``sign``
    flips c on this mesh: an oscillating sequence)."""
    h = 0.0 if n is None else 1.0 / n
    theta0, edge0, settle0 = (f + sign * c * h ** p for f, c in zip(LIMITS, COEFFS))
    return {"time": T, "theta": theta0 * np.sin(T), "edge": edge0 * np.abs(np.sin(T)),
            "v": -settle0 * (1.0 - np.cos(T)) / 2.0, "dt": 1e-4 / (n or 64), "steps": T.size,
            "wall": 1.0}


def rows_of(p: float, signs=(1.0, 1.0, 1.0)) -> dict:
    rows = {f"explicit-{n}": synthetic(n, p, s) for n, s in zip((8, 16, 32), signs)}
    rows["explicit-32-half"] = synthetic(None, p)
    rows["implicit-16"] = synthetic(16, p)
    return rows


def exact(n: int, p: float) -> list[float]:
    """The closed-form error c h^p / f₀ of each quantity of ``ec.ERRORS`` on ``n`` across."""
    peaks = [c * (1.0 / n) ** p / f for f, c in zip(LIMITS, COEFFS)]
    return peaks + [abs(peaks[0]), abs(peaks[2])]


@pytest.mark.parametrize("p", [1.0, 1.7, 2.0])
def test_richardson_recovers_a_closed_form_order(p):
    """f = f₀ + c h^p: the observed order is p and the estimates of 16 and 32 across are
    |c| h^p / f₀ (closed form), to 1e-9 relative."""
    rows = rows_of(p)
    found = cr.estimates(rows, ("explicit-8", "explicit-16", "explicit-32"), (8, 16, 32),
                         rows["explicit-32-half"])
    for name, e16, e32 in zip(ec.ERRORS, exact(16, p), exact(32, p)):
        assert found[name]["order"] == pytest.approx(p, rel=1e-9), name
        assert found[name]["flag"] == "richardson"
        assert found[name]["middle"] == pytest.approx(abs(e16), rel=1e-9), name
        assert found[name]["finest"] == pytest.approx(abs(e32), rel=1e-9), name


def test_the_table_states_measured_and_estimated_errors():
    """The table's cells (read back as Markdown): the measured error of 16 across against the
    limit is c h^p / f₀ signed, its estimate the same unsigned with p; the implicit row is
    measured against the reference too (closed form, p = 2)."""
    p = 2.0
    rows = rows_of(p)
    found = bench_output.markdown_tables("# t\n\n" + cr.table(rows, cr.RUNS))["t"]

    def row(start):
        return next(r for r in found if r["what"].startswith(start))

    measured, estimated = row("explicit-16: its own error"), row("explicit-16: Richardson")
    implicit, time_row = row("implicit-16"), row("explicit-32: time error")
    for name, e in zip(ec.ERRORS, exact(16, p)):
        assert float(bench_output.number(measured[name])) == pytest.approx(100 * e, abs=6e-4)
        assert float(bench_output.number(implicit[name])) == pytest.approx(100 * e, abs=6e-4)
        assert bench_output.number(estimated[name].lstrip("±")) == \
            pytest.approx(100 * abs(e), abs=6e-4)
        assert "p = 2.00" in estimated[name]
    assert bench_output.number(time_row["peak theta"]) == pytest.approx(100 * exact(32, p)[0],
                                                                        abs=6e-4)


def test_an_oscillating_sequence_is_a_flagged_bound():
    """Signs of c alternating between meshes: no order holds for the signed peaks, and the
    estimate of 16 across is the plain |f₃₂ − f₁₆| over f₀, flagged (closed form)."""
    p = 2.0
    rows = rows_of(p, signs=(1.0, -1.0, 1.0))
    found = cr.estimates(rows, ("explicit-8", "explicit-16", "explicit-32"), (8, 16, 32),
                         rows["explicit-32-half"])
    for k, name in enumerate(ec.ERRORS[:3]):
        bound = abs(COEFFS[k]) * (16.0 ** -p + 32.0 ** -p) / LIMITS[k]
        assert math.isnan(found[name]["order"])
        assert found[name]["flag"] == "order does not hold"
        assert found[name]["middle"] == pytest.approx(bound, rel=1e-9)
        assert found[name]["finest"] == pytest.approx(bound, rel=1e-9)
    cell = cr.table(rows, cr.RUNS)
    assert "≤" in cell and "bound: order does not hold" in cell


def test_the_roles_of_the_runs():
    """The full study's reference is what continuum_elcentro reads as the converged one."""
    full, quick = cr.roles(cr.RUNS), cr.roles(cr.QUICK_RUNS)
    assert full["reference"] == ec.CONVERGED == cr.REFERENCE
    assert full["meshes"] == ("explicit-8", "explicit-16", "explicit-32")
    assert full["across"] == (8, 16, 32) and full["implicit"] == "implicit-16"
    assert quick["across"] == (2, 4, 8)


def test_elcentro_compares_with_the_converged_reference_where_it_covers_the_row(tmp_path):
    """A row equal to the kept reference has zero error against it; a row shorter than the
    reference falls back to the implicit route; the table's text names the reference used,
    and says so when none is kept."""
    reference = synthetic(None, 2.0)
    np.savez(tmp_path / f"{ec.CONVERGED}.npz", **reference)
    converged = ec.converged_reference(tmp_path)
    assert converged is not None and str(tmp_path) in ec.reference_note(converged, tmp_path)
    base = {"n": 16, "duration": float(T[-1]), "threads": 1, "step": 1.0, "wall": 1.0,
            "dofs": 1, "steps": T.size, "dt": 1e-4, "energy": 0.0}
    same = {**base, **synthetic(None, 2.0), "route": "explicit", "rtol": 1e-5}
    implicit = {**base, **synthetic(16, 2.0), "route": "implicit", "rtol": 1e-6}
    short = {**same, "time": T[:1000], "theta": same["theta"][:1000],
             "v": same["v"][:1000], "edge": same["edge"][:1000]}
    done = ec.finish([implicit, same, short], converged)
    assert done[1]["reference"].startswith("converged")
    assert all(abs(v) < 1e-12 for v in done[1]["errors"].values())
    assert done[0]["errors"]["peak theta"] == pytest.approx(exact(16, 2.0)[0], rel=1e-9)
    assert done[2]["reference"] == "implicit rtol 1e-6, 16 across"
    assert ec.converged_reference(tmp_path / "absent") is None
    assert "No converged reference" in ec.reference_note(None, tmp_path / "absent")
    assert ec.finish([implicit, same])[1]["reference"] == "implicit rtol 1e-6, 16 across"


def test_quick_run_end_to_end(tmp_path, elcentro):
    """``--quick`` (2 s on 2, 4 and 8 across, about 10 s): exit 0, every run kept, the table
    complete; its time error on 8 across (step halved) is below 0.1 % in peak θ (the full
    study's explicit step halving on 8 across moved it by 0.004 %,
    benchmarks/CONTINUUM_CONVERGENCE.md)."""
    out = tmp_path / "reference"
    env = {**os.environ, "OMP_NUM_THREADS": "1"}
    result = subprocess.run([sys.executable, str(BENCH / "continuum_reference.py"), "--quick",
                             "--out", str(out)], cwd=tmp_path, env=env, capture_output=True,
                            text=True, timeout=300)
    assert result.returncode == 0, result.stderr[-3000:]
    assert "estimated wall time" in result.stderr
    assert len(list((out / "rows-quick").glob("*.npz"))) == len(cr.QUICK_RUNS)
    text = (out / cr.FILE).read_text(encoding="utf-8")
    assert "Incomplete run" not in text
    found = bench_output.markdown_tables(text)
    table = found["Continuum dynamics: a reference converged in time and mesh"]
    time_row = next(r for r in table if r["what"].startswith("explicit-8: time error"))
    assert abs(bench_output.number(time_row["peak theta"])) < 0.1
    assert len(found["Runs"]) == len(cr.QUICK_RUNS)
