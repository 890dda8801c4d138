"""The optional extras of the package, and the one-line hint that names what to install.

hullslice needs numpy, scipy and manifold3d; the rest is optional, by extra (see
``pyproject.toml``): :data:`EXTRAS` lists the modules of each. :func:`need` imports one, or
raises a :class:`~hullslice.errors.MissingDependencyError` whose one line says which extra
to install. The command line calls it for everything a command will need before it does
any work (a figure, an output format, a repair, a cluster), so that a run is never lost to
a missing library at its end.
"""

from __future__ import annotations

import importlib
from types import ModuleType

from .errors import MissingDependencyError

__all__ = ["EXTRAS", "need"]

#: The modules each extra brings, by the extra's name (``pip install 'hullslice[NAME]'``).
EXTRAS: dict[str, tuple[str, ...]] = {
    "plot": ("matplotlib",),
    "repair": ("pymeshfix",),
    "formats": ("trimesh", "lxml", "networkx", "meshio"),
    "sweep": ("dask", "distributed", "xarray", "h5netcdf", "h5py", "zarr", "pyarrow"),
}


def need(extra: str, module: str, what: str) -> ModuleType:
    """Import ``module`` of the extra ``extra``, or say in one line what to install.

    Parameters
    ----------
    extra : str
        The extra that brings the module: a key of :data:`EXTRAS`.
    module : str
        The module to import.
    what : str
        What needs it, the start of the message: ``"--plot"``, ``"reading PLY files"``.

    Returns
    -------
    module
        The module imported.

    Raises
    ------
    MissingDependencyError
        ``module`` cannot be imported: ``"{what} needs {module}: pip install
        'hullslice[{extra}]' (or pip install {module})"``.
    """
    if module.split(".")[0] not in EXTRAS[extra]:
        raise KeyError(f"{module} is not a module of the extra {extra!r}")
    try:
        return importlib.import_module(module)
    except ImportError:
        raise MissingDependencyError(
            f"{what} needs {module}: pip install 'hullslice[{extra}]' (or pip install "
            f"{module.split('.')[0]})"
        ) from None
