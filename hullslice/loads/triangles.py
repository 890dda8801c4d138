"""Plane triangles for the load mapping: cut at vertical lines, and the mean of a linear
field's positive part."""

from __future__ import annotations

import numpy as np

__all__ = ["clip", "mean_positive", "split"]


def split(x: np.ndarray, y: np.ndarray, parent: np.ndarray, lines: np.ndarray):
    """Triangles ``(x, y)`` cut at every ``x = line`` they cross (``lines`` sorted), so
    that each piece lies between two neighbouring lines: each round cuts the triangles
    that cross a line at the first line they cross."""
    out = []
    while len(x):
        first = np.searchsorted(lines, x.min(axis=1), side="right")  # first line above
        last = np.searchsorted(lines, x.max(axis=1), side="left")  # lines below the top
        cross = last > first
        out.append((x[~cross], y[~cross], parent[~cross]))
        if not cross.any():
            break
        x, y, parent = x[cross], y[cross], parent[cross]
        at = lines[first[cross]]
        out.append(clip(x, y, parent, at, below=True))  # crosses no line
        x, y, parent = clip(x, y, parent, at, below=False)
    return (
        np.concatenate([o[0] for o in out]).reshape(-1, 3),
        np.concatenate([o[1] for o in out]).reshape(-1, 3),
        np.concatenate([o[2] for o in out]),
    )


def clip(x: np.ndarray, y: np.ndarray, parent: np.ndarray, bound, below: bool):
    """Triangles ``(x, y)`` (p, 3) cut to the side ``x <= bound`` (``below``) or
    ``x >= bound`` (a number, or one per triangle): the triangles inside, and the pieces
    (one or two triangles) of those that cross, with their ``parent``."""
    bounds = np.broadcast_to(np.asarray(bound, dtype=np.float64), (len(x),))
    inside = (x <= bounds[:, None]) if below else (x >= bounds[:, None])
    count = inside.sum(axis=1)
    keep = count == 3
    out = [(x[keep], y[keep], parent[keep])]
    for k in (1, 2):  # one corner inside: a triangle; two: a quadrilateral, two triangles
        rows = np.nonzero(count == k)[0]
        if not len(rows):
            continue
        # roll each row so that its lone corner (inside for k = 1, outside for 2) is first
        lone = inside[rows] if k == 1 else ~inside[rows]
        shift = np.argmax(lone, axis=1)
        order = (shift[:, None] + np.arange(3)) % 3
        xr = np.take_along_axis(x[rows], order, axis=1)
        yr = np.take_along_axis(y[rows], order, axis=1)
        b = bounds[rows]
        t1 = (b - xr[:, 0]) / (xr[:, 1] - xr[:, 0])
        t2 = (b - xr[:, 0]) / (xr[:, 2] - xr[:, 0])
        p1 = (b, yr[:, 0] + t1 * (yr[:, 1] - yr[:, 0]))
        p2 = (b, yr[:, 0] + t2 * (yr[:, 2] - yr[:, 0]))
        if k == 1:
            tris = [((xr[:, 0], p1[0], p2[0]), (yr[:, 0], p1[1], p2[1]))]
        else:
            tris = [
                ((p1[0], xr[:, 1], xr[:, 2]), (p1[1], yr[:, 1], yr[:, 2])),
                ((p1[0], xr[:, 2], p2[0]), (p1[1], yr[:, 2], p2[1])),
            ]
        for tx, ty in tris:
            out.append((np.stack(tx, axis=1), np.stack(ty, axis=1), parent[rows]))
    return (
        np.concatenate([o[0] for o in out]).reshape(-1, 3),
        np.concatenate([o[1] for o in out]).reshape(-1, 3),
        np.concatenate([o[2] for o in out]),
    )


def mean_positive(d: np.ndarray) -> np.ndarray:
    """(m,) the mean of ``max(d, 0)`` over each plane triangle whose corners have the
    values ``d`` (m, 3) (a linear field), exactly."""
    s = -np.sort(-d, axis=1)  # descending
    a, b, c = s[:, 0], s[:, 1], s[:, 2]
    with np.errstate(invalid="ignore", divide="ignore"):
        one = a**3 / (3.0 * (a - b) * (a - c))
        two = (a + b + c) / 3.0 - c**3 / (3.0 * (a - c) * (b - c))
    out = np.where(c >= 0, (a + b + c) / 3.0, 0.0)
    out = np.where((b <= 0) & (a > 0), np.nan_to_num(one), out)
    out = np.where((c < 0) & (b > 0), np.nan_to_num(two), out)
    return out
