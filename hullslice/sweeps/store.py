"""What a sweep keeps on disk: each finished case as it arrives, for ``--resume``, and the
provenance of its inputs.

A partial folder holds ``sweep.json`` (what the sweep is: base case, grid, number of cases,
the mesh's SHA-256) and one small JSON file per finished case, each written atomically
(:func:`~hullslice.atomic.write_atomic`): a sweep killed at any moment leaves whole files
only, and one run again with ``resume`` skips the cases found there.
"""

from __future__ import annotations

import hashlib
import json
import os
import shutil
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import numpy as np

from ..atomic import write_atomic
from ..errors import InputError

#: File of a partial sweep's description, in its folder.
PARTIAL_SPEC = "sweep.json"


def spec(
    base: Mapping[str, Any], grid: Mapping[str, Any], cases: int, mesh_sha256: str, keep: bool
) -> dict[str, Any]:
    """What a partial folder must match to be resumed: the base case (paths absolute, so
    that any working folder resumes it), the grid, the number of cases, the mesh's SHA-256
    and whether histories are kept."""
    return {
        "base": jsonable(
            {k: Path(v).resolve() if isinstance(v, Path) else v for k, v in base.items()}
        ),
        "grid": jsonable(grid),
        "cases": cases,
        "mesh_sha256": mesh_sha256,
        "keep_histories": bool(keep),
    }


def _dump(path: Path, data: Any) -> None:
    write_atomic(path, json.dumps(data, allow_nan=True, default=str))


class Partial:
    """A folder with one small file per finished case, for resuming a sweep."""

    def __init__(self, folder: Path, spec: dict, resume: bool) -> None:
        self.folder = folder
        self.done: dict[int, dict] = {}
        spec_file = folder / PARTIAL_SPEC
        if folder.exists():
            if not resume:
                raise InputError(
                    f"a partial sweep is in {str(folder)!r}: give --resume (resume=True) to "
                    "continue it, or remove the folder to start again"
                )
            try:
                found = json.loads(spec_file.read_text(encoding="utf-8"))
            except (OSError, ValueError):
                found = None
            if found != json.loads(json.dumps(spec, default=str)):
                raise InputError(
                    f"the partial results in {str(folder)!r} are of another sweep (another "
                    "case, grid or mesh): remove the folder, or resume with the same case file"
                )
            for f in folder.glob("case-*.json"):
                try:
                    index = int(f.stem.removeprefix("case-"))
                    record = json.loads(f.read_text(encoding="utf-8"))
                except (OSError, ValueError):
                    continue  # a file cut short by the kill: the case runs again
                if not record.pop("lost", False):
                    self.done[index] = record
        self.spec = spec

    def create(self) -> None:
        """Make the folder (once the sweep is about to run)."""
        if not self.folder.exists():
            self.folder.mkdir()
            _dump(self.folder / PARTIAL_SPEC, self.spec)

    def add(self, index: int, record: dict) -> None:
        _dump(self.folder / f"case-{index}.json", record)


def remove_partial(folder: str | os.PathLike) -> None:
    """Remove a sweep's partial results (once its output is complete)."""
    folder = Path(folder)
    if (folder / PARTIAL_SPEC).is_file():
        shutil.rmtree(folder, ignore_errors=True)


def sha256(path: str | os.PathLike) -> str:
    """The SHA-256 of a file, hex."""
    h = hashlib.sha256()
    with open(path, "rb") as fh:
        for block in iter(lambda: fh.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def jsonable(value: Any) -> Any:
    """``value`` with paths as text, tuples and arrays as lists (for JSON)."""
    if isinstance(value, Path):
        return str(value)
    if isinstance(value, Mapping):
        return {str(k): jsonable(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [jsonable(v) for v in value]
    if isinstance(value, np.ndarray):
        return value.tolist()
    return value
