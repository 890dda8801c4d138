"""Studies: one computation described by a :class:`Study` and run by :func:`execute`.

A study is built in Python, from a case file or from the command line, checked once, and
executed into a result object (the hull, and the sections, the force or the history) from
which the tables, CSV, JSON and figures are made::

    >>> import hullslice as hs
    >>> study = hs.Study(
    ...     command="force",
    ...     mesh="meshes/paper_prism.stl",
    ...     mass=1.0,                # kg
    ...     draft=0.0383,            # m
    ...     velocity=-3.4943,        # m/s, negative down
    ...     slices=(16, 32, 64),
    ... )
    >>> result = hs.execute(study)                        # doctest: +SKIP
    >>> result.convergence.richardson.extrapolated        # doctest: +SKIP
    147.9...
    >>> study.command_line()[:2]
    ['force', 'meshes/paper_prism.stl']

The same study as a case file is ``hs.Study.from_case(hs.load_case("paper.toml"),
checked=True)``; ``study.to_case()`` gives the mapping that
:func:`~hullslice.case.write_case` writes.
"""

from __future__ import annotations

from .execute import (
    ForceStudyResult,
    InfoResult,
    SectionsResult,
    SimulationResult,
    StudyResult,
    execute,
    load,
    mesh_options,
    simulation,
)
from .spec import COMMANDS, Study, StudyError

__all__ = [
    "COMMANDS",
    "ForceStudyResult",
    "InfoResult",
    "SectionsResult",
    "SimulationResult",
    "Study",
    "StudyError",
    "StudyResult",
    "execute",
    "load",
    "mesh_options",
    "simulation",
]
