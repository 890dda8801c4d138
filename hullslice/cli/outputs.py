"""The files a command writes: checked before the work, written all or none.

Every output path (``-o``, ``--plot``, ``--save-case``, ``--write-mesh``) is checked before
any computation (:func:`check_path`): not empty, not a folder, in an existing folder that
takes a new file (a temporary file is made and removed beside it), not one of the run's
inputs, and not the same file as another output (:func:`check_output`). After the work the
files are written to temporaries and put in place together (:func:`write_together`, over
:func:`hullslice.atomic.together`): when one fails, none is left.
"""

from __future__ import annotations

import argparse
import errno
import os
import sys
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from types import SimpleNamespace
from typing import Any

from ..atomic import check_writable, is_device, together, write_atomic
from ..errors import InputError
from ..paths import check_not_an_input, printable, run_inputs
from ..study import Study, StudyResult, execute
from ..textout import csv_text, json_text

#: Extensions of the figure files ``--plot`` draws.
FIGURE_FORMATS = (".png", ".svg", ".pdf")


@dataclass
class Outcome:
    """What a command produced, in every form it can be given.

    Attributes
    ----------
    table : str
        The terminal view.
    data : dict
        The JSON view.
    csv_columns : list of str
        Columns of the CSV view.
    csv_rows : list of dict
        Rows of the CSV view.
    figures : dict of str to callable
        Figure builders by name; the first is the one ``--plot`` draws.
    """

    table: str
    data: dict
    csv_columns: list[str]
    csv_rows: list[dict]
    figures: dict[str, Callable] = field(default_factory=dict)

    def text(self, fmt: str) -> str:
        if fmt == "json":
            return json_text(self.data)
        if fmt == "csv":
            return csv_text(self.csv_columns, self.csv_rows)
        return self.table


def compute(
    study: Study,
    save_case: str | None = None,
    progress=None,
    write_mesh: str | None = None,
    sections_every: int = 0,
) -> StudyResult:
    """Check the outputs can be written and the optional libraries they need are installed
    (before any work), then execute the study (``sections_every``: a simulation keeps
    every Nth instant's slices)."""
    check_output(study, save_case, write_mesh)
    check_extras(study, write_mesh)
    return execute(study, progress=progress, sections_every=sections_every)


def check_extras(study: Study, write_mesh: str | None = None, figures: bool = False) -> None:
    """Refuse, before any work, a study that needs an optional library not installed, with
    the one-line hint naming the extra (:func:`hullslice.extras.need`): matplotlib for
    ``--plot`` (or the ``figures`` of a report), pymeshfix for ``--repair close``, and the
    libraries of a mesh format of ``hullslice[formats]``, read or written (``write_mesh``).
    """
    from ..extras import need
    from ..readers.extra import require_format

    if study.plot or figures:
        need("plot", "matplotlib", "--plot" if study.plot else "a report")
    if study.repair == "close":
        need("repair", "pymeshfix", "--repair close")
    require_format(Path(study.mesh).suffix)
    if write_mesh:
        require_format(Path(write_mesh).suffix, writing=True)


#: A file a command writes besides its text, figure and case: ``(option, path, writer)``,
#: the writer writing ``path`` through :func:`hullslice.atomic.write_atomic`.
Extra = tuple[str, str, Callable[[], object]]


def finish(
    study: Study,
    outcome: Outcome,
    save_case: str | None = None,
    extra: Sequence[Extra] = (),
) -> int:
    """Give a study's outcome: the text in its format, the figure, the case file and the
    ``extra`` files, all or none: each is written to its temporary, and all are put in
    place only when every one is complete (:func:`hullslice.atomic.together`)."""
    if study.plot and not outcome.figures:
        raise InputError(f"hullslice {study.command} draws no figure; leave out --plot")
    text = outcome.text(study.format or "table")
    writers: list[Extra] = []
    if study.plot:
        from ..plots import save

        plot = study.plot
        writers.append(("--plot", plot, lambda: save(next(iter(outcome.figures.values()))(), plot)))
    if save_case:
        from ..case import write_case

        case_path = save_case
        writers.append(("--save-case", case_path, lambda: write_case(study.to_case(), case_path)))
    writers += extra
    if study.output:
        output = study.output
        writers.append(("--output", output, lambda: write_atomic(output, text)))
    check_output(study, save_case, *(path for option, path, _ in extra))
    write_together(writers)
    if not study.output:
        print_result(text)
    return 0


def print_result(text: str) -> None:
    """Write a command's result to stdout, a line break at its end; a stdout that cannot
    take it (a full disk, ``> /dev/full``) is an :class:`InputError` naming it."""
    try:
        sys.stdout.write(text if text.endswith("\n") else text + "\n")
        sys.stdout.flush()
    except BrokenPipeError:
        raise  # the reader went away (| head): not an error
    except OSError as exc:
        raise InputError(
            f"cannot write the result to stdout: {exc.strerror or exc}; free some space, or "
            "give -o PATH"
        ) from None


def write_together(writers: Sequence[Extra]) -> None:
    """Write every ``(option, path, writer)`` all or none, then say which were written.

    Raises
    ------
    InputError
        A file that cannot be written, naming its option, its path and the fix; no file of
        ``writers`` is then written.
    """
    options = {os.fspath(path): option for option, path, _ in writers}
    current = ("", "")
    try:
        with together():
            for option, path, write in writers:
                current = (option, path)
                write()
            current = ("", "")
    except OSError as exc:
        path = os.fspath(exc.filename) if exc.filename else current[1]
        raise write_error(path, options.get(path, current[0]), exc) from None
    except InputError as exc:  # a writer's own message (a mesh format, a case value)
        if current[0] and current[0] not in str(exc):
            raise InputError(f"{exc} ({current[0]})") from None
        raise
    for _, path, _ in writers:
        print(f"wrote {path}", file=sys.stderr)


def write_error(path: str, option: str, exc: OSError) -> InputError:
    """The error for an output that cannot be written: its path (never a temporary file's),
    its option, the reason and the fix."""
    fixes = {
        errno.EACCES: "give a path in a folder you can write to",
        errno.EPERM: "give a path in a folder you can write to",
        errno.EROFS: "the file system is read-only; give a path on another",
        errno.ENOENT: "create the folder first, or give a path in an existing one",
        errno.ENOTDIR: "a part of the path is a file, not a folder; give a path in a folder",
        errno.EISDIR: "it is a folder; give a file name in it",
        errno.ENOSPC: "free some space, or give a path on another disk",
        errno.EDQUOT: "free some space, or give a path on another disk",
        errno.ENAMETOOLONG: "give a shorter name",
    }
    reason = exc.strerror or str(exc)
    fix = fixes.get(exc.errno or 0)
    folder = os.path.dirname(os.path.realpath(path))
    if exc.errno == errno.ENOENT and os.path.isdir(folder):  # /proc, a folder being removed
        fix = f"the folder {printable(folder)!r} takes no new files; give a path in another"
    where = f" ({option})" if option else ""
    return InputError(
        f"cannot write {printable(path)!r}{where}: {reason}" + (f"; {fix}" if fix else "")
    )


def out_path(what: str = "file"):
    """An argparse type for an output path: an empty one is refused, naming the option."""

    def parse(text: str) -> str:
        if not text:
            raise argparse.ArgumentTypeError(f"an empty path; give a {what} name")
        return text

    parse.__name__ = f"{what} path"
    return parse


def check_output(study: Study, save_case: str | None = None, *more: str | None) -> None:
    """Refuse an ``--output``, ``--plot`` or ``--save-case`` (and ``more``: the command's
    other outputs, ``--write-mesh``) that cannot be written, before any work is done:
    see :func:`check_path`; and two outputs that are the same file."""
    given = [
        (option, path)
        for option, path in (
            ("--output", study.output),
            ("--plot", study.plot),
            ("--save-case", save_case),
            *(("--write-mesh", m) for m in more),
        )
        if path is not None
    ]
    for option, path in given:
        check_path(path, study, option)
    check_distinct(given)


def check_distinct(outputs: Sequence[tuple[str, str]]) -> None:
    """Refuse two outputs that are the same file (another spelling, or a link to it)."""
    seen: list[tuple[str, str, str]] = []
    for option, path in outputs:
        real = os.path.realpath(path)
        for other_option, other, other_real in seen:
            same = real == other_real
            if not same and os.path.exists(real) and os.path.exists(other_real):
                same = os.path.samefile(real, other_real)
            if same and not is_device(path):
                raise InputError(
                    f"cannot write {printable(path)!r} ({option}): {other_option} writes the "
                    f"same file ({printable(other)!r}); give each output its own file"
                )
        seen.append((option, path, real))


def _inputs(source: Any) -> list[tuple[str, Path]]:
    """The input files of a study, or of a parsed command line."""
    if isinstance(source, Study):
        source = SimpleNamespace(
            mesh=source.mesh,
            case=source.case_file,
            kinematics=source.kinematics,
            mass_distribution=source.mass_distribution,
            solver_option=source.solver_options,
        )
    return run_inputs(source)


def check_path(out: str, source: Any, option: str = "--output") -> None:
    """Refuse an output path, before any work, that is empty, a folder, in a missing folder
    (or one that is a file), that cannot be written (a read-only folder or file system: a
    temporary file is made and removed beside it), or one of the inputs of ``source`` (a
    study, or a parsed command line)."""
    shown = printable(out)
    if not os.fspath(out):
        raise InputError(f"{option}: an empty path; give a file name")
    target = Path(out)
    if target.is_dir():
        raise InputError(f"cannot write {out!r} ({option}): it is a folder; give a file name in it")
    folder = target.parent if str(target.parent) else Path(".")
    if not folder.is_dir():
        if folder.exists() or any(p.is_file() for p in folder.parents):
            raise InputError(
                f"cannot write {shown!r} ({option}): a part of the path "
                f"{printable(folder)!r} is a file, not a folder; give a path in a folder"
            )
        raise InputError(
            f"cannot write {out!r} ({option}): the folder {str(target.parent)!r} does not "
            "exist; create it first"
        )
    if option == "--plot" and target.suffix.lower() not in FIGURE_FORMATS:
        raise InputError(
            f"cannot write {shown!r} (--plot): a figure is drawn as "
            f"{', '.join(f[1:].upper() for f in FIGURE_FORMATS)} by the file's extension; "
            "name it .png"
        )
    check_not_an_input(out, _inputs(source), option)
    try:
        check_writable(out)
    except OSError as exc:
        raise write_error(os.fspath(out), option, exc) from None


def emit(target: Any, text: str) -> None:
    """Print a command's output, or write it to the ``output`` of ``target`` (a study or a
    parsed command line), completely or not at all."""
    output = getattr(target, "output", None)
    if output:
        check_path(output, target)
        write_together([("--output", output, lambda: write_atomic(output, text))])
    else:
        print_result(text)
