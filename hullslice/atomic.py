"""Files written completely or not at all, the outputs of one command all or none, and the
temporary files of killed runs."""

from __future__ import annotations

import contextvars
import errno
import os
import re
import tempfile
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path

__all__ = [
    "check_writable",
    "is_device",
    "remove_stale",
    "temp_prefix",
    "together",
    "write_atomic",
]


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


#: Longest target name, in bytes, kept whole in its temporary's name: the temporary adds
#: about 35 bytes (``.``, ``.hullslice-PID-``, 8 random characters, ``.tmp``) and a name may
#: have 255 bytes.
_NAME_IN_TEMP = 200


def _stem(name: str) -> str:
    """``name`` as its temporaries carry it: whole when short, else its first bytes and a
    hash of the whole name, so that a legal 255-byte name gets a legal temporary."""
    raw = name.encode("utf-8", "surrogateescape")
    if len(raw) <= _NAME_IN_TEMP:
        return name
    import hashlib

    head = raw[: _NAME_IN_TEMP - 20].decode("utf-8", "ignore")  # whole characters only
    return f"{head}~{hashlib.sha256(raw).hexdigest()[:12]}"


def temp_prefix(name: str) -> str:
    """Prefix of the temporary files and folders written for the target ``name``: hidden,
    and naming this process, so that one left by a killed run is recognised and removed by
    the next write to the same target (:func:`remove_stale`). A name too long to be carried
    whole is shortened with a hash of it (:data:`_NAME_IN_TEMP`)."""
    return f".{_stem(name)}.hullslice-{os.getpid()}-"


def remove_stale(parent: Path, name: str) -> None:
    """Remove the temporary files and folders of ``name`` in ``parent`` whose process has
    ended (a run killed with SIGKILL cannot clean up after itself)."""
    import shutil

    pattern = re.compile(re.escape(f".{_stem(name)}.hullslice-") + r"(\d+)-[^/]*$")
    try:
        entries = list(os.scandir(parent))
    except OSError:
        return
    for entry in entries:
        m = pattern.match(entry.name)
        if not m or int(m.group(1)) == os.getpid() or _alive(int(m.group(1))):
            continue
        try:
            if entry.is_dir(follow_symlinks=False):
                shutil.rmtree(entry.path)
            else:
                os.unlink(entry.path)
        except OSError:
            pass


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except (PermissionError, OverflowError, ValueError):
        return True  # another user's process, or not a process id: leave its files
    return True


def _named(exc: OSError, path: str | os.PathLike) -> OSError:
    """``exc`` naming the file asked for instead of a temporary file beside it."""
    if exc.errno is None:
        return exc
    return OSError(exc.errno, exc.strerror or os.strerror(exc.errno), os.fspath(path))


def _target(path: str | os.PathLike) -> Path:
    """The file a write to ``path`` replaces: a symbolic link is written through."""
    target = Path(path)
    if not target.is_symlink():
        return target
    real = Path(os.path.realpath(target))
    # a link the system resolves itself (/dev/stdout to a pipe: /proc/PID/fd/1 names no
    # file) is written through as it is
    return real if real.exists() or not target.exists() else target


def _device(target: Path) -> bool:
    """Whether ``target`` is a device or a pipe (written to directly, not replaced)."""
    return target.exists() and not target.is_file() and not target.is_dir()


def is_device(path: str | os.PathLike) -> bool:
    """Whether a write to ``path`` goes to a device or a pipe (``/dev/null``, ``/dev/stdout``)
    directly, not through a temporary file."""
    return _device(_target(path))


def _folder(target: Path) -> Path:
    return target.parent if str(target.parent) else Path(".")


def check_writable(path: str | os.PathLike) -> None:
    """Check that ``path`` can be written, before any work: a temporary file is made and
    removed beside it (so that a read-only folder, a read-only file system or one that takes
    no new file is found whoever runs; a device is checked for writing).

    Raises
    ------
    OSError
        Naming ``path`` (never the temporary file), with the reason in ``strerror``.
    """
    target = _target(path)
    if _device(target):
        if not os.access(target, os.W_OK):
            raise OSError(errno.EACCES, os.strerror(errno.EACCES), os.fspath(path))
        return
    parent = _folder(target)
    if not parent.is_dir():
        raise OSError(errno.ENOENT, f"folder {str(parent)!r} does not exist", os.fspath(path))
    try:
        fd, tmp = tempfile.mkstemp(prefix=temp_prefix(target.name), suffix=".tmp", dir=parent)
        os.close(fd)
        os.unlink(tmp)
    except OSError as exc:
        raise _named(exc, path) from None


@dataclass
class _Staged:
    """A file written to its temporary and waiting to be put in place."""

    path: str | os.PathLike  # as asked for, for messages
    target: Path  # the file replaced
    tmp: Path | None  # None for a device, written directly
    data: str | bytes


_BATCH: contextvars.ContextVar[list[_Staged] | None] = contextvars.ContextVar(
    "hullslice_atomic_batch", default=None
)


@contextmanager
def together() -> Iterator[None]:
    """Write the files of one command all or none.

    Inside the block, :func:`write_atomic` writes each file to its temporary beside the
    target and puts none in place. When the block ends, every file is put in place; when
    the block raises (an error, Ctrl-C, SIGTERM), or a file cannot be put in place, none
    is: the temporaries are removed and the files already put in place are restored as
    they were (removed if they were new). Blocks do not nest.

    Raises
    ------
    OSError
        A file that cannot be put in place, naming it.
    """
    if _BATCH.get() is not None:
        raise RuntimeError("hullslice.atomic.together() blocks do not nest")
    staged: list[_Staged] = []
    token = _BATCH.set(staged)
    try:
        yield
    except BaseException:
        _discard(staged)
        raise
    finally:
        _BATCH.reset(token)
    _place(staged)


def _discard(staged: list[_Staged]) -> None:
    for s in staged:
        if s.tmp is not None:
            try:
                os.unlink(s.tmp)
            except OSError:
                pass


def _place(staged: list[_Staged]) -> None:
    """Put staged files in place, devices last; on a failure restore those already placed."""
    files = [s for s in staged if s.tmp is not None]
    placed: list[tuple[_Staged, Path | None, bool]] = []  # (file, its backup, existed)
    try:
        for s in files:
            assert s.tmp is not None
            existed = s.target.is_file()
            backup = None
            if existed:  # a second name for the old file, to put it back after a failure
                backup = s.tmp.with_name(s.tmp.name.removesuffix(".tmp") + ".old")
                try:
                    os.link(s.target, backup)
                except OSError:
                    backup = None
            try:
                os.replace(s.tmp, s.target)
            except OSError as exc:
                if backup is not None:
                    os.unlink(backup)
                raise _named(exc, s.path) from None
            placed.append((s, backup, existed))
        for s in staged:
            if s.tmp is None:
                try:
                    _write_direct(s.target, s.data)
                except OSError as exc:  # a full device (/dev/full): named as asked for
                    raise _named(exc, s.path) from None
    except BaseException:
        for s, backup, existed in reversed(placed):
            try:
                if backup is not None:
                    os.replace(backup, s.target)
                elif not existed:
                    os.unlink(s.target)
            except OSError:
                pass
        _discard([s for s in files if s not in [p[0] for p in placed]])
        raise
    for _, backup, _ in placed:
        if backup is not None:
            try:
                os.unlink(backup)
            except OSError:
                pass


def _write_direct(target: Path, data: str | bytes) -> None:
    if isinstance(data, bytes):
        with open(target, "wb") as fb:
            fb.write(data)
    else:
        with open(target, "w", encoding="utf-8") as ft:
            ft.write(data)


def write_atomic(path: str | os.PathLike, data: str | bytes) -> Path:
    """Write a file completely or not at all.

    The data goes to a temporary file in the same folder, which then replaces ``path`` in
    one step; after an error ``path`` is unchanged. A symbolic link is written through (the
    file it points to is replaced, the link kept); a device or a pipe (``/dev/null``) is
    written to directly, as it cannot be replaced. The temporary file is named after the
    target and this process (:func:`temp_prefix`); those of killed runs are removed first.
    Inside a :func:`together` block the file is put in place when the block ends, with the
    block's other files.

    Raises
    ------
    OSError
        The file cannot be written; the error names ``path``, not the temporary file.
    """
    target = _target(path)
    batch = _BATCH.get()
    if _device(target):
        if batch is not None:
            batch.append(_Staged(path, target, None, data))
            return Path(path)
        try:
            _write_direct(target, data)
        except OSError as exc:
            raise _named(exc, path) from None
        return Path(path)
    parent = _folder(target)
    if not parent.is_dir():
        raise FileNotFoundError(
            errno.ENOENT, f"folder {str(parent)!r} does not exist", os.fspath(path)
        )
    remove_stale(parent, target.name)
    try:
        fd, tmp = tempfile.mkstemp(prefix=temp_prefix(target.name), suffix=".tmp", dir=parent)
    except OSError as exc:
        raise _named(exc, path) from None
    try:
        if isinstance(data, bytes):
            with os.fdopen(fd, "wb") as fb:
                fb.write(data)
        else:
            with os.fdopen(fd, "w", encoding="utf-8") as ft:
                ft.write(data)
        os.chmod(tmp, 0o666 & ~_umask())  # as an ordinary file, not mkstemp's private one
        if batch is not None:
            batch.append(_Staged(path, target, Path(tmp), data=b""))
            return Path(path)
        os.replace(tmp, target)
    except BaseException as exc:  # an error, Ctrl-C or SIGTERM (hullslice.safety): no file left
        try:
            os.unlink(tmp)
        except OSError:
            pass
        if isinstance(exc, OSError):
            raise _named(exc, path) from None
        raise
    return Path(path)
