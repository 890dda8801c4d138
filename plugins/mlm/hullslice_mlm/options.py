"""The MLM's options checked, each bad value refused in one line that names the option and
the fix."""

from __future__ import annotations

import math
from numbers import Real
from typing import Any

from hullslice import InputError


def _number(
    solver: Any, key: str, lo: float, hi: float, *, open_lo: bool = False, open_hi: bool = False
) -> float:
    value = solver.settings[key]
    ok = isinstance(value, Real) and not isinstance(value, bool)
    v = float(value) if ok else math.nan
    inside = math.isfinite(v) and (v > lo if open_lo else v >= lo)
    inside = inside and (v < hi if open_hi else v <= hi)
    if not inside:
        close = "]" if math.isfinite(hi) and not open_hi else ")"  # finite values only
        span = f"in ({lo:g}, {hi:g}{close}" if open_lo else f"in [{lo:g}, {hi:g}{close}"
        raise InputError(
            f"solver 'mlm': option {key}={value!r} is not a number {span} "
            f"(default {solver.options[key]!r})"
        )
    return v


def check_options(solver: Any, options: dict[str, Any]) -> tuple[float | None, bool]:
    """Check the solver's settings, normalising them in place; the continuation's slope
    (None for ``"tangent"``) and whether it was given."""
    s = solver.settings
    if s["section_method"] not in ("auto", "contour", "wedge"):
        raise InputError(
            f"solver 'mlm': option section_method={s['section_method']!r} is unknown; "
            "choose auto, contour or wedge"
        )
    cont = s["continuation"]
    given = "continuation" in options
    if isinstance(cont, str):
        if cont.strip().lower() != "tangent":
            raise InputError(
                f"solver 'mlm': option continuation={cont!r} is neither 'tangent' nor a "
                "deadrise in degrees (e.g. 57.5)"
            )
        s["continuation"] = "tangent"
        cont_tan = None
    else:
        if cont == 90.0:
            raise InputError(
                f"solver 'mlm': option continuation={cont!r} deg is vertical: the contact "
                "would stop at the edge; give a deadrise below 90 deg, e.g. 60"
            )
        deg = _number(solver, "continuation", 0.0, 90.0, open_lo=True, open_hi=True)
        s["continuation"] = deg
        cont_tan = math.tan(math.radians(deg))
    s["smooth_edge_deg"] = _number(solver, "smooth_edge_deg", 0.0, 90.0, open_lo=True)
    # above zero, as the other solvers ask: zero would flag nothing
    s["froude_min"] = _number(solver, "froude_min", 0.0, math.inf, open_lo=True)
    grav = s["gravity"]
    if isinstance(grav, str) and grav.strip().lower() == "hulin":
        s["gravity"] = "hulin"
    elif not isinstance(grav, bool):
        raise InputError(
            f"solver 'mlm': option gravity={grav!r} is not true, false or 'hulin' (true: the "
            "hydrostatic pressure; 'hulin': with gravity's correction of the contact and its "
            "pressure)"
        )
    return cont_tan, given
