"""Options and helpers shared by the commands."""

from __future__ import annotations

import argparse
import json

from ..constants import RHO_SEA, RHO_WATER
from ..options import option
from ..study import Study

# the argument types, given here with the option helpers
from .argtypes import (  # noqa: F401
    lower,
    number,
    pair,
    positive_int,
    slice_list,
    solver_option,
    times,
)
from .options import add_option, add_options

# the commands' output helpers, given here with the option helpers
from .outputs import (  # noqa: F401
    FIGURE_FORMATS,
    Extra,
    Outcome,
    check_distinct,
    check_extras,
    check_output,
    check_path,
    compute,
    emit,
    finish,
    out_path,
    write_error,
    write_together,
)

#: The text output formats (the rows of ``--format``).
FORMATS = option("format").choices


class UsageError(Exception):
    """A command-line usage error (one line, exit status 2, as argparse's own)."""


def add_solver_options(g: argparse._ArgumentGroup, command: str) -> None:
    """``--solver NAME`` and the repeatable ``--solver-option KEY=VALUE``."""
    add_options(g, command, "solver", "solver_options")


def solver_label(study: Study) -> str:
    """The solver's name with the options given, for table headers."""
    if not study.solver_options:
        return study.solver
    opts = ", ".join(f"{k}={json.dumps(v)}" for k, v in study.solver_options)
    return f"{study.solver} ({opts})"


def add_mesh_options(p: argparse.ArgumentParser, command: str) -> None:
    """The mesh, how to read it, and the mass (its options' rows, in this order)."""
    add_option(p, "mesh", command)
    g = p.add_argument_group("mesh options")
    add_options(g, command, "units", "forward", "up")
    add_shape_options(g, command)
    m = p.add_argument_group("mass")
    add_options(m, command, "mass", "mass_distribution", "cg", "inertia")


def add_shape_options(g, command: str) -> None:
    """``--scale``, ``--length``, ``--repair``, ``--keep`` and ``--keep-box``
    (:mod:`hullslice.prepare`)."""
    add_options(g, command, "scale", "length", "repair", "no_fix", "keep", "keep_box")


def add_section_options(g, command: str) -> None:
    """``--deadrise ESTIMATOR`` and ``--slicing wetted|fixed``."""
    add_options(g, command, "deadrise", "slicing")


def add_pose_options(g, command: str, pitch_rate: bool = True, forward_speed: bool = True) -> None:
    """Pitch (and optionally forward speed and pitch rate) options, in degrees and m/s."""
    add_option(g, "pitch", command)
    if forward_speed:
        add_option(g, "forward_speed", command)
    if pitch_rate:
        add_option(g, "pitch_rate", command)


#: Waters by name, kg/m^3.
WATERS = {"sea": RHO_SEA, "fresh": RHO_WATER}


def water(text: str) -> float:
    """An argparse type: a water by name (:data:`WATERS`) or a density in kg/m^3."""
    key = text.strip().lower()
    if key in WATERS:
        return WATERS[key]
    try:
        return number("kg/m^3")(text)
    except argparse.ArgumentTypeError:
        raise argparse.ArgumentTypeError(
            f"{text!r} is neither sea, fresh nor a density in kg/m^3"
        ) from None


def add_fluid_options(p: argparse.ArgumentParser, command: str) -> None:
    """``--rho``, ``--water`` (a water by name, the same density) and ``--g``."""
    g = p.add_argument_group("water")
    add_option(g, "rho", command)
    g.add_argument(
        "--water",
        dest="rho",
        type=water,
        metavar="sea|fresh",
        help=f"the water by name: sea ({RHO_SEA:g} kg/m^3, for a ditching) or fresh "
        f"({RHO_WATER:g} kg/m^3), or a density in kg/m^3",
    )
    add_option(g, "g", command)


def add_output_options(p: argparse.ArgumentParser, command: str, plot: str = "") -> None:
    """``--format``, ``-o/--output``, ``--plot`` (drawing ``plot``) and ``--save-case``."""
    g = p.add_argument_group("output")
    add_options(g, command, "format", "output")
    if plot:
        add_option(g, "plot", command, figure=plot)
    g.add_argument(
        "--save-case",
        type=out_path(),
        metavar="PATH.toml",
        help="also write the case this command amounts to, for 'hullslice run' to repeat it",
    )
