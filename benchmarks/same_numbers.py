"""Are two output folders the same numbers? Every JSON leaf, CSV cell and NetCDF array of one
folder against the other's, timings and provenance aside.

    python benchmarks/same_numbers.py BEFORE AFTER [--rtol 0]

A change that is meant to leave every number as it was (a restructuring, a faster kernel) is
checked by running the same command before and after it into two folders and comparing them
here. Files are matched by their path relative to the folder; a file only one side has is
reported (a renamed file must be named in ``--rename OLD=NEW``); with ``--added-ok`` what only
the after side has (a file, a variable, a key, an attribute) is listed apart and does not count
(a restructuring that adds labels, keeping every number it had). JSON leaves and CSV cells
compare as numbers where both parse as numbers (equal to ``--rtol``, default 0: bit for bit),
as text otherwise; NetCDF files compare variable by variable (values, dims) and their
non-provenance attributes. What is left out: keys and attributes that name a time or a
duration or derives from one (``*time*``, ``*seconds*``, ``elapsed*``, ``*_utc``,
``computed*``, speeds, the cheapest run, the Pareto front: what is fastest changes with the
machine's load), provenance
(``provenance*``, ``source_sha256``, versions, ``platform``, ``python``), machine paths
(values that are absolute paths), and figures (PNG, SVG, GIF, PDF, HTML: looked at, not
compared). NetCDF files are read as upliftlab reads them back (its CF encodings undone);
``--values-only`` leaves their attributes out. Exit 0 when the same, 1 with one line per
difference (the first 200) otherwise.
"""

from __future__ import annotations

import argparse
import csv
import json
import math
import re
import sys
from pathlib import Path

IGNORED_KEY = re.compile(r"(time|seconds|elapsed|_utc$|^computed|provenance|sha256|version|"
                         r"platform|^python$|^created|wall|runtime|^host|^numpy$|^scipy$|"
                         r"^numba$|^scikit_fem$|^xarray$|^h5py$|session|measured_utc|"
                         r"^directory$|^files$|^store$|^html$|^path$|^key$|speed|_s$|_ms$|"
                         r"faster|ratio$|cheapest|pareto|repeats|^conclusion$)", re.I)
#: Files that hold timings alone, or what timings pick (the Pareto front); a file named for a
#: scene ("wall_elcentro") is compared.
TIMING_FILE = re.compile(r"^(timings?|runtimes?|speed|elapsed|pareto)$", re.I)
SKIPPED_SUFFIX = {".png", ".svg", ".gif", ".pdf", ".html", ".xdmf", ".h5", ".lock", ".part",
                  ".npz", ".gz"}


def _number(text):
    try:
        return float(text)
    except (TypeError, ValueError):
        return None


def _same_value(a, b, rtol: float) -> bool:
    x, y = _number(a), _number(b)
    if x is None or y is None or isinstance(a, bool) or isinstance(b, bool):
        return a == b
    if math.isnan(x) and math.isnan(y):
        return True
    return x == y or abs(x - y) <= rtol * max(abs(x), abs(y))


def _json_diffs(a, b, where: str, rtol: float, out: list) -> None:
    if isinstance(a, dict) and isinstance(b, dict):
        for key in sorted(set(a) | set(b)):
            if IGNORED_KEY.search(str(key)):
                continue
            if key not in a or key not in b:
                out.append(f"{where}.{key}: only in {'after' if key in b else 'before'}")
                continue
            _json_diffs(a[key], b[key], f"{where}.{key}", rtol, out)
    elif isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            out.append(f"{where}: length {len(a)} → {len(b)}")
            return
        for i, (x, y) in enumerate(zip(a, b)):
            _json_diffs(x, y, f"{where}[{i}]", rtol, out)
    elif isinstance(a, str) and isinstance(b, str) and (a.startswith("/") or b.startswith("/")):
        return  # a machine path
    elif not _same_value(a, b, rtol):
        out.append(f"{where}: {a!r} → {b!r}")


def _csv_diffs(a: Path, b: Path, where: str, rtol: float, out: list) -> None:
    rows_a = list(csv.reader(x for x in a.read_text().splitlines() if not x.startswith("#")))
    rows_b = list(csv.reader(x for x in b.read_text().splitlines() if not x.startswith("#")))
    if len(rows_a) != len(rows_b):
        out.append(f"{where}: {len(rows_a)} rows → {len(rows_b)}")
        return
    header = rows_a[0] if rows_a else []
    keep = [i for i, name in enumerate(header) if not IGNORED_KEY.search(name)]
    for r, (x, y) in enumerate(zip(rows_a, rows_b)):
        if len(x) != len(y):
            out.append(f"{where} row {r}: {len(x)} cells → {len(y)}")
            continue
        for i in keep if r else range(len(x)):
            if i < len(x) and not _same_value(x[i], y[i], rtol):
                out.append(f"{where} row {r} {header[i] if i < len(header) else i}: "
                           f"{x[i]!r} → {y[i]!r}")


def _open(path: Path):
    """A NetCDF file as upliftlab reads it back (:func:`upliftlab.results.read_dataset`: CF's
    encodings of time and labels undone), so a change of encoding alone is not a change of
    numbers; plain xarray where upliftlab is not importable."""
    try:
        from upliftlab.results import read_dataset
    except ImportError:
        import xarray as xr
        return xr.load_dataset(path, engine="h5netcdf", decode_times=False)
    return read_dataset(path)


def _netcdf_diffs(a: Path, b: Path, where: str, rtol: float, out: list,
                  attributes: bool = True) -> None:
    import numpy as np

    with _open(a) as x, _open(b) as y:
        names = sorted(set(x.variables) | set(y.variables))
        for name in names:
            if IGNORED_KEY.search(name) and name != "time":
                continue
            if name not in x.variables or name not in y.variables:
                side = "after" if name in y.variables else "before"
                out.append(f"{where}:{name}: only in {side}")
                continue
            u, v = x[name], y[name]
            if u.dims != v.dims or u.shape != v.shape:
                out.append(f"{where}:{name}: {u.dims}{u.shape} → {v.dims}{v.shape}")
                continue
            p, q = np.asarray(u.values), np.asarray(v.values)
            if p.dtype.kind in "fc" or q.dtype.kind in "fc":
                p, q = p.astype(float), q.astype(float)
                with np.errstate(invalid="ignore"):  # inf − inf where both are inf: equal
                    bad = ~((p == q) | (np.isnan(p) & np.isnan(q))
                            | (np.abs(p - q) <= rtol * np.maximum(np.abs(p), np.abs(q))))
                if bad.any():
                    k = int(np.flatnonzero(bad.ravel())[0])
                    out.append(f"{where}:{name}: {bad.sum()} values differ, first "
                               f"{p.ravel()[k]!r} → {q.ravel()[k]!r}")
            elif not np.array_equal(p, q):
                out.append(f"{where}:{name}: values differ")
            for key in sorted(set(u.attrs) | set(v.attrs)) if attributes else ():
                if not IGNORED_KEY.search(key) and str(u.attrs.get(key)) != str(v.attrs.get(key)):
                    out.append(f"{where}:{name}@{key}: {u.attrs.get(key)!r} → "
                               f"{v.attrs.get(key)!r}")
        for key in sorted(set(x.attrs) | set(y.attrs)) if attributes else ():
            if not IGNORED_KEY.search(key) and str(x.attrs.get(key)) != str(y.attrs.get(key)):
                out.append(f"{where}@{key}: {x.attrs.get(key)!r} → {y.attrs.get(key)!r}")


def differences(before: Path, after: Path, rtol: float = 0.0,
                rename: dict[str, str] | None = None, attributes: bool = True) -> list[str]:
    """Every difference between the two folders (module docstring), one line each."""
    rename = rename or {}

    def files(root: Path) -> dict[str, Path]:
        return {str(p.relative_to(root)): p for p in root.rglob("*")
                if p.is_file() and p.suffix.lower() not in SKIPPED_SUFFIX
                and "store" not in p.relative_to(root).parts
                and not TIMING_FILE.search(p.stem)
                and not p.name.startswith(".") and p.name != "upliftlab-run.json"}

    a, b = files(before), files(after)
    a = {rename.get(k, k): v for k, v in a.items()}
    out = [f"{k}: only in {'after' if k in b else 'before'}" for k in sorted(set(a) ^ set(b))]
    for name in sorted(set(a) & set(b)):
        suffix = Path(name).suffix.lower()
        if suffix == ".json":
            _json_diffs(json.loads(a[name].read_text()), json.loads(b[name].read_text()), name,
                        rtol, out)
        elif suffix == ".csv":
            _csv_diffs(a[name], b[name], name, rtol, out)
        elif suffix == ".nc":
            _netcdf_diffs(a[name], b[name], name, rtol, out, attributes)
        elif a[name].read_bytes() != b[name].read_bytes() and suffix not in (".md", ".txt"):
            out.append(f"{name}: bytes differ")
    return out


def is_addition(line: str) -> bool:
    """Whether a difference line says only that the after side has something more."""
    return line.endswith(": only in after") or re.search(r"@[^:]+: None → ", line) is not None


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("before", type=Path)
    parser.add_argument("after", type=Path)
    parser.add_argument("--rtol", type=float, default=0.0)
    parser.add_argument("--rename", action="append", default=[], metavar="OLD=NEW")
    parser.add_argument("--values-only", action="store_true",
                        help="compare the NetCDF files' values, not their attributes")
    parser.add_argument("--added-ok", action="store_true",
                        help="what only the after side has is listed apart, not counted")
    args = parser.parse_args(argv)
    rename = dict(item.split("=", 1) for item in args.rename)
    found = differences(args.before, args.after, args.rtol, rename, not args.values_only)
    if args.added_ok:
        added = [line for line in found if is_addition(line)]
        found = [line for line in found if not is_addition(line)]
        print(f"{len(added)} additions (only in after), not counted", file=sys.stderr)
    for line in found[:200]:
        print(line)
    print(f"{len(found)} differences" if found else "the same numbers", file=sys.stderr)
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
