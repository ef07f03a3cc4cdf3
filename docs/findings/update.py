"""Write the findings pages' data, ``docs/findings/data/<study>.json``, from study outputs.

Run by hand after a study's results changed (like the benchmarks' ``--write``), then build the
docs: every ``{finding}`` reference is read again, and one that names a key the new data lack
fails the strict build. Usage::

    python docs/findings/update.py FOLDER [FOLDER ...] [--data DIR] [--check]

Each FOLDER is a study's output folder (``upliftlab study NAME --out FOLDER``: its name is
``NAME`` or ``NAME-fast``, or its summary says which study wrote it), or a folder holding such
folders (``upliftlab report --out DIR`` writes them under ``DIR/studies``). ``--check`` writes
nothing and exits 1 if a data file would change.

The data file keeps what the study wrote, whatever its format, so that a page can cite any
number of it by a key path:

- ``summary``: the study's ``summary.json`` as it is (its ``numbers``, ``conclusions``, ...);
  besides it, ``summary.files.<stem>`` for each ``*.nc`` (its global attributes and its
  variables of at most 64 values, as lists) and ``summary.figures.<stem>`` for each
  ``*.figure.json`` (the title, what it shows, its computed conclusion);
- ``source``, ``fast``, ``created_utc``, ``upliftlab_version``, ``source_sha256``: where it
  came from (the summary's provenance, or the result's attributes).

Standard library, numpy and xarray only (xarray for the NetCDF files).
"""

from __future__ import annotations

import argparse
import json
import math
import sys
from pathlib import Path

DATA = Path(__file__).resolve().parent / "data"
#: A NetCDF variable with more values than this is left out (a page cites values, not fields).
MAX_VALUES = 64


def plain(value):
    """``value`` as JSON: numpy scalars and arrays to Python numbers and lists, NaN to None,
    an absolute path to its last part (no machine's folders in the committed data)."""
    if hasattr(value, "tolist"):
        value = value.tolist()
    if isinstance(value, dict):
        return {str(k): plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [plain(v) for v in value]
    if isinstance(value, float) and not math.isfinite(value):
        return None if math.isnan(value) else ("inf" if value > 0 else "-inf")
    if isinstance(value, bytes):
        value = value.decode("utf-8", "replace")
    if isinstance(value, str) and value.startswith("/") and " " not in value:
        return Path(value).name  # a path of the machine that ran it: its name only
    return value


def netcdf_numbers(path: Path) -> dict:
    """The attributes and the small variables of a NetCDF file."""
    from upliftlab.results import read_dataset

    ds = read_dataset(path)  # as written: seconds, and labels as indexes (upliftlab.cf)
    out = {"attrs": {k: plain(v) for k, v in ds.attrs.items()
                     if not (isinstance(v, str) and len(v) > 500)}}
    for name, var in {**ds.coords, **ds.data_vars}.items():
        if var.size <= MAX_VALUES and var.dtype.kind in "biufUSO":
            out[str(name)] = plain(var.values)
    return out


def study_name(folder: Path, summary: dict) -> str:
    """Which study wrote ``folder``: its summary's provenance, else the folder's name; with
    ``_<reference>`` after it when the study ran on a continuum reference other than the box
    (``winkler_map --reference half_plane`` -> ``winkler_map_half_plane``), so that the map on
    each reference keeps its own data file."""
    provenance = summary.get("provenance", {})
    study = provenance.get("study") or folder.name.removesuffix("-fast")
    reference = provenance.get("options", {}).get("reference", "box")
    return study if reference in ("box", None) else f"{study}_{reference}"


def source_command(summary: dict, study: str, fast: bool) -> str:
    """The command that wrote the data, as far as the summary tells it."""
    provenance = summary.get("provenance", {})
    name = provenance.get("study") or study
    reference = provenance.get("options", {}).get("reference", "box")
    return (f"upliftlab study {name}" + (" --fast" if fast else "")
            + (f" --reference {reference}" if reference not in ("box", None) else ""))


def collect(folder: Path) -> tuple[str, dict]:
    """(study, data) of one study's output folder."""
    path = folder / "summary.json"
    summary = json.loads(path.read_text(encoding="utf-8")) if path.is_file() else {}
    provenance = summary.get("provenance", {})
    files = {p.stem: netcdf_numbers(p) for p in sorted(folder.glob("*.nc"))}
    figures = {p.name.removesuffix(".figure.json"): json.loads(p.read_text(encoding="utf-8"))
               for p in sorted(folder.glob("*.figure.json"))}
    if not summary and not files:
        raise SystemExit(f"update.py: {folder} holds no summary.json and no *.nc: not a "
                         "study's output folder")
    attrs = next(iter(files.values()), {}).get("attrs", {})
    study = study_name(folder, summary)
    fast = provenance.get("fast", folder.name.endswith("-fast"))
    data = {
        "study": study,
        "source": source_command(summary, study, fast),
        "fast": bool(fast),
        "created_utc": provenance.get("created_utc", attrs.get("created_utc")),
        "upliftlab_version": provenance.get("upliftlab_version",
                                            attrs.get("upliftlab_version")),
        "source_sha256": provenance.get("source_sha256", attrs.get("source_sha256")),
        "summary": {**plain(summary), **({"files": files} if files else {}),
                    **({"figures": figures} if figures else {})},
    }
    return study, data


def study_folders(paths: list[Path]) -> list[Path]:
    """The study folders named, or found one level (or ``studies/``) below a named folder."""
    found = []
    for path in paths:
        if (path / "summary.json").is_file() or any(path.glob("*.nc")):
            found.append(path)
            continue
        below = path / "studies" if (path / "studies").is_dir() else path
        found += sorted(p for p in below.iterdir() if p.is_dir() and
                        ((p / "summary.json").is_file() or any(p.glob("*.nc"))))
    return found


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("folders", nargs="+", type=Path)
    parser.add_argument("--data", type=Path, default=DATA, help="where the data files go")
    parser.add_argument("--check", action="store_true",
                        help="write nothing; exit 1 if a data file would change")
    args = parser.parse_args(argv)
    changed = []
    for folder in study_folders(args.folders):
        study, data = collect(folder)
        target = args.data / f"{study}.json"
        text = json.dumps(data, indent=1, sort_keys=True, ensure_ascii=False) + "\n"
        old = target.read_text(encoding="utf-8") if target.is_file() else None
        if old != text:
            changed.append(target)
            if not args.check:
                target.parent.mkdir(parents=True, exist_ok=True)
                target.write_text(text, encoding="utf-8")
        print(f"{'would write' if args.check else 'wrote'} {target} from {folder}"
              if old != text else f"unchanged {target}", file=sys.stderr)
    return 1 if args.check and changed else 0


if __name__ == "__main__":
    sys.exit(main())
