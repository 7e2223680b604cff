"""Outline geometry of a contact: free outline pieces, straightness, vertices, lobes.

Helpers of `classify_contact`. Coordinates are taxel indices (x = column, y = row).
"""

from __future__ import annotations

import math

import numpy as np

from taxel.features._fitting import CircleFit, circle_fit_algebraic, dot, line_fit_core

__all__ = [
    "circle_spread",
    "corner_score",
    "free_chains",
    "line_spread",
    "lobes",
    "ramp",
    "sagitta",
    "tolerance",
    "two_arms",
]

# Straight / concentric: the spread of |residual| (both edges of a band sit at the same
# distance from its centre line) under 0.75 taxel or 1.5 % of the length; edge jitter on a
# noisy frame is ~0.3-0.5 taxel.
_SPREAD_TAXELS = 0.75
_SPREAD_RELATIVE = 0.015
# Two straight arms: each holds >= 20 % of the outline; the vertex lies >= 2 taxels off
# the chord between the arms' far ends (less is a straight line at this resolution).
_MIN_ARM = 0.2
_MIN_VERTEX_OFFSET = 2.0
# Free outline pieces shorter than this many taxels are ignored (blur-rounded corners).
_MIN_CHAIN = 6


def ramp(value: float, low: float, high: float) -> float:
    """0 below `low`, 1 above `high`, linear between."""
    return float(min(max((value - low) / (high - low), 0.0), 1.0))


def _spread(residual: np.ndarray) -> float:
    """Spread of |residual|: ~0 for one curve or two parallel/concentric ones."""
    return float(np.std(np.abs(residual)))


def line_spread(x: np.ndarray, y: np.ndarray) -> tuple[float, float]:
    """Band-aware spread about the best line, and the points' length along it."""
    fit = line_fit_core(x, y)
    cosine, sine = math.cos(fit.angle_rad), math.sin(fit.angle_rad)
    residual = -sine * x + cosine * y - fit.offset_m
    return _spread(residual), float(np.ptp(cosine * x + sine * y))


def circle_spread(x: np.ndarray, y: np.ndarray) -> tuple[float, CircleFit]:
    """Band-aware spread about the best circle, and the circle."""
    fit = circle_fit_algebraic(x, y)
    if not math.isfinite(fit.radius_m):
        return math.inf, fit
    residual = np.hypot(x - fit.center_m[0], y - fit.center_m[1]) - fit.radius_m
    return _spread(residual), fit


def tolerance(length: float) -> float:
    """Largest spread [taxels] of a straight or circular outline of `length` taxels."""
    return max(_SPREAD_TAXELS, _SPREAD_RELATIVE * length)


def sagitta(radius: float, chord: float) -> float:
    """How far an arc of `radius` bows over a `chord` (both in the same unit)."""
    if not math.isfinite(radius):
        return 0.0
    half = chord / 2
    return radius if half >= radius else radius - math.sqrt(radius**2 - half**2)


def two_arms(x: np.ndarray, y: np.ndarray) -> tuple[float, float]:
    """Fit two straight arms meeting at a vertex: (worst arm spread, interior angle).

    The arms' far ends are the point farthest from the centroid and the point farthest
    from that one; the vertex is the point farthest from the chord between them.
    """
    far_a = int(np.argmax((x - x.mean()) ** 2 + (y - y.mean()) ** 2))
    far_b = int(np.argmax((x - x[far_a]) ** 2 + (y - y[far_a]) ** 2))
    ax, ay, bx, by = x[far_a], y[far_a], x[far_b], y[far_b]
    chord = math.hypot(bx - ax, by - ay)
    if chord == 0:
        return math.inf, math.pi
    off = np.abs((bx - ax) * (ay - y) - (ax - x) * (by - ay)) / chord
    vertex = int(np.argmax(off))
    if off[vertex] < _MIN_VERTEX_OFFSET:
        return math.inf, math.pi
    vx, vy = x[vertex], y[vertex]
    # each point joins the arm whose segment it lies nearer to
    distances = []
    for ex, ey in ((ax, ay), (bx, by)):
        length_sq = max((ex - vx) ** 2 + (ey - vy) ** 2, 1e-12)
        t = np.clip(((x - vx) * (ex - vx) + (y - vy) * (ey - vy)) / length_sq, 0, 1)
        distances.append(np.hypot(x - vx - t * (ex - vx), y - vy - t * (ey - vy)))
    first = distances[0] <= distances[1]
    smaller = min(int(first.sum()), int((~first).sum()))
    if smaller < _MIN_ARM * x.size or smaller < 3:
        return math.inf, math.pi
    worst = max(line_spread(x[first], y[first])[0], line_spread(x[~first], y[~first])[0])
    arm_a = math.atan2(ay - vy, ax - vx)
    arm_b = math.atan2(by - vy, bx - vx)
    angle = abs((arm_a - arm_b + math.pi) % (2 * math.pi) - math.pi)
    return worst, angle


def corner_score(best_single: float, arms: tuple[float, float]) -> float:
    """Evidence in [0, 1] that an outline is two straight arms rather than one curve."""
    spread, angle = arms
    if not math.isfinite(spread):
        return 0.0
    ratio = best_single / max(spread, 0.1)
    return ramp(ratio, 1.5, 3.0) * ramp(math.pi - angle, math.radians(15), math.radians(35))


def free_chains(
    contours: list[np.ndarray],
    shape: tuple[int, int],
    explained: np.ndarray,
    margin: int = 1,
) -> list[tuple[np.ndarray, np.ndarray]]:
    """Open pieces of the contacts' outlines, as (cols, rows) taxel arrays.

    A *free* outline taxel is neither within `margin` taxels of the array's border (the
    object continues there, and a pad presses less toward its own free edge, which draws
    an outline along the border that no object made) nor on the wall of a hole or slot.
    Closed outlines (a contact wholly inside the array) return nothing: they outline a
    finite face or tip, not an edge crossing the array.
    """
    rows, cols = shape
    low, high_x, high_y = margin, cols - 1 - margin, rows - 1 - margin
    chains = []
    for contour in contours:
        if contour.shape[0] < _MIN_CHAIN:
            continue
        x, y = contour[:, 0, 0], contour[:, 0, 1]
        free = (x >= low) & (x <= high_x) & (y >= low) & (y <= high_y) & (explained[y, x] == 0)
        if free.all() or not free.any():
            continue
        start = int(np.argmin(free))  # begin on a taxel that is not free
        free, x, y = np.roll(free, -start), np.roll(x, -start), np.roll(y, -start)
        steps = np.diff(np.concatenate(([0], free.view(np.int8), [0])))
        for begin, end in zip(
            np.flatnonzero(steps == 1), np.flatnonzero(steps == -1), strict=True
        ):
            if end - begin >= _MIN_CHAIN:
                chains.append((x[begin:end].astype(float), y[begin:end].astype(float)))
    return chains


def lobes(contour: np.ndarray, centre: tuple[float, float], order: int) -> float:
    """Relative amplitude of the `order`-th angular harmonic of a closed outline's radius.

    The outline's points (x, y), evenly spaced along it, are seen from `centre` (x, y) at
    angle t and radius r; the result is |sum r exp(-i order t)| / sum r: 0 for a circle
    or an ellipse at order 3, 0.42 for a sharp equilateral triangle at order 3 (its three
    vertices), 0.21 for a square at order 4.
    """
    x = contour[:, 0, 0] - centre[0]
    y = contour[:, 0, 1] - centre[1]
    radius = np.hypot(x, y)
    total = float(radius.sum())
    if total <= 0:
        return 0.0
    angle = order * np.arctan2(y, x)
    return math.hypot(dot(radius, np.cos(angle)), dot(radius, np.sin(angle))) / total
