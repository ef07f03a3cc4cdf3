"""Output folders: checked before the work, claimed while it runs, marked complete at its end.

A command that writes results first calls :func:`claim`, before any computation:

* the path is refused if it is empty, is a file, lies under a file, or cannot be written
  (a probe file is created and removed; folders created for the probe are removed again if
  the command then fails, so a refused command leaves nothing behind);
* a folder another live process is writing to (its lock file names a running process) is
  refused, whatever it holds;
* a folder holding another run's results — its completion marker records different settings —
  is refused unless ``force`` (two runs into one folder must not silently mix);
* a completion marker or a record of files being written that is not upliftlab's (a link, or
  not a JSON object) is refused: it is the user's, and upliftlab replaces only its own files;
* the files the command will write (``outputs``) are checked by name before any work
  (:func:`check_outputs`): each must fit the file system's name limit in bytes, be no link or
  other non-regular file, and, if it exists, be one upliftlab made here (listed by the
  folder's marker or record of files being written). A file of the user's at an output's name
  is refused with or without ``force``: the user moves it, or removes it;
* the folder is locked (:data:`LOCK`, holding this process's id) until the command ends, and
  is the one place the command writes to until then (:func:`upliftlab.paths.check_target`).
  Nothing in it is removed but upliftlab's own files: the temporary files of a killed writer
  are removed beside the file that is written again (:mod:`upliftlab.paths`), the user's own
  files never.

Just before it writes its first file the command calls :meth:`Claim.start_writing`, which
records the files it is about to write (:data:`WRITING`, when it declared ``outputs``) and
removes the old completion marker; when every file is written it calls
:meth:`Claim.complete`, which writes the completion marker :data:`MARKER` last and removes the
record. A folder whose marker is missing holds an interrupted or failed run; its record still
names the files upliftlab made, which the next run may replace. The marker lists the files and
the settings (:func:`settings_digest`): of the files the command names, only those upliftlab
made there (declared, written by this run, or listed before), never a file of the user's.

The claim watches every file the run writes in the folder (through
:func:`~upliftlab.paths.check_target`). A command whose files are named only as it runs (a
study) claims its folder with ``guard``: a file there that upliftlab did not make is refused
when the run comes to write it, not replaced; the run's first file starts the writing
(:meth:`Claim.start_writing`), and each file it writes is added to :data:`WRITING` before it is
written, so that an interrupted run's files are still known as upliftlab's.

A lock names the process holding it. A lock whose process has ended is stale and removed; so
is one whose content is no process id (not a whole number from 1 to 2³¹ − 1: upliftlab never
writes that, so no live upliftlab run holds it). An empty lock is a run that has created it
and not yet written its id: it is refused, with what to do if it was left by a crash.
"""

from __future__ import annotations

import contextlib
import hashlib
import json
import os
import re
import stat
import tempfile
from dataclasses import dataclass, field
from pathlib import Path

from .checks import InputError
from .paths import (check_folder_name, check_output_name, check_target, disk_full, pop_root,
                    push_root)

__all__ = ["MARKER", "LOCK", "WRITING", "Claim", "claim", "probe_folder", "settings_digest",
           "read_marker"]

MARKER = "upliftlab-run.json"
_CONTROL = re.compile(r"[\x00-\x1f\x7f]")
LOCK = ".upliftlab.lock"
#: The record of the files a run is writing (present from :meth:`Claim.start_writing` until
#: :meth:`Claim.complete`; it survives an interrupted run).
WRITING = ".upliftlab-writing.json"
#: The largest process id a lock may name (pid_t is a signed 32-bit integer).
_PID_MAX = 2**31 - 1


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
    """Whether process ``pid`` (1 to :data:`_PID_MAX`) runs."""
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
    outputs: list[str] = field(default_factory=list)
    #: Refuse, when it comes to be written, a file upliftlab did not make (module docstring).
    guard: bool = False
    #: The names (in the folder) of the files this run has written or is writing.
    written: set[str] = field(default_factory=set)
    watching: bool = False
    writing: bool = False
    made: set[str] | None = None
    #: The completion marker's bytes when the writing started (None: there was none).
    old_marker: bytes | None = None

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
        self.root = push_root(self.path, watch=self._watch)

    def _watch(self, target: Path) -> None:
        """A file about to be written in the folder (``target``, its folder resolved): recorded
        as this run's; with :attr:`guard`, refused if a file upliftlab did not make is there."""
        if not self.watching:  # the watcher is registered with the root, in _lock
            return
        name = str(target.relative_to(self.root))
        if name in (MARKER, WRITING, LOCK) or name in self.written:
            return
        if self.guard:
            _refuse_a_users_file(target, name, self._made_before())
            if not self.writing:
                self.start_writing()
        self.written.add(name)
        if self.guard:
            self._record_writing()

    def _made_before(self) -> set[str]:
        """The files upliftlab made in the folder before this run (:func:`_made_here`), read
        once: this run's own records of its writing must not add to them."""
        if self.made is None:
            self.made = _made_here(self.path)
        return self.made

    def _record_writing(self) -> None:
        """Write :data:`WRITING`: the files upliftlab made here, declared and written."""
        from .results import write_text

        names = sorted((self.made or set()) | set(self.outputs) | self.written)
        write_text(self.path / WRITING, json.dumps({"files": names}, indent=2) + "\n")

    def start_writing(self) -> None:
        """The first file is about to be written: the folder no longer holds a complete run.
        The declared outputs (and the files upliftlab made here before) are recorded first
        (:data:`WRITING`), so that an interrupted run's files are still known as upliftlab's."""
        self._made_before()
        if self.outputs or self.guard:
            self._record_writing()
        self.writing = True
        with contextlib.suppress(OSError):
            self.old_marker = (self.path / MARKER).read_bytes()
        with contextlib.suppress(FileNotFoundError):
            (self.path / MARKER).unlink()

    def complete(self, files) -> Path:
        """Write the completion marker (last) and release the folder."""
        from .results import write_text

        names = sorted(self._own_names(files))
        record = {"complete": True, "settings": self.settings,
                  "settings_digest": settings_digest(self.settings), "files": names}
        path = write_text(self.path / MARKER, json.dumps(record, indent=2, default=str) + "\n")
        with contextlib.suppress(FileNotFoundError):
            (self.path / WRITING).unlink()  # the marker now lists what was written
        self.release()
        return path

    def _undo_writing(self) -> None:
        """Remove :data:`WRITING` and put the old completion marker back (see :meth:`abandon`)."""
        from .results import write_bytes

        with contextlib.suppress(FileNotFoundError):
            (self.path / WRITING).unlink()
        if self.old_marker is not None:
            write_bytes(self.path / MARKER, self.old_marker)
        self.writing = False

    def _own_names(self, files) -> set[str]:
        """The names, in the folder, of those of ``files`` upliftlab made there: declared,
        written by this run, or made by an earlier one (a user's file is never listed)."""
        own = self._made_before() | set(self.outputs) | self.written
        folder = self.path.resolve()
        names = set()
        for file in files:
            where = Path(os.path.realpath(Path(file).parent)) / Path(file).name
            if where.is_relative_to(folder) and str(where.relative_to(folder)) in own:
                names.add(str(where.relative_to(folder)))
        return names

    def remove_own(self, name: str) -> bool:
        """Remove the file ``name`` (in the folder) if an earlier run of upliftlab made it
        there and this run has not written it: an output of that run this one does not make
        again (a report's PDF on a paper not asked for now). A file upliftlab did not make is
        left as it is, and so is anything but a regular file (a link, a folder). Once removed,
        the name is no longer upliftlab's here: the record of the files being written forgets
        it, so that a file the user puts there later is theirs. True if a file was removed."""
        target = self.path / name
        inside = Path(os.path.realpath(target.parent)).is_relative_to(self.path.resolve())
        if not inside or name in self.written or name not in self._made_before():
            return False
        try:
            if not stat.S_ISREG(os.lstat(target).st_mode):
                return False
            target.unlink()
        except OSError:  # gone already, or not ours to remove after all: left as it is
            return False
        self.made.discard(name)
        if self.writing and (self.outputs or self.guard):
            self._record_writing()
        return True

    def release(self) -> None:
        if self.locked:
            with contextlib.suppress(FileNotFoundError):
                (self.path / LOCK).unlink()
            self.locked = False
            pop_root(self.root)

    def abandon(self) -> None:
        """Give the folder up after a failure: unlock it and remove the folders this claim
        created, if nothing was written in them. A run refused after it started writing whose
        files are all gone again (a study refused by its budget removes the records it
        copied) leaves the folder as it found it: its record of files being written removed,
        the old completion marker put back."""
        if self.writing and not any(os.path.lexists(self.path / n) for n in self.written):
            self._undo_writing()
        self.release()
        for folder in reversed(self.created):
            with contextlib.suppress(OSError):
                folder.rmdir()  # only if empty


def _lock_pid(lock: Path) -> int | None:
    """The process id ``lock`` holds; 0 if it is empty (a run between creating it and writing
    its id) or cannot be read; None if its content is no process id (module docstring)."""
    try:
        text = lock.read_text(errors="replace").strip()
    except OSError:
        return 0
    if not text:
        return 0
    try:
        pid = int(text)
    except ValueError:
        return None
    return pid if 0 < pid <= _PID_MAX else None


def _lock_owner(lock: Path) -> str:
    """Who holds ``lock``, for the refusal's line."""
    pid = _lock_pid(lock)
    if pid is None:
        return f"lock file {lock.name}, holding no process id"
    if not pid:
        return (f"lock file {lock.name}, empty or unreadable; if no upliftlab run is writing "
                "there, a crash left it: remove it")
    return f"process {pid}"


def _take_stale_lock(lock: Path) -> None:
    """Remove a lock left by a process that no longer runs, or one holding no process id."""
    pid = _lock_pid(lock)
    if pid is None or (pid and not _alive(pid)):
        with contextlib.suppress(FileNotFoundError):
            lock.unlink()


def claim(out: str | os.PathLike | None, default: str | os.PathLike, *, settings: dict,
          force: bool = False, option: str = "--out", outputs=(), patterns=(),
          guard: bool = False) -> Claim:
    """Check and claim the output folder ``out`` (``default`` when None) for a run with
    ``settings`` that will write the files named ``outputs`` in it (module docstring), and
    files whose names, known only as it runs, match the glob ``patterns`` (those already
    there are checked as outputs). ``guard``: the files are named only as the run goes; each is
    checked when it comes to be written (module docstring). Nothing is computed before this
    returns. A path through
    ``..`` is resolved first (links followed), so that no folder is created that the ``..``
    then leaves."""
    if out is not None and (not isinstance(out, (str, os.PathLike)) or not str(out).strip()):
        raise InputError(f"{option} = {out!r}: expected a folder path")
    path = check_folder_name(out if out is not None else default, option)
    if ".." in path.parts:
        path = Path(os.path.realpath(path))
    try:
        result = _claim(path, settings, force, option)
        result.outputs = [str(name) for name in outputs]
        result.outputs += _matching(path, patterns, result.outputs)
        result.guard = bool(guard)
        try:
            check_outputs(result)
        except BaseException:
            result.abandon()
            raise
        result.watching = True
        return result
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
        _make_writable(path, option)
    finally:
        for made in reversed(created):
            with contextlib.suppress(OSError):
                made.rmdir()
    return path


def _make_writable(path: Path, option: str) -> None:
    """Make the folder ``path`` (and its parents) and a probe file in it, removed again: an
    :class:`InputError` naming ``option`` when nothing can be written there; a full disk is
    not bad input and keeps its own exit (3, no space left)."""
    try:
        path.mkdir(parents=True, exist_ok=True)
        fd, probe = tempfile.mkstemp(prefix=".probe.", dir=path)
        os.close(fd)
        os.unlink(probe)
    except OSError as exc:
        if disk_full(exc):
            raise
        raise InputError(f"{option} = {str(path)!r}: cannot write there "
                         f"({exc.strerror or exc})") from None


def _claim(path: Path, settings: dict, force: bool, option: str) -> Claim:
    """:func:`claim` of the folder ``path`` (its checks, in order)."""
    if _CONTROL.search(str(path)):
        raise InputError(f"{option} = {str(path)!r}: a folder name with a control character "
                         "(a line break, a tab, …) is refused")
    _refuse_a_file(path, option)
    created = [p for p in reversed([path, *path.parents]) if not p.exists()]
    result = Claim(path, settings, created)
    try:
        _make_writable(path, option)
    except BaseException:
        result.abandon()
        raise
    if (path / LOCK).exists():
        _take_stale_lock(path / LOCK)
    try:  # a live writer is named before the folder's old contents are judged
        result._lock(option)
    except (InputError, OSError):
        result.abandon()
        raise
    try:
        marker = _own_record(path, MARKER, option)
        _own_record(path, WRITING, option)
    except InputError:
        result.abandon()
        raise
    if marker is not None and not force:
        if marker.get("settings_digest") != settings_digest(settings):
            result.abandon()
            before = marker.get("settings", {})
            what = ", ".join(f"{k} {before.get(k)!r}" for k in ("command", "scene", "overrides")
                             if before.get(k) != settings.get(k)) or "other settings"
            raise InputError(f"{option} = {str(path)!r}: holds a different run ({what}); "
                             "choose another folder, or add --force to replace it")
    return result


def _own_record(folder: Path, name: str, option: str) -> dict | None:
    """The JSON object in ``folder / name`` (the marker, or the record of files being written),
    None if there is none; an :class:`InputError` if something else is there (a link, a folder,
    not a JSON object): upliftlab did not make it, and does not replace it."""
    path = folder / name
    try:
        mode = os.lstat(path).st_mode
    except FileNotFoundError:
        return None
    record = None
    if stat.S_ISREG(mode):
        try:
            record = json.loads(path.read_text())
        except (OSError, ValueError):
            record = None
    if not isinstance(record, dict):
        what = "a regular file but not upliftlab's JSON" if stat.S_ISREG(mode) else \
            "not a regular file"
        raise InputError(f"{option} = {str(folder)!r}: its {name} is {what}, so not "
                         "upliftlab's; move it away or remove it, then run again")
    return record


def _made_here(folder: Path) -> set[str]:
    """The names of the files upliftlab made in ``folder``: those the completion marker lists
    and those the record of an interrupted run's files lists."""
    names: set[str] = set()
    for record in (read_marker(folder), _read_json(folder / WRITING)):
        files = record.get("files") if isinstance(record, dict) else None
        if isinstance(files, list):
            names.update(str(f) for f in files)
    return names


def _read_json(path: Path) -> object:
    """The JSON in ``path``, None if there is none or it is not JSON."""
    try:
        return json.loads(path.read_text())
    except (OSError, ValueError):
        return None


def _matching(folder: Path, patterns, named) -> list[str]:
    """The names (in ``folder``) of the entries there that match a glob of ``patterns`` and are
    not in ``named``: a file, a link or another non-folder a run writing such names could
    replace."""
    found = {str(entry.relative_to(folder)) for pattern in patterns
             for entry in folder.glob(pattern) if entry.is_symlink() or not entry.is_dir()}
    return sorted(found - set(named))


def check_outputs(held: Claim) -> None:
    """Check, before any work, each file ``held`` will write (its ``outputs``, names in its
    folder): the name fits the file system in bytes, with its temporary file's
    (:func:`~upliftlab.paths.check_output_name`); nothing but a regular file is there, and the
    path stays inside the folder (:func:`~upliftlab.paths.check_target`); a file that is there
    is one upliftlab made here (:func:`_made_here`), else it is the user's and is refused,
    ``force`` or not."""
    made = _made_here(held.path) if held.outputs else set()
    for name in held.outputs:
        _refuse_a_users_file(check_target(check_output_name(held.path / name)), name, made)


def _refuse_a_users_file(target: Path, name: str, made: set[str]) -> None:
    """Refuse ``target`` (``name`` in its folder) if a file is there that upliftlab did not
    make (not in ``made``): it is the user's, and never replaced, ``force`` or not."""
    if os.path.lexists(target) and name not in made:
        raise InputError(f"output {str(target)!r}: a file upliftlab did not make is at this "
                         "output's name; move it away (or remove it), then run again (--force "
                         "replaces only upliftlab's own files)")
