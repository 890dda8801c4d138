"""The command line's argument types: each reads one option's text, or says in one line
what is wrong with it (an ``argparse.ArgumentTypeError``, the usage error of exit
status 2)."""

from __future__ import annotations

import argparse
import json
import math
from typing import Any

from ..safety import non_finite


def positive_int(text: str) -> int:
    try:
        n = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a whole number") from None
    if n < 1:
        raise argparse.ArgumentTypeError(f"{text!r} is not positive (give 1 or more)")
    return n


def slice_list(text: str) -> list[int]:
    """``"16,32,64"`` to ``[16, 32, 64]``."""
    parts = [p.strip() for p in text.split(",") if p.strip()]
    if not parts:
        raise argparse.ArgumentTypeError("give one or more slice counts, e.g. 16,32,64")
    out = [positive_int(p) for p in parts]
    if len(set(out)) != len(out):
        raise argparse.ArgumentTypeError(f"slice counts {text!r} repeat a value")
    return out


def number(unit: str):
    def parse(text: str) -> float:
        try:
            return float(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{text!r} is not a number (in {unit})") from None

    parse.__name__ = f"number in {unit}"
    return parse


def lower(text: str) -> str:
    """A case-insensitive choice: ``MM`` is ``mm``."""
    return text.strip().lower()


def solver_option(text: str) -> tuple[str, Any]:
    """``"KEY=VALUE"`` to ``(KEY, value)``, the value read as JSON when it parses, else text.

    ``rho=1025`` gives the number 1025, ``a_coeffs=[0, -3000]`` a list, ``pile_up=wagner``
    and ``table=curves.csv`` the text as it is.
    """
    key, sep, value = text.partition("=")
    key = key.strip()
    if not sep or not key:
        raise argparse.ArgumentTypeError(
            f"{text!r} is not KEY=VALUE (e.g. --solver-option pile_up=wagner)"
        )
    try:
        parsed = json.loads(value)
    except json.JSONDecodeError:
        return key, value
    bad = non_finite(parsed)
    if bad is not None:  # NaN would pass every comparison's test: a check switched off
        raise argparse.ArgumentTypeError(
            f"{text!r}: {bad!r} is not a finite number; give a finite value"
        )
    return key, parsed


def pair(unit: str):
    def parse(text: str) -> tuple[float, float]:
        parts = text.split(",")
        try:
            if len(parts) != 2:
                raise ValueError
            return float(parts[0]), float(parts[1])
        except ValueError:
            raise argparse.ArgumentTypeError(
                f"{text!r} is not two numbers X,Z (in {unit}), e.g. 16.5,1.2"
            ) from None

    parse.__name__ = f"pair in {unit}"
    return parse


def times(text: str) -> list[float]:
    """``"0.01,0.02"`` to ``[0.01, 0.02]`` (s)."""
    parts = [p.strip() for p in text.split(",") if p.strip()]
    if not parts:
        raise argparse.ArgumentTypeError("give one or more times in s, e.g. --at 0.01,0.02")
    out = []
    for part in parts:
        try:
            t = float(part)
        except ValueError:
            raise argparse.ArgumentTypeError(
                f"{part!r} is not a time in s (give e.g. --at 0.01,0.02)"
            ) from None
        if not math.isfinite(t):
            raise argparse.ArgumentTypeError(f"{part!r} is not a finite time in s")
        out.append(t)
    return out
