"""What a sweep keeps on disk: each finished case as it arrives, for ``--resume``, and the
provenance of its inputs.

A partial folder holds ``sweep.json`` (what the sweep is: base case, grid, number of cases,
the mesh's SHA-256) and one small JSON file per finished case, each written atomically
(:func:`~hullslice.atomic.write_atomic`): a sweep killed at any moment leaves whole files
only, and one run again with ``resume`` skips the cases found there.

A case's file holds its record as JSON text with that text's SHA-256 and the versions that
computed it (hullslice's, and the solver's name, class and distribution version). A file
that fails its check on resuming (an edited value, text that is not such a record, ``[]``,
another hullslice or solver version) is not merged: its case runs again, and one warning
says how many did.
"""

from __future__ import annotations

import hashlib
import json
import os
import shutil
import warnings
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import numpy as np

from ..atomic import write_atomic
from ..errors import HullsliceWarning, InputError

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


def _record_text(record: Mapping[str, Any]) -> str:
    return json.dumps(record, allow_nan=True, default=str, sort_keys=True)


def _checked(data: Any, versions: Mapping[str, str]) -> dict | None:
    """The record of a case's file, or None when it fails its check (see the module notes)."""
    if not isinstance(data, dict) or not isinstance(data.get("record"), str):
        return None
    text = data["record"]
    if data.get("sha256") != hashlib.sha256(text.encode("utf-8")).hexdigest():
        return None
    if any(data.get(k) != v for k, v in versions.items()):
        return None
    try:
        record = json.loads(text)
    except ValueError:
        return None
    return record if isinstance(record, dict) else None


class Partial:
    """A folder with one small file per finished case, for resuming a sweep.

    ``versions`` (``{"hullslice": ..., "solver": ...}``) is written with each case and must
    match for a case to be resumed."""

    def __init__(
        self, folder: Path, spec: dict, resume: bool, versions: Mapping[str, str] | None = None
    ) -> None:
        self.folder = folder
        self.versions = dict(versions or {})
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
            rejected = 0
            for f in folder.glob("case-*.json"):
                try:
                    index = int(f.stem.removeprefix("case-"))
                except ValueError:
                    continue  # not a case's file
                if not 0 <= index < int(spec.get("cases", 0)):
                    continue
                try:
                    record = _checked(json.loads(f.read_text(encoding="utf-8")), self.versions)
                except (OSError, ValueError, RecursionError):
                    record = None
                if record is None:
                    rejected += 1  # its case runs again
                elif not record.pop("lost", False):
                    self.done[index] = record
            if rejected:
                warnings.warn(
                    f"{rejected} saved case(s) in {str(folder)!r} failed their check (edited, "
                    "malformed, or computed by another hullslice or solver version): they "
                    "run again",
                    HullsliceWarning,
                    stacklevel=3,
                )
        self.spec = spec

    def create(self) -> None:
        """Make the folder (once the sweep is about to run)."""
        if not self.folder.exists():
            self.folder.mkdir()
            _dump(self.folder / PARTIAL_SPEC, self.spec)

    def add(self, index: int, record: dict) -> None:
        text = _record_text(record)
        digest = hashlib.sha256(text.encode("utf-8")).hexdigest()
        _dump(
            self.folder / f"case-{index}.json",
            {**self.versions, "sha256": digest, "record": text},
        )


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
