"""Labelled results: histories, force results and sections as xarray Datasets and pandas
DataFrames with units, and Datasets written to netCDF, Zarr or Parquet.

xarray and pandas are the optional extra ``hullslice[sweep]``; importing this module does not
need them, converting does (a :class:`~hullslice.errors.MissingDependencyError` says what to
install). Units are CF/UDUNITS strings (``m s-1``) in each variable's ``units`` attribute
(``DataFrame.attrs["units"]`` for a DataFrame), with a ``long_name``.
"""

from __future__ import annotations

import io
import json
import math
import os
import shutil
import tempfile
from pathlib import Path
from typing import Any

import numpy as np

from .errors import InputError, MissingDependencyError
from .extras import need

__all__ = [
    "OUTPUT_FORMATS",
    "UNITS",
    "attrs_for",
    "force_to_dataframe",
    "force_to_xarray",
    "history_to_dataframe",
    "history_to_xarray",
    "output_format",
    "require_output",
    "sections_to_dataframe",
    "sections_to_xarray",
    "write_dataset",
]

#: Units (CF) and long names of the quantities hullslice reports, by column name.
UNITS: dict[str, tuple[str, str]] = {
    # histories
    "t": ("s", "time since the start of the run"),
    "draft": ("m", "draft of the lowest point below the calm water"),
    "velocity": ("m s-1", "vertical velocity, negative down"),
    "acceleration": ("m s-2", "vertical acceleration of the centre of gravity, positive up"),
    "force": ("N", "vertical 2D+t force, positive up"),
    "pitch_deg": ("degree", "pitch angle, positive nose up"),
    "pitch_rate_deg_s": ("degree s-1", "pitch rate, positive nose up"),
    "forward_speed": ("m s-1", "forward speed"),
    "force_x": ("N", "horizontal force, positive forward"),
    "moment": ("N m", "pitch moment about the centre of gravity, positive nose up"),
    "wetted_length": ("m", "length of the wetted part"),
    "x_aft": ("m", "earth X of the aft end of the wetted part"),
    "x_fore": ("m", "earth X of the fore end of the wetted part"),
    "slices": ("1", "number of wetted slices"),
    "valid": ("", "every slice inside the method's range of validity"),
    "valid_share": ("1", "share of the force carried by valid slices"),
    "flagged_share": ("1", "share of the force carried by flagged slices"),
    "added_mass": ("kg", "heave added mass of a momentum-form solver"),
    "slenderness": ("1", "wetted length over wetted beam"),
    "suction_share": ("1", "share of the wetted length held at the water's suction bound"),
    "air_force": ("N", "vertical force of the air on the body, positive up"),
    "air_force_x": ("N", "horizontal force of the air on the body, positive forward"),
    "air_moment": ("N m", "pitch moment of the air about the centre of gravity, nose up"),
    "friction": ("N", "friction of the water on the wetted surface, positive forward"),
    "chine_wetted": ("", "the water reached a section's chine"),
    "reason": ("", "why the instant or slice is not valid"),
    # sections and force results
    "station": ("1", "index of the slice"),
    "x": ("m", "earth X of the station"),
    "dx": ("m", "slice thickness"),
    "half_beam": ("m", "half-width of the wetted section at the waterline"),
    "half_beam_port": ("m", "port half-width at the waterline"),
    "half_beam_stbd": ("m", "starboard half-width at the waterline"),
    "deadrise": ("radian", "local deadrise angle"),
    "deadrise_port": ("radian", "port deadrise angle"),
    "deadrise_stbd": ("radian", "starboard deadrise angle"),
    "deadrise_deg": ("degree", "local deadrise angle"),
    "deadrise_port_deg": ("degree", "port deadrise angle"),
    "deadrise_stbd_deg": ("degree", "starboard deadrise angle"),
    "area": ("m2", "area of the station's cross-section"),
    "mass_per_metre": ("kg m-1", "mass per metre of the wetted piece"),
    "keel_slope": ("1", "slope dZ/dX of the keel line over the slice"),
    "keel_z": ("m", "earth Z of the keel"),
    "y_keel": ("m", "earth Y of the keel"),
    "part_half_beam": ("m", "half-width of the section's part at the waterline"),
    "force_per_metre": ("N m-1", "vertical force per metre of body length, positive up"),
}

#: Output formats of a dataset, by file extension.
OUTPUT_FORMATS = {".nc": "netCDF", ".zarr": "Zarr", ".parquet": "Parquet"}


def _xarray():
    return need("sweep", "xarray", "a labelled result")


def attrs_for(name: str) -> dict[str, str]:
    """The ``units`` and ``long_name`` of a quantity named ``name`` (none for text and
    flags; an unknown name ending in ``_deg`` or ``_deg_s`` is in degree or degree s-1)."""
    if name in UNITS:
        units, long_name = UNITS[name]
    elif name.endswith("_deg_s"):
        units, long_name = "degree s-1", name.replace("_", " ")
    elif name.endswith("_deg"):
        units, long_name = "degree", name.replace("_", " ")
    else:
        return {"long_name": name.replace("_", " ")}
    return {"units": units, "long_name": long_name} if units else {"long_name": long_name}


def _attr_value(value: Any) -> Any:
    """An attribute value netCDF and Zarr can hold: numbers and text as they are, anything
    else as JSON text."""
    if isinstance(value, bool):
        return int(value)
    if isinstance(value, int | float | str | np.integer | np.floating):
        return value
    return json.dumps(value, default=str)


def _variable(name: str, values: np.ndarray, dim: str):
    arr = np.asarray(values)
    if arr.dtype == object:
        arr = arr.astype(str)
    return (dim, arr, attrs_for(name))


def history_to_xarray(history):
    """A :class:`~hullslice.motion.History` as an ``xarray.Dataset`` along ``t`` (s).

    Every column of ``history.columns()`` is a variable with its units; the run's mode,
    stop reason, the first crossing of each limit (s, NaN for never) and its settings (JSON)
    are attributes.
    """
    xr = _xarray()
    cols = history.columns()
    t = np.asarray(cols.pop("t"), dtype=np.float64)
    ds = xr.Dataset(
        {name: _variable(name, values, "t") for name, values in cols.items()},
        coords={"t": ("t", t, attrs_for("t"))},
    )
    ds.attrs.update(
        {
            "mode": history.mode,
            "stop_reason": history.stop_reason,
            **{
                f"first_crossed_{rule}": math.nan if when is None else float(when)
                for rule, when in history.first_crossed.items()
            },
            "settings": _attr_value(dict(history.settings)),
        }
    )
    return ds


def history_to_dataframe(history):
    """A :class:`~hullslice.motion.History` as a ``pandas.DataFrame`` indexed by ``t`` (s);
    ``attrs["units"]`` maps each column to its unit."""
    return _dataframe(history_to_xarray(history))


def sections_to_xarray(sections):
    """:class:`~hullslice.sections.Sections` as an ``xarray.Dataset`` along ``entry`` (a
    wetted piece of a slice), one variable per array with its units; the pose is in the
    attributes (the polygons are left out)."""
    xr = _xarray()
    ds = xr.Dataset(
        {name: _variable(name, v, "entry") for name, v in sections.as_dict().items()},
        coords={"entry": np.arange(len(sections))},
    )
    ds.attrs.update(
        {
            "deadrise_method": sections.deadrise_method,
            "draft_m": float(sections.draft),
            "pitch_deg": math.degrees(sections.pitch),
            "wetted_length_m": float(sections.wetted_length),
        }
    )
    return ds


def sections_to_dataframe(sections):
    """:class:`~hullslice.sections.Sections` as a ``pandas.DataFrame``, one row per entry."""
    return _dataframe(sections_to_xarray(sections))


def force_to_xarray(result):
    """A :class:`~hullslice.forces.ForceResult` as an ``xarray.Dataset`` along ``entry``:
    every per-slice column (the solver's diagnostics included) with its units, the totals
    (N, N m), the solver and the state in the attributes."""
    xr = _xarray()
    ds = xr.Dataset(
        {name: _variable(name, v, "entry") for name, v in result.columns().items()},
        coords={"entry": np.arange(len(result))},
    )
    ds.attrs.update(
        {
            "solver": result.solver,
            "total_force_N": result.total,
            "total_force_x_N": result.total_x,
            "moment_N_m": result.moment,
            "draft_m": float(result.pose.draft),
            "pitch_deg": math.degrees(result.pose.pitch),
            "velocity_m_s": float(result.motion.velocity),
            "forward_speed_m_s": float(result.motion.forward_speed),
            "pitch_rate_deg_s": math.degrees(result.motion.pitch_rate),
            "rho_kg_m3": float(result.fluid.rho),
            "g_m_s2": float(result.fluid.g),
        }
    )
    return ds


def force_to_dataframe(result):
    """A :class:`~hullslice.forces.ForceResult` as a ``pandas.DataFrame``, one row per
    slice entry."""
    return _dataframe(force_to_xarray(result))


def _dataframe(ds):
    df = ds.to_dataframe()
    df.attrs = {
        **ds.attrs,
        "units": {k: v.attrs["units"] for k, v in ds.variables.items() if "units" in v.attrs},
    }
    return df


# -- files -----------------------------------------------------------------------------------


def output_format(path: str | os.PathLike) -> str:
    """The extension of a dataset's output file (``.nc``, ``.zarr`` or ``.parquet``), or an
    InputError that names the path and the extensions there are."""
    ext = Path(path).suffix.lower()
    if ext not in OUTPUT_FORMATS:
        choices = ", ".join(f"{e} ({n})" for e, n in OUTPUT_FORMATS.items())
        raise InputError(
            f"cannot write {str(path)!r}: a sweep's results are written as {choices}; "
            "give one of these extensions"
        )
    return ext


#: The libraries each output format needs besides xarray, by extension.
_FORMAT_NEEDS = {".nc": "h5netcdf", ".zarr": "zarr", ".parquet": "pyarrow"}


def require_output(path: str | os.PathLike) -> str:
    """Check, before any work, that a dataset can be written to ``path``: its extension
    (:func:`output_format`), and xarray and the format's library installed. Returns the
    extension.

    Raises
    ------
    InputError
        An extension that is not one of :data:`OUTPUT_FORMATS`.
    MissingDependencyError
        xarray or the format's library is not installed: the message names what to install.
    """
    ext = output_format(path)
    _xarray()
    need("sweep", _FORMAT_NEEDS[ext], f"{OUTPUT_FORMATS[ext]} output")
    return ext


def write_dataset(ds, path: str | os.PathLike) -> Path:
    """Write a Dataset to ``path`` by its extension, completely or not at all.

    ``.nc``: netCDF-4 (h5netcdf); ``.zarr``: a Zarr store (a folder), written beside the
    target and moved into place; ``.parquet``: one row per point of the dataset's
    dimensions, its attributes and units as JSON in the file's metadata (key ``hullslice``).
    """
    target = Path(path)
    output_format(target)
    try:  # the data is in memory: no Dask scheduler (nor its locks) is wanted for writing
        import dask
    except ImportError:
        return _write(ds, target)
    with dask.config.set(scheduler="synchronous"):
        return _write(ds, target)


def _write(ds, target: Path) -> Path:
    from .atomic import write_atomic

    ext = output_format(target)
    if ext == ".nc":
        need("sweep", "h5netcdf", "netCDF output")
        try:
            data = ds.to_netcdf(engine="h5netcdf")
        except (ImportError, ValueError) as exc:
            if "h5netcdf" not in str(exc) and not isinstance(exc, ImportError):
                raise
            raise MissingDependencyError(
                "netCDF output needs h5netcdf: pip install 'hullslice[sweep]' (or pip install "
                "h5netcdf)"
            ) from None
        return write_atomic(target, bytes(data))
    if ext == ".parquet":
        return write_atomic(target, _parquet_bytes(ds))
    return _write_zarr(ds, target)


def _parquet_bytes(ds) -> bytes:
    pa = need("sweep", "pyarrow", "Parquet output")
    pq = need("sweep", "pyarrow.parquet", "Parquet output")
    df = ds.to_dataframe().reset_index()
    table = pa.Table.from_pandas(df, preserve_index=False)
    meta = {
        "attrs": {k: _attr_value(v) for k, v in ds.attrs.items()},
        "variables": {k: dict(v.attrs) for k, v in ds.variables.items()},
    }
    table = table.replace_schema_metadata(
        {**(table.schema.metadata or {}), b"hullslice": json.dumps(meta, default=str).encode()}
    )
    buf = io.BytesIO()
    pq.write_table(table, buf)
    return buf.getvalue()


def _write_zarr(ds, target: Path) -> Path:
    need("sweep", "zarr", "Zarr output")
    parent = target.parent if str(target.parent) else Path(".")
    tmp = Path(tempfile.mkdtemp(prefix=f".{target.name}.", suffix=".tmp", dir=parent))
    old = None
    try:
        store = tmp / target.name
        ds.to_zarr(store, mode="w", consolidated=False)
        if target.exists():
            old = tmp / "previous"
            os.replace(target, old)
        os.replace(store, target)
    except BaseException:
        if old is not None and old.exists() and not target.exists():
            os.replace(old, target)
        raise
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    return target


def read_dataset(path: str | os.PathLike):
    """Read a dataset written by :func:`write_dataset` (``.nc`` or ``.zarr``) into memory."""
    xr = _xarray()
    ext = output_format(path)
    if ext == ".parquet":
        raise InputError(f"{str(path)!r} is a table: read it with pandas.read_parquet")
    if ext == ".nc":
        with xr.open_dataset(path, engine="h5netcdf") as ds:
            return ds.load()
    with xr.open_zarr(path, consolidated=False) as ds:
        return ds.load()
