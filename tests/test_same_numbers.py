"""``benchmarks/same_numbers.py`` tells a changed number from an added one.

Reference: folders written here by hand with xarray and json, whose differences are known by
construction (one value changed by one ulp, one variable and one attribute added)."""

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import xarray as xr

SCRIPT = Path(__file__).resolve().parents[1] / "benchmarks" / "same_numbers.py"


def _folder(root: Path, value: float, extra: bool) -> Path:
    root.mkdir()
    ds = xr.Dataset({"theta": ("x", np.array([1.0, value]), {"units": "rad"})})
    summary = {"numbers": {"peak": value}}
    if extra:
        ds["uplift"] = ("x", np.array([0.5, 0.25]))
        ds["theta"].attrs["long_name"] = "rotation"
        summary["numbers"]["share"] = 0.126
    ds.to_netcdf(root / "map.nc", engine="h5netcdf")
    (root / "summary.json").write_text(json.dumps(summary))
    return root


def _run(*args) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, str(SCRIPT), *map(str, args)], capture_output=True,
                          text=True)


def test_additions_pass_only_when_allowed(tmp_path):
    before = _folder(tmp_path / "before", 2.0, extra=False)
    after = _folder(tmp_path / "after", 2.0, extra=True)
    strict = _run(before, after)
    assert strict.returncode == 1 and len(strict.stdout.splitlines()) == 3, strict.stdout
    added = _run(before, after, "--added-ok")
    assert added.returncode == 0, added.stdout + added.stderr
    assert "3 additions" in added.stderr


def test_a_changed_value_fails_even_with_additions_allowed(tmp_path):
    before = _folder(tmp_path / "before", 2.0, extra=False)
    after = _folder(tmp_path / "after", np.nextafter(2.0, 3.0), extra=True)
    result = _run(before, after, "--added-ok")
    assert result.returncode == 1
    assert "map.nc:theta: 1 values differ" in result.stdout
    assert "summary.json.numbers.peak" in result.stdout


def test_values_only_ignores_attributes_and_scene_named_files_are_compared(tmp_path):
    """A file named for a scene ("wall_elcentro") holds numbers: it used to be skipped for its
    "wall"; an attribute alone differs only when attributes are compared."""
    before = _folder(tmp_path / "before", 2.0, extra=False)
    after = _folder(tmp_path / "after", 2.0, extra=False)
    with xr.open_dataset(after / "map.nc", engine="h5netcdf") as ds:
        changed = ds.load()
    changed["theta"].attrs["units"] = "degree"
    (after / "map.nc").unlink()
    changed.to_netcdf(after / "map.nc", engine="h5netcdf")
    assert _run(before, after).returncode == 1
    assert _run(before, after, "--values-only").returncode == 0
    for root, value in ((before, 1.0), (after, 1.5)):
        xr.Dataset({"peak_u": ("x", [value])}).to_netcdf(root / "wall_elcentro.nc",
                                                          engine="h5netcdf")
    result = _run(before, after, "--values-only")
    assert result.returncode == 1 and "wall_elcentro.nc:peak_u" in result.stdout
