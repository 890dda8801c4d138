"""Collecting a run's instants into its :class:`~hullslice.motion.history.History`, and
applying the stop rules as they come."""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping

import numpy as np

from ..errors import InputError
from ..forces import CHINE_REASON, MIN_SLENDERNESS, ForceResult
from ..loads import SectionRecord
from .history import (
    MAX_FLAGGED_SHARE,
    OUTSIDE,
    SETTLE_ACCELERATION,
    SETTLE_PITCH_RATE,
    SETTLE_VELOCITY,
    SETTLE_WINDOW,
    STOP_RULES,
    History,
    _check_rules,
    check_share,
)

__all__ = ["Recorder"]


class Recorder:
    """Collects the instants of a run and applies the stop rules."""

    def __init__(
        self,
        stop_on: Iterable[str],
        max_flagged_share: float = MAX_FLAGGED_SHARE,
        sections_every: int = 0,
    ) -> None:
        self.stop_on = _check_rules(stop_on)
        self.max_flagged_share = check_share(max_flagged_share)
        self.rows: list[dict] = []
        self.first: dict[str, float | None] = dict.fromkeys(STOP_RULES)
        self.stop: str | None = None
        self.touched = False
        self._still_since: float | None = None
        self.every = check_every(sections_every)
        self.kept: list[SectionRecord] = []
        self._last: tuple[float, ForceResult] | None = None

    def add(
        self,
        t: float,
        r: ForceResult,
        acceleration: float,
        draft: float | None = None,
        outside: Mapping[str, float] | None = None,
    ) -> bool:
        """Record an instant; True when a stop rule ends the run here. ``draft`` is the
        body's own when the force was computed at a draft clipped to its height;
        ``outside`` the air's forces and the friction (zero by default)."""
        share = _valid_share(r)
        slender = r.slenderness
        texts = set(r.loads.reason.tolist())  # a few texts, each over many slices
        reasons = sorted({part for text in texts if text for part in text.split("; ")})
        w = r.motion.velocity
        s = r.sections
        wet = s.penetration > 0
        wetted = bool(wet.any())
        self.touched = self.touched or wetted
        crossed = {
            "velocity": w >= 0.0 and r.motion.forward_speed == 0.0,
            "left": self.touched and not wetted and w > 0.0,
            "settled": self._settled(t, wetted, w, r.motion.pitch_rate, acceleration),
            # flagged by hullslice where the solver does not model the separation at the
            # chine (a flag for another reason, e.g. a float wholly under water, is not it)
            "chine": CHINE_REASON in reasons,
            "validity": 1.0 - share > self.max_flagged_share,
            "slender": slender < MIN_SLENDERNESS,
        }
        if wetted:
            fp = (float((s.x - s.dx / 2)[wet].min()), float((s.x + s.dx / 2)[wet].max()))
        else:
            fp = (math.nan, math.nan)
        self.rows.append(
            {
                "t": t,
                "draft": r.pose.draft if draft is None else draft,
                "velocity": w,
                "acceleration": acceleration,
                "force": r.total,
                "pitch": r.pose.pitch,
                "pitch_rate": r.motion.pitch_rate,
                "forward_speed": r.motion.forward_speed,
                "force_x": r.total_x,
                "moment": r.moment,
                "wetted_length": s.wetted_length,
                "slices": int(np.count_nonzero(np.bincount(s.station[wet]))),  # distinct
                "valid": r.all_valid,
                "valid_share": share,
                "chine_wetted": bool(s.chine_wetted.any()),
                "reason": "; ".join(reasons),
                "footprint": fp,
                "added_mass": r.added_mass,
                "slenderness": slender,
                "suction_share": _suction_share(r),
                **dict.fromkeys(OUTSIDE, 0.0),
                **(outside or {}),
            }
        )
        if self.every:
            if (len(self.rows) - 1) % self.every == 0:
                self.kept.append(SectionRecord.of(t, r))
                self._last = None
            else:
                self._last = (t, r)
        for rule, hit in crossed.items():
            if hit and self.first[rule] is None:
                self.first[rule] = t
            if hit and rule in self.stop_on and self.stop is None:
                self.stop = rule
        return self.stop is not None

    def _settled(self, t: float, wetted: bool, w: float, q: float, a: float) -> bool:
        """Whether the body has been wetted and still (:data:`SETTLE_VELOCITY`,
        :data:`SETTLE_PITCH_RATE`, :data:`SETTLE_ACCELERATION`) for :data:`SETTLE_WINDOW`."""
        still = (
            wetted
            and abs(w) <= SETTLE_VELOCITY
            and abs(q) <= SETTLE_PITCH_RATE
            and abs(a) <= SETTLE_ACCELERATION
        )
        if not still:
            self._still_since = None
        elif self._still_since is None:
            self._still_since = t
        return self._still_since is not None and t - self._still_since >= SETTLE_WINDOW

    def end(self, rule: str, t: float) -> None:
        """End the run here by ``rule`` (a limit the run cannot go past)."""
        self.first[rule] = t if self.first[rule] is None else self.first[rule]
        self.stop = self.stop or rule

    def history(self, end: str, mode: str, settings: dict) -> History:
        def col(name, dtype):
            return np.array([row[name] for row in self.rows], dtype=dtype)

        dtypes = {"slices": int, "valid": bool, "chine_wetted": bool, "reason": object}
        arrays = {name: col(name, dtypes.get(name, float)) for name in History.ARRAYS}
        arrays["footprint"] = arrays["footprint"].reshape(-1, 2)
        if self._last is not None:  # the last instant is always kept
            self.kept.append(SectionRecord.of(*self._last))
            self._last = None
        return History(
            **arrays,
            stop_reason=self.stop or end,
            first_crossed=dict(self.first),
            mode=mode,
            settings=settings,
            sections=tuple(self.kept),
        )


def _valid_share(r: ForceResult) -> float:
    """Share of the slices' absolute forces carried by valid slices (1 with no force)."""
    size = np.abs(r.force)
    total = size.sum()
    return float(size[r.loads.valid].sum() / total) if total > 0 else 1.0


def _suction_share(r: ForceResult) -> float:
    """Share of the wetted length whose force per metre is held at the water's suction
    bound (a momentum-form solver's ``suction_limited``; 0 for the others)."""
    limited = r.loads.diagnostics.get("suction_limited")
    if limited is None:
        return 0.0
    s = r.sections
    wet = s.penetration > 0
    length = float(s.dx[wet].sum())
    if length <= 0.0:
        return 0.0
    return float(s.dx[wet & (np.asarray(limited) > 0)].sum() / length)


def check_every(every: int) -> int:
    """A ``sections_every`` checked: a whole number >= 0 (0 keeps none)."""
    if isinstance(every, bool) or not isinstance(every, (int, np.integer)) or every < 0:
        raise InputError(
            f"sections_every={every!r} is not a whole number >= 0: give N to keep every Nth "
            "instant's sections (with the last), or 0 for none"
        )
    return int(every)
