"""Discovery of 2D solvers through the entry-point group ``hullslice.solvers``.

Every solver, the default one included, is found through installed distributions'
entry points. Discovery reads metadata only; a plugin's module is imported when the solver
is first asked for by name or when all solvers are listed. A plugin that fails to import,
is not a :class:`~hullslice.solvers.base.Solver` or
:class:`~hullslice.solvers.base.MomentumFormSolver`, leaves its abstract methods
unimplemented or has no ``name`` is broken: asking for it raises a
:class:`~hullslice.errors.PluginError` naming it and its distribution,
:func:`list_solvers` lists it with the status ``"broken"`` and the error, and the other
solvers keep working. A solver that fails when it is built raises a
:class:`~hullslice.errors.SolverError` naming it and its distribution. When two
distributions register the same name, the one from hullslice itself wins, otherwise the
first by distribution name, and a :class:`~hullslice.errors.PluginWarning` names both.
Setting the environment variable ``HULLSLICE_NO_PLUGINS=1`` loads only the solvers
registered by hullslice itself.
"""

from __future__ import annotations

import functools
import os
import warnings
from collections.abc import Mapping
from dataclasses import dataclass, field
from importlib.metadata import EntryPoint, entry_points
from typing import Any, NoReturn

from ..errors import HullsliceError, PluginError, PluginWarning, SolverError, UnknownSolverError
from ..safety import failure, plugin_code
from .base import SolverBase, did_you_mean

__all__ = [
    "DEFAULT_SOLVER",
    "ENTRY_POINT_GROUP",
    "SolverInfo",
    "get_solver",
    "list_solvers",
    "refresh",
    "solver_names",
]

ENTRY_POINT_GROUP = "hullslice.solvers"
DEFAULT_SOLVER = "extended-von-karman"
NO_PLUGINS_ENV = "HULLSLICE_NO_PLUGINS"
_OWN_DIST = "hullslice"


@dataclass(frozen=True)
class SolverInfo:
    """One registered solver, as ``hullslice solvers`` lists it.

    Attributes
    ----------
    name : str
        Registry name (the entry point's name).
    value : str
        The entry point's target, ``module:Class``.
    distribution : str
        Name of the installed distribution that registers it.
    version : str
        That distribution's version.
    status : str
        ``"ok"``, ``"broken"`` (fails to load), ``"shadowed"`` (another distribution
        registers the same name and wins) or ``"not loaded"`` (not imported yet).
    description : str
        The solver's one-line description (empty until loaded).
    error : str
        Why it is broken or shadowed.
    options : dict
        The solver's options with their defaults (empty until loaded).
    kind : str
        ``"free-fall"`` or ``"momentum"`` (:data:`~hullslice.solvers.base.SOLVER_KINDS`;
        empty until loaded).
    """

    name: str
    value: str
    distribution: str
    version: str
    status: str = "not loaded"
    description: str = ""
    error: str = ""
    options: Mapping[str, Any] = field(default_factory=dict)
    kind: str = ""


def _dist_of(ep: EntryPoint) -> tuple[str, str]:
    dist = getattr(ep, "dist", None)
    if dist is None:
        return "(unknown)", ""
    return str(dist.metadata["Name"] or "(unknown)"), str(dist.version or "")


def _plugins_disabled() -> bool:
    return os.environ.get(NO_PLUGINS_ENV, "").strip().lower() not in ("", "0", "false", "no")


class _Registry:
    """Entry points by name, and the solver classes loaded from them."""

    def __init__(self, eps: list[EntryPoint]) -> None:
        self.winners: dict[str, EntryPoint] = {}
        self.shadowed: list[tuple[EntryPoint, EntryPoint]] = []
        self.classes: dict[str, type[SolverBase]] = {}
        self.broken: dict[str, str] = {}
        by_name: dict[str, list[EntryPoint]] = {}
        for ep in eps:
            if _plugins_disabled() and _dist_of(ep)[0] != _OWN_DIST:
                continue
            by_name.setdefault(ep.name, []).append(ep)
        for name, group in sorted(by_name.items()):
            # the same entry point seen twice (a path listed twice) is one registration
            unique = {(_dist_of(ep)[0], ep.value): ep for ep in group}
            ordered = sorted(
                unique.values(), key=lambda e: (_dist_of(e)[0] != _OWN_DIST, _dist_of(e)[0])
            )
            self.winners[name] = ordered[0]
            for loser in ordered[1:]:
                self.shadowed.append((loser, ordered[0]))
                warnings.warn(
                    f"two solvers are registered as {name!r}: {_describe(ordered[0])} is used, "
                    f"{_describe(loser)} is ignored; uninstall one of them",
                    PluginWarning,
                    stacklevel=4,
                )

    def load(self, name: str) -> type[SolverBase]:
        if name in self.classes:
            return self.classes[name]
        if name in self.broken:
            raise PluginError(self.broken[name])
        ep = self.winners[name]
        try:
            with plugin_code(f"solver plugin {ep.name!r} (loading)"):
                obj = ep.load()
        except (Exception, SystemExit) as exc:  # a plugin's sys.exit() does not end hullslice
            msg = f"solver plugin {_describe(ep)} failed to load: {failure(exc)}"
            return self._broken(name, msg)
        if not (isinstance(obj, type) and issubclass(obj, SolverBase)):
            msg = (
                f"solver plugin {_describe(ep)} does not implement the solver interface: "
                f"{ep.value} is not a subclass of hullslice.Solver or "
                "hullslice.MomentumFormSolver"
            )
            return self._broken(name, msg)
        if getattr(obj, "__abstractmethods__", None):
            missing = ", ".join(sorted(obj.__abstractmethods__))
            msg = f"solver plugin {_describe(ep)} does not implement {missing}"
            return self._broken(name, msg)
        if not (isinstance(obj.name, str) and obj.name):
            msg = (
                f"solver plugin {_describe(ep)} does not set the class variable 'name' "
                "(the name its results are reported under)"
            )
            return self._broken(name, msg)
        self.classes[name] = obj
        return obj

    def _broken(self, name: str, msg: str) -> NoReturn:
        # the error is the report: a warning with the same text would only repeat it
        self.broken[name] = msg
        raise PluginError(msg)

    def distribution(self, name: str) -> str:
        """``name (dist version)`` of the plugin registered as ``name``, for messages."""
        ep = self.winners.get(name)
        return _describe(ep) if ep is not None else repr(name)


def _describe(ep: EntryPoint) -> str:
    dist, version = _dist_of(ep)
    return f"{ep.name!r} ({ep.value}, distribution {dist} {version})".replace(" )", ")")


@functools.cache
def _registry() -> _Registry:
    return _Registry(list(entry_points(group=ENTRY_POINT_GROUP)))


def refresh() -> None:
    """Forget what was discovered, so that newly installed plugins are found."""
    _registry.cache_clear()


def list_solvers() -> list[SolverInfo]:
    """Every registered solver, loaded so that its status is known, sorted by name."""
    reg = _registry()
    out = []
    for name, ep in reg.winners.items():
        dist, version = _dist_of(ep)
        try:
            cls = reg.load(name)
        except PluginError as exc:
            out.append(SolverInfo(name, ep.value, dist, version, "broken", "", str(exc)))
            continue
        out.append(
            SolverInfo(
                name,
                ep.value,
                dist,
                version,
                "ok",
                cls.description,
                options=dict(cls.options),
                kind=cls.kind,
            )
        )
    for loser, winner in reg.shadowed:
        dist, version = _dist_of(loser)
        out.append(
            SolverInfo(
                loser.name,
                loser.value,
                dist,
                version,
                "shadowed",
                "",
                f"the same name is registered by {_describe(winner)}, which is used",
            )
        )
    return sorted(out, key=lambda s: (s.name, s.status != "ok"))


def solver_names() -> list[str]:
    """Names of the registered solvers (without loading them)."""
    return sorted(_registry().winners)


def get_solver(solver: str | type[SolverBase] | SolverBase | None = None, **options) -> SolverBase:
    """A solver instance from a registered name, a solver class, or an instance.

    Parameters
    ----------
    solver : str, SolverBase subclass, SolverBase instance or None
        ``None`` means the default, ``"extended-von-karman"``.
    **options
        Options passed to the solver's constructor (not allowed with an instance).

    Raises
    ------
    UnknownSolverError
        No installed solver has that name; the message lists the installed ones.
    PluginError
        The plugin registered under that name cannot be loaded.
    SolverError
        The solver fails when it is built with these options (other than by refusing an
        option with an :class:`~hullslice.errors.InputError`).
    """
    if solver is None:
        solver = DEFAULT_SOLVER
    if isinstance(solver, SolverBase):
        if options:
            raise TypeError("options cannot be given with a solver instance")
        return solver
    if isinstance(solver, type) and issubclass(solver, SolverBase):
        return _build(solver, options, lambda: _describe_class(solver))
    if not isinstance(solver, str):
        raise TypeError(
            f"solver must be a name, a solver class or a solver instance, not {solver!r}"
        )
    reg = _registry()
    if solver not in reg.winners:
        installed = ", ".join(sorted(reg.winners)) or "none"
        hint = ""
        if _plugins_disabled():
            hint = f" (plugins are off: {NO_PLUGINS_ENV} is set)"
        close = did_you_mean(solver, reg.winners)
        raise UnknownSolverError(
            f"no solver named {solver!r} is installed{hint}; {close}installed solvers: {installed}"
        )
    return _build(reg.load(solver), options, lambda: reg.distribution(solver))


def _build(cls: type[SolverBase], options: dict, who) -> SolverBase:
    """``cls(**options)``; an unexpected exception becomes a SolverError naming the plugin."""
    try:
        with plugin_code(f"solver {getattr(cls, 'name', cls.__name__)!r} (starting)"):
            return cls(**options)
    except HullsliceError:
        raise
    except (Exception, SystemExit) as exc:
        raise SolverError(
            f"solver {who()} failed to start with options {options!r}: {failure(exc)}"
        ) from exc


def describe(solver: SolverBase) -> str:
    """Name, class and distribution of a solver instance, for error messages."""
    reg = _registry()
    for name, cls in reg.classes.items():
        if cls is type(solver):
            return reg.distribution(name)
    return _describe_class(type(solver))


def _describe_class(cls: type) -> str:
    """``'name' (module.Class, distribution D V)`` for a solver class not found by name."""
    name = getattr(cls, "name", "") or cls.__name__
    where = f"{cls.__module__}.{cls.__qualname__}"
    dist = _distribution_of_module(cls.__module__)
    return f"{name!r} ({where}, distribution {dist})" if dist else f"{name!r} ({where})"


def _distribution_of_module(module: str) -> str:
    """``"name version"`` of the distribution whose entry point imports from the same
    top-level package as ``module``, or ``""``."""
    top = module.split(".")[0]
    for ep in _registry().winners.values():
        if ep.value.split(":")[0].split(".")[0] == top:
            dist, version = _dist_of(ep)
            return f"{dist} {version}".strip()
    return ""
