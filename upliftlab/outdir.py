"""Output folders: checked before the work, claimed while it runs, marked complete at its end.

A command that writes results first calls :func:`claim`, before any computation:

* the path is refused if it is empty, is a file, lies under a file, or cannot be written
  (a probe file is created and removed; folders created for the probe are removed again if
  the command then fails, so a refused command leaves nothing behind);
* a folder another live process is writing to (its lock file names a running process) is
  refused, whatever it holds;
* a folder holding another run's results — its completion marker records different settings —
  is refused unless ``force`` (two runs into one folder must not silently mix);
* the folder is locked (:data:`LOCK`, holding this process's id) until the command ends, and
  is the one place the command writes to until then (:func:`upliftlab.paths.check_target`).
  Nothing in it is removed but upliftlab's own files: the temporary files of a killed writer
  are removed beside the file that is written again (:mod:`upliftlab.paths`), the user's own
  files never.

Just before it writes its first file the command calls :meth:`Claim.start_writing`, which
removes the old completion marker; when every file is written it calls
:meth:`Claim.complete`, which writes the completion marker :data:`MARKER` last. A folder whose
marker is missing holds an interrupted or failed run. The marker lists the files and the
settings (:func:`settings_digest`).
"""

from __future__ import annotations

import contextlib
import hashlib
import json
import os
import re
import tempfile
from dataclasses import dataclass, field
from pathlib import Path

from .checks import InputError
from .paths import check_folder_name, disk_full, pop_root, push_root

__all__ = ["MARKER", "LOCK", "Claim", "claim", "probe_folder", "settings_digest", "read_marker"]

MARKER = "upliftlab-run.json"
_CONTROL = re.compile(r"[\x00-\x1f\x7f]")
LOCK = ".upliftlab.lock"


def settings_digest(settings: dict) -> str:
    """SHA-256 of a run's settings (JSON, sorted keys)."""
    return hashlib.sha256(json.dumps(settings, sort_keys=True, default=str).encode()).hexdigest()


def read_marker(folder: str | os.PathLike) -> dict | None:
    """The completion marker of ``folder`` (None if it has none, or an unreadable one)."""
    try:
        return json.loads((Path(folder) / MARKER).read_text())
    except (OSError, ValueError):
        return None


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True


@dataclass
class Claim:
    """A claimed output folder (see :func:`claim`). Use as a context manager around the work:
    the lock is released when the block ends; after an exception the folders the claim created
    are removed too if they are still empty."""

    path: Path
    settings: dict
    created: list[Path] = field(default_factory=list)
    locked: bool = False
    root: Path | None = None

    def __enter__(self) -> Claim:
        return self

    def __exit__(self, kind, value, tb) -> None:
        if kind is not None:
            self.abandon()
        else:
            self.release()

    def _lock(self, option: str) -> None:
        lock = self.path / LOCK
        try:
            fd = os.open(lock, os.O_CREAT | os.O_EXCL | os.O_WRONLY, 0o644)
        except FileExistsError:
            raise InputError(f"{option} = {str(self.path)!r}: another upliftlab run is writing "
                             f"to it ({_lock_owner(lock)})") from None
        try:
            with os.fdopen(fd, "w") as fh:
                fh.write(str(os.getpid()))
        except OSError:  # no room even for a process id: leave no empty lock behind
            with contextlib.suppress(OSError):
                lock.unlink()
            raise
        self.locked = True
        self.root = push_root(self.path)

    def start_writing(self) -> None:
        """The first file is about to be written: the folder no longer holds a complete run."""
        with contextlib.suppress(FileNotFoundError):
            (self.path / MARKER).unlink()

    def complete(self, files) -> Path:
        """Write the completion marker (last) and release the folder."""
        from .results import write_text

        names = sorted({str(Path(f).resolve().relative_to(self.path.resolve()))
                        if Path(f).resolve().is_relative_to(self.path.resolve()) else str(f)
                        for f in files})
        record = {"complete": True, "settings": self.settings,
                  "settings_digest": settings_digest(self.settings), "files": names}
        path = write_text(self.path / MARKER, json.dumps(record, indent=2, default=str) + "\n")
        self.release()
        return path

    def release(self) -> None:
        if self.locked:
            with contextlib.suppress(FileNotFoundError):
                (self.path / LOCK).unlink()
            self.locked = False
            pop_root(self.root)

    def abandon(self) -> None:
        """Give the folder up after a failure: unlock it and remove the folders this claim
        created, if nothing was written in them."""
        self.release()
        for folder in reversed(self.created):
            with contextlib.suppress(OSError):
                folder.rmdir()  # only if empty


def _lock_owner(lock: Path) -> str:
    try:
        pid = int(lock.read_text().strip())
    except (OSError, ValueError):
        return f"lock file {lock.name}"
    return f"process {pid}"


def _take_stale_lock(lock: Path) -> None:
    """Remove a lock left by a process that no longer runs."""
    try:
        pid = int(lock.read_text().strip())
    except (OSError, ValueError):
        return
    if not _alive(pid):
        with contextlib.suppress(FileNotFoundError):
            lock.unlink()


def claim(out: str | os.PathLike | None, default: str | os.PathLike, *, settings: dict,
          force: bool = False, option: str = "--out") -> Claim:
    """Check and claim the output folder ``out`` (``default`` when None) for a run with
    ``settings`` (module docstring). Nothing is computed before this returns."""
    if out is not None and (not isinstance(out, (str, os.PathLike)) or not str(out).strip()):
        raise InputError(f"{option} = {out!r}: expected a folder path")
    path = check_folder_name(out if out is not None else default, option)
    try:
        return _claim(path, settings, force, option)
    except OSError as exc:  # a name too long, a folder not reachable: one line, not a trace
        if disk_full(exc):  # not bad input: the command's own exit (3, no space left)
            raise
        raise InputError(f"{option} = {str(path)[:80]!r}: cannot be used as a folder "
                         f"({exc.strerror or exc})") from None


def _refuse_a_file(path: Path, option: str) -> None:
    """An :class:`InputError` naming ``option`` if ``path``, or the nearest of its folders that
    exists, is a file (nothing can be made in it)."""
    for parent in [path, *path.parents]:
        if parent.exists():
            if not parent.is_dir():
                where = "is" if parent == path else f"lies under {str(parent)!r}, which is"
                raise InputError(f"{option} = {str(path)!r}: {where} a file, not a folder")
            break


def probe_folder(folder: str | os.PathLike, option: str) -> Path:
    """``folder``, checked before any work to be a folder this process can write to: named as
    one (:func:`~upliftlab.paths.check_folder_name`), not a file nor under one, and one where a
    file can be made (a probe file is made and removed, and the folders made for it removed
    again: nothing is left behind). Else an :class:`InputError` naming ``option`` and the
    value. Unlike :func:`claim` it locks nothing (a study's store is shared on purpose)."""
    path = check_folder_name(folder, option)
    _refuse_a_file(path, option)
    created = [p for p in reversed([path, *path.parents]) if not p.exists()]
    try:
        path.mkdir(parents=True, exist_ok=True)
        fd, probe = tempfile.mkstemp(prefix=".probe.", dir=path)
        os.close(fd)
        os.unlink(probe)
    except OSError as exc:
        if disk_full(exc):  # not bad input: the command's own exit (3, no space left)
            raise
        raise InputError(f"{option} = {str(path)!r}: cannot write there "
                         f"({exc.strerror or exc})") from None
    finally:
        for made in reversed(created):
            with contextlib.suppress(OSError):
                made.rmdir()
    return path


def _claim(path: Path, settings: dict, force: bool, option: str) -> Claim:
    """:func:`claim` of the folder ``path`` (its checks, in order)."""
    if _CONTROL.search(str(path)):
        raise InputError(f"{option} = {str(path)!r}: a folder name with a control character "
                         "(a line break, a tab, …) is refused")
    _refuse_a_file(path, option)
    created = [p for p in reversed([path, *path.parents]) if not p.exists()]
    result = Claim(path, settings, created)
    try:
        path.mkdir(parents=True, exist_ok=True)
        fd, probe = tempfile.mkstemp(prefix=".probe.", dir=path)
        os.close(fd)
        os.unlink(probe)
    except OSError as exc:
        result.abandon()
        if disk_full(exc):
            raise
        raise InputError(f"{option} = {str(path)!r}: cannot write there "
                         f"({exc.strerror or exc})") from None
    if (path / LOCK).exists():
        _take_stale_lock(path / LOCK)
    try:  # a live writer is named before the folder's old contents are judged
        result._lock(option)
    except (InputError, OSError):
        result.abandon()
        raise
    marker = read_marker(path)
    if marker is not None and not force:
        if marker.get("settings_digest") != settings_digest(settings):
            result.abandon()
            before = marker.get("settings", {})
            what = ", ".join(f"{k} {before.get(k)!r}" for k in ("command", "scene", "overrides")
                             if before.get(k) != settings.get(k)) or "other settings"
            raise InputError(f"{option} = {str(path)!r}: holds a different run ({what}); "
                             "choose another folder, or add --force to replace it")
    return result
