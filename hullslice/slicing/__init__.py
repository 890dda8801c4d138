"""The slicing strategies and their result, below the slicing API of :mod:`hullslice.sections`.

:mod:`~hullslice.slicing.record`
    :class:`Sections`, the cut's result: arrays over the wetted pieces.
:mod:`~hullslice.slicing.assemble`
    Stations and wetted properties made into :class:`Sections`.
:mod:`~hullslice.slicing.fixed`
    Fixed slices over the body's length, cut once per pitch and kept (:class:`FixedCut`).
"""

from __future__ import annotations
