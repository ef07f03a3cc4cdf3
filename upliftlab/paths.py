"""Where upliftlab may write, and what it may remove.

A scene, a motion file or an option is untrusted input, and three rules keep it from harming
the user's files, whatever field or path carries it:

* **A name that becomes a path is one plain component** (:func:`path_component`): a scene's
  name and case, a study's label. No separator, no ``.`` or ``..``, no leading dot (hidden
  names are upliftlab's own temporary files), no control character, at most
  :data:`MAX_COMPONENT` bytes in the file system's encoding (a character may take several).
* **Every file is written inside the output folder** (:func:`check_target`). While a command
  holds an output folder (:mod:`upliftlab.outdir` registers it, and a study its store), a
  target whose resolved path, links followed, lies outside every registered root is refused.
  A target that exists and is not a regular file (a device node, a folder, a pipe, a link) is
  refused in any case, also through the Python API. A root may be registered with a watcher
  (:func:`push_root`), which sees every target checked in it (and in no root nested deeper,
  such as a study's store inside its output folder): the claim of an output folder records
  there what the run writes, and may refuse to replace a file upliftlab did not make.
* **Only files upliftlab made are removed** (:func:`temporary_sibling`). A temporary file is
  named ``.<target>.upliftlab-<pid>-<random>.part``, beside its target; before writing a target,
  the temporary files of that same target whose process is no longer alive are removed, and
  nothing else. A process that is ended (a pool's worker told to stop) removes its own
  unfinished temporaries first (:func:`remove_live_temporaries`).

A write that finds no room (a full disk, a quota, a file-size limit: :func:`disk_full`) is not
bad input: the command line ends it with its own line and exit code.
"""

from __future__ import annotations

import contextlib
import errno
import os
import re
import shutil
import stat
import tempfile
import threading
from collections.abc import Iterator
from pathlib import Path

from .checks import InputError

__all__ = ["MAX_COMPONENT", "path_component", "check_folder_name", "check_output_name",
           "check_target", "TEMPORARY_EXTRA",
           "output_root", "temporary_sibling", "TEMPORARY_TAG", "DISK_FULL", "disk_full",
           "forget_temporary", "remove_live_temporaries", "file_kind",
           "REGULAR_FILE", "NO_SUCH_FILE"]

#: Longest name upliftlab turns into a path component, in bytes of the file system's encoding
#: (a file name may hold 255 bytes; the name is joined with a case, a suffix and a temporary
#: file's tag).
MAX_COMPONENT = 100

#: What marks a temporary file as upliftlab's own.
TEMPORARY_TAG = "upliftlab"

#: The errors of a write that found no room: no space, a quota, a file-size limit.
DISK_FULL = frozenset({errno.ENOSPC, errno.EDQUOT, errno.EFBIG})

_UNSAFE = re.compile(r"[\x00-\x1f\x7f/\\]")
_CONTROL_CHAR = re.compile(r"[\x00-\x1f\x7f]")
_ROOTS: list[Path] = []
_LIVE: set[Path] = set()  # this process's temporaries not yet moved into place or removed
_ROOTS_LOCK = threading.Lock()
#: The watcher of a root registered with one (:func:`push_root`), by root.
_WATCHES: dict[Path, object] = {}


def path_component(name: str, field: str) -> str:
    """``name``, checked to be one plain path component (module docstring); else an
    :class:`~upliftlab.checks.InputError` naming ``field``."""
    valid = (f"valid: 1 to {MAX_COMPONENT} bytes (UTF-8: an accented letter takes 2), no '/', "
             "'\\', control characters or leading '.'")
    if not isinstance(name, str) or not name:
        raise InputError(f"{field} = {name!r}: not a name; {valid}")
    size = _name_bytes(name)
    if size > MAX_COMPONENT:
        raise InputError(f"{field} = {name[:40]!r}...: {len(name)} characters, {size} bytes; "
                         f"{valid}")
    if _UNSAFE.search(name) or name.startswith(".") or name.strip() != name:
        raise InputError(f"{field} = {name!r}: cannot name a file; {valid}")
    return name


def _name_bytes(name: str) -> int:
    """The length of ``name`` in bytes of the file system's encoding, which is what its limits
    count (a name that cannot be encoded counts its UTF-8 bytes, and fails where it is used)."""
    try:
        return len(os.fsencode(name))
    except UnicodeError:
        return len(name.encode("utf-8", "surrogatepass"))


#: The longest temporary sibling's name beyond its target's name: ``.`` + ``.upliftlab-`` +
#: a process id (at most 10 digits) + ``-`` + 8 random characters + ``.part``.
TEMPORARY_EXTRA = len(f"..{TEMPORARY_TAG}-{2**31 - 1}-xxxxxxxx.part")


def check_output_name(path: str | os.PathLike, field: str = "output") -> Path:
    """``path``, a file upliftlab will write, checked by its name alone before any work: the
    name and its temporary sibling's longer one (:func:`temporary_sibling`) fit the file
    system's NAME_MAX, counted in bytes; else an :class:`~upliftlab.checks.InputError`."""
    path = Path(path)
    folder = next((p for p in [path.parent, *path.parent.parents] if p.is_dir()), Path("."))
    try:
        name_max = os.pathconf(folder, "PC_NAME_MAX")
    except (OSError, ValueError, AttributeError):
        name_max = 255
    size = _name_bytes(path.name)
    if size + TEMPORARY_EXTRA > name_max:
        raise InputError(f"{field} {path.name[:60]!r}...: a file name of {size} bytes; with "
                         f"its temporary file's {TEMPORARY_EXTRA} more it must fit the file "
                         f"system's {name_max} (shorten the scene file's or the case's name)")
    return path


def check_folder_name(path: str | os.PathLike, option: str = "--out") -> Path:
    """``path`` as a folder path, checked by its text alone before any work: no control
    character (NUL, a line break, a tab, …), no component longer than the file system's
    NAME_MAX and no path longer than its PATH_MAX (:func:`_limits`)."""
    if not isinstance(path, (str, os.PathLike)) or not str(path).strip():
        raise InputError(f"{option} = {path!r}: expected a folder path")
    text = str(path)
    if _CONTROL_CHAR.search(text):
        raise InputError(f"{option} = {text[:80]!r}: a folder name with a control character "
                         "(NUL, a line break, a tab, …) is refused")
    name_max, path_max = _limits()
    longest = max(Path(text).expanduser().parts, key=lambda p: len(os.fsencode(p)), default="")
    if len(os.fsencode(longest)) > name_max:
        raise InputError(f"{option} = {text[:80]!r}: a folder name of "
                         f"{len(os.fsencode(longest))} bytes; the file system allows at most "
                         f"{name_max} in one name")
    full = len(os.fsencode(os.path.abspath(os.path.expanduser(text))))
    if full >= path_max:
        raise InputError(f"{option} = {text[:80]!r}: a path of {full} bytes; the file system "
                         f"allows fewer than {path_max}")
    return Path(text).expanduser()


def _limits() -> tuple[int, int]:
    """(NAME_MAX, PATH_MAX) of the file system of the working folder (255 and 4096 where
    it does not say)."""
    try:
        return os.pathconf(".", "PC_NAME_MAX"), os.pathconf(".", "PC_PATH_MAX")
    except (OSError, ValueError, AttributeError):
        return 255, 4096


@contextlib.contextmanager
def output_root(folder: str | os.PathLike) -> Iterator[Path]:
    """Register ``folder`` as a place this process may write to while the block runs."""
    root = Path(folder).resolve()
    with _ROOTS_LOCK:
        _ROOTS.append(root)
    try:
        yield root
    finally:
        with _ROOTS_LOCK:
            _ROOTS.remove(root)


def push_root(folder: str | os.PathLike, watch=None) -> Path:
    """Register ``folder`` (:func:`output_root` without a block); undo with :func:`pop_root`.
    ``watch(target)``, if given, is called by :func:`check_target` with each target (its folder
    resolved) whose innermost registered root is this one, after the other checks: it may
    raise :class:`~upliftlab.checks.InputError` to refuse the target."""
    root = Path(folder).resolve()
    with _ROOTS_LOCK:
        _ROOTS.append(root)
        if watch is not None:
            _WATCHES[root] = watch
    return root


def pop_root(root: Path) -> None:
    """Unregister a root registered by :func:`push_root` (once; a second call does nothing)."""
    with _ROOTS_LOCK, contextlib.suppress(ValueError):
        _ROOTS.remove(root)
        if root not in _ROOTS:
            _WATCHES.pop(root, None)


def _resolved(path: Path) -> Path:
    """``path`` with its folder's links resolved and its own name kept (a link at the target
    itself is refused by :func:`check_target`, not followed)."""
    return Path(os.path.realpath(path.parent)) / path.name


def check_target(path: str | os.PathLike) -> Path:
    """``path`` as a file upliftlab may (re)place: an existing target must be a regular file,
    and while output roots are registered it must lie inside one. Raises
    :class:`~upliftlab.checks.InputError` before anything is written."""
    path = Path(path)
    try:
        mode = os.lstat(path).st_mode
    except FileNotFoundError:
        mode = None
    except OSError as exc:
        raise InputError(f"output {str(path)!r}: cannot be examined ({exc.strerror})") from None
    if mode is not None and not stat.S_ISREG(mode):
        kind = _kind(mode)
        raise InputError(f"output {str(path)!r}: is {kind}, not a regular file; upliftlab "
                         "replaces only regular files")
    with _ROOTS_LOCK:
        roots, watches = list(_ROOTS), dict(_WATCHES)
    if roots:
        where = _resolved(path)
        inside = [root for root in roots if where.is_relative_to(root)]
        if not inside:
            raise InputError(f"output {str(path)!r}: resolves to {str(where)!r}, outside the "
                             f"output folder {str(roots[-1])!r}; nothing is written there")
        watch = watches.get(max(inside, key=lambda root: len(root.parts)))
        if watch is not None:
            watch(where)
    return path


#: What :func:`file_kind` calls a regular file, and a path that names nothing.
REGULAR_FILE, NO_SUCH_FILE = "a regular file", "no such file"


def file_kind(path: str | os.PathLike, where: str) -> str:
    """What an input ``path`` is: :data:`REGULAR_FILE`, :data:`NO_SUCH_FILE`, or what else it
    is ("a folder", "a named pipe", "a character device", ...). Found by ``os.stat`` (links
    followed) without opening it: opening a named pipe waits for a writer, and a device such
    as /dev/zero never ends. A path that cannot be examined is refused in one line that begins
    with ``where`` (the option or field and the path)."""
    try:
        mode = os.stat(path).st_mode
    except (FileNotFoundError, NotADirectoryError):
        return NO_SUCH_FILE
    except OSError as exc:
        raise InputError(f"{where}: cannot be examined ({exc.strerror})") from None
    except ValueError as exc:  # a NUL in the path
        raise InputError(f"{where}: not a path ({exc})") from None
    return REGULAR_FILE if stat.S_ISREG(mode) else _kind(mode)


def _kind(mode: int) -> str:
    for test, kind in ((stat.S_ISDIR, "a folder"), (stat.S_ISLNK, "a symbolic link"),
                       (stat.S_ISCHR, "a character device"), (stat.S_ISBLK, "a block device"),
                       (stat.S_ISFIFO, "a named pipe"), (stat.S_ISSOCK, "a socket")):
        if test(mode):
            return kind
    return "not a regular file"


def _prefix(target: Path) -> str:
    return f".{target.name}.{TEMPORARY_TAG}-"


_STALE = re.compile(r"(\d+)-[A-Za-z0-9_]+\.part")


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except (PermissionError, OverflowError):
        return True
    return True


def remove_stale_temporaries(target: Path) -> list[Path]:
    """Remove the temporary files of ``target`` left beside it by upliftlab processes that no
    longer run (a kill during a write); returns what was removed. Nothing else is touched."""
    prefix, removed = _prefix(target), []
    try:
        names = os.listdir(target.parent)
    except OSError:
        return removed
    for name in names:
        match = _STALE.fullmatch(name[len(prefix):]) if name.startswith(prefix) else None
        if match and not _alive(int(match.group(1))):
            candidate = target.parent / name
            with contextlib.suppress(OSError):
                if stat.S_ISREG(os.lstat(candidate).st_mode):
                    candidate.unlink()
                    removed.append(candidate)
    return removed


def temporary_sibling(target: str | os.PathLike, *, directory: bool = False) -> Path:
    """Create and return a temporary file (or folder) beside ``target``, named as upliftlab's
    own (module docstring), after checking the target (:func:`check_target`) and removing its
    stale temporaries. The caller moves it into place or removes it."""
    target = check_target(target)
    target.parent.mkdir(parents=True, exist_ok=True)
    remove_stale_temporaries(target)
    prefix = f"{_prefix(target)}{os.getpid()}-"
    if directory:
        made = Path(tempfile.mkdtemp(prefix=prefix, suffix=".part", dir=target.parent))
    else:
        fd, name = tempfile.mkstemp(prefix=prefix, suffix=".part", dir=target.parent)
        os.close(fd)
        made = Path(name)
    _LIVE.add(made)
    return made


def forget_temporary(path: Path) -> None:
    """``path``, a temporary of :func:`temporary_sibling`, was moved into place or removed."""
    _LIVE.discard(path)


def remove_live_temporaries() -> None:
    """Remove every temporary file or folder this process made and has not finished (a process
    being ended calls it: nothing half-written stays behind)."""
    for path in list(_LIVE):
        with contextlib.suppress(OSError):
            if path.is_dir() and not path.is_symlink():
                shutil.rmtree(path, ignore_errors=True)
            else:
                path.unlink()
        _LIVE.discard(path)


def disk_full(exc: BaseException) -> bool:
    """Whether ``exc`` is a write that found no room (:data:`DISK_FULL`)."""
    return isinstance(exc, OSError) and exc.errno in DISK_FULL
