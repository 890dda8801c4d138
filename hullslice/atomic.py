"""Files written completely or not at all, and the temporary files of killed runs."""

from __future__ import annotations

import os
import re
import tempfile
from pathlib import Path

__all__ = ["remove_stale", "temp_prefix", "write_atomic"]


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


def temp_prefix(name: str) -> str:
    """Prefix of the temporary files and folders written for the target ``name``: hidden,
    and naming this process, so that one left by a killed run is recognised and removed by
    the next write to the same target (:func:`remove_stale`)."""
    return f".{name}.hullslice-{os.getpid()}-"


def remove_stale(parent: Path, name: str) -> None:
    """Remove the temporary files and folders of ``name`` in ``parent`` whose process has
    ended (a run killed with SIGKILL cannot clean up after itself)."""
    import shutil

    pattern = re.compile(re.escape(f".{name}.hullslice-") + r"(\d+)-[^/]*$")
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


def write_atomic(path: str | os.PathLike, data: str | bytes) -> Path:
    """Write a file completely or not at all.

    The data goes to a temporary file in the same folder, which then replaces ``path`` in
    one step; after an error ``path`` is unchanged. A symbolic link is written through (the
    file it points to is replaced, the link kept); a device or a pipe (``/dev/null``) is
    written to directly, as it cannot be replaced. The temporary file is named after the
    target and this process (:func:`temp_prefix`); those of killed runs are removed first.
    """
    target = Path(path)
    if target.is_symlink():
        target = Path(os.path.realpath(target))
    if target.exists() and not target.is_file() and not target.is_dir():
        if isinstance(data, bytes):
            with open(target, "wb") as fb:
                fb.write(data)
        else:
            with open(target, "w", encoding="utf-8") as ft:
                ft.write(data)
        return Path(path)
    parent = target.parent if str(target.parent) else Path(".")
    if not parent.is_dir():
        raise FileNotFoundError(f"folder {str(parent)!r} does not exist")
    remove_stale(parent, target.name)
    fd, tmp = tempfile.mkstemp(prefix=temp_prefix(target.name), suffix=".tmp", dir=parent)
    try:
        if isinstance(data, bytes):
            with os.fdopen(fd, "wb") as fb:
                fb.write(data)
        else:
            with os.fdopen(fd, "w", encoding="utf-8") as ft:
                ft.write(data)
        os.chmod(tmp, 0o666 & ~_umask())  # as an ordinary file, not mkstemp's private one
        os.replace(tmp, target)
    except BaseException:  # an error, Ctrl-C or SIGTERM (hullslice.safety): no file left
        try:
            os.unlink(tmp)
        except OSError:
            pass
        raise
    return Path(path)
