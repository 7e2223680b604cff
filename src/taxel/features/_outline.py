"""Outline geometry of a contact: free outline pieces, straightness, vertices, lobes.

Helpers of `classify_contact`. Coordinates are taxel indices (x = column, y = row).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import cast

import cv2
import numpy as np

from taxel.features._fitting import LineFit, centred, dot, line_through, std, taubin_circle

__all__ = [
    "bends",
    "circle_spread",
    "corner_score",
    "curved",
    "edge_line",
    "free_chains",
    "line_spread",
    "lobes",
    "one_side",
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
# The corner score ramps up as the arms turn from 15 to 35 degrees off a straight line.
_IN_LINE = math.radians(15.0)
_BENT = math.radians(35.0)
# Arms under 60 degrees apart can be misread (the vertex taken for a far end, and an end
# of the outline piece for the vertex, see `two_arms`). The piece's own ends are then
# tried as the far ends, and kept for arms under 70 degrees apart whose worst spread is a
# third of the misread ones' or less: 0.19-0.30 of it on wedges opening 30-55 degrees on
# 32-96 taxel arrays at 0-3 % noise, 0.30-0.86 on rough faces (foam, screens, a slot) of
# the 16 x 16 features benchmark, which only one of them (0.42) misreads so. A band's end
# (a bar's, a finger's) is misread so too, its sides taken for the arms: their halves away
# from the vertex run within 4-7 degrees of parallel (32 x 32 arrays), a wedge's 21-60
_ACUTE = math.radians(70.0)
_MISREAD = 3.0
# A piece that passes as straight is a circle arc when it bows by >= 2 taxels over its
# length (the arc's sagitta, as for a band in `taxel.features._shape`) and a circle fits it
# at least twice as closely as the line: a round face's rim (a washer, a plate's hole
# wall) within a few taxels' radius bows like that, while a short band's clipped end (two
# sides and the cap between them) is fitted by a circle barely better than by its axis.
_ARC_BOW = 2.0
_ARC_CLOSER = 0.5
# A face's edge: at most 10 % of the contact (beyond a taxel of the line) lies on the far
# side of its straight free outline; a band's sides have half of it on each side.
_ONE_SIDE = 0.1
# Free outline pieces shorter than this many taxels are ignored (blur-rounded corners).
_MIN_CHAIN = 6
_ZERO = np.zeros(1, np.int8)


def ramp(value: float, low: float, high: float) -> float:
    """0 below `low`, 1 above `high`, linear between."""
    return float(min(max((value - low) / (high - low), 0.0), 1.0))


def _spread(residual: np.ndarray) -> float:
    """Spread of |residual|: ~0 for one curve or two parallel/concentric ones.

    `residual` (float64, owned by the caller) is overwritten.
    """
    return std(np.abs(residual, out=residual))


Centred = tuple[float, float, float, np.ndarray]  # see `taxel.features._fitting.centred`


def _line_spread(
    x: np.ndarray, y: np.ndarray, points: Centred | None = None
) -> tuple[float, float, float]:
    """Band-aware spread about the best line, and that line's direction (cos, sin).

    `points`: (x, y) as `centred` gives them, if already made.
    """
    angle, offset, _ = line_through(points or centred(x, y))
    cosine, sine = math.cos(angle), math.sin(angle)
    residual = -sine * x
    residual += cosine * y
    residual -= offset
    return _spread(residual), cosine, sine


def line_spread(
    x: np.ndarray, y: np.ndarray, points: Centred | None = None
) -> tuple[float, float]:
    """Band-aware spread about the best line, and the points' length along it.

    `points`: (x, y) as `centred` gives them, if already made.
    """
    spread, cosine, sine = _line_spread(x, y, points)
    along = cosine * x
    along += sine * y
    return spread, float(np.maximum.reduce(along)) - float(np.minimum.reduce(along))


def circle_spread(x: np.ndarray, y: np.ndarray, points: Centred | None = None) -> float:
    """Band-aware spread about the best (Taubin) circle; inf for collinear points.

    `points`: (x, y) as `centred` gives them, if already made (its third row is
    overwritten).
    """
    circle = taubin_circle(x, y, points)
    if circle is None:
        return math.inf
    centre_x, centre_y, radius = circle
    residual = np.hypot(x - centre_x, y - centre_y)
    residual -= radius
    return _spread(residual)


def curved(x: np.ndarray, y: np.ndarray, points: Centred, line: float, extent: float) -> bool:
    """Whether an outline piece within the straight tolerance is a circle arc (see above).

    `points`: (x, y) as `centred` gave them (its third row is overwritten); `line`: the
    piece's band-aware spread about its line; `extent`: its length along it [taxels].
    """
    circle = taubin_circle(x, y, points)
    if circle is None:
        return False
    centre_x, centre_y, radius = circle
    if sagitta(radius, extent) < _ARC_BOW:
        return False
    residual = np.hypot(x - centre_x, y - centre_y)
    residual -= radius
    return _spread(residual) <= _ARC_CLOSER * line


def tolerance(length: float) -> float:
    """Largest spread [taxels] of a straight or circular outline of `length` taxels."""
    return max(_SPREAD_TAXELS, _SPREAD_RELATIVE * length)


def sagitta(radius: float, chord: float) -> float:
    """How far an arc of `radius` bows over a `chord` (both in the same unit)."""
    if not math.isfinite(radius):
        return 0.0
    half = chord / 2
    return radius if half >= radius else radius - math.sqrt(radius**2 - half**2)


def two_arms(x: np.ndarray, y: np.ndarray, points: Centred | None = None) -> tuple[float, float]:
    """Fit two straight arms meeting at a vertex: (worst arm spread, interior angle).

    The arms' far ends are the point farthest from the centroid and the point farthest
    from that one; the vertex is the point farthest from the chord between them. Under
    60 degrees the vertex lies farther from one far end than the other far end does, and
    is taken for an end, and an end of the piece for the vertex: where `x`, `y` run along
    an open outline piece (as `free_chains` gives them) and that happens, the piece's own
    ends are tried as the far ends, and kept when they give arms under 70 degrees apart
    that fit three times better or more and whose halves away from the vertex are no
    band's parallel sides (over 15 degrees apart). `points`: (x, y) as `centred` gives
    them, if already made.
    """
    terms = (points or centred(x, y))[3]
    # plain floats for the scalar arithmetic (NumPy scalars cost several times more)
    far_a = int((terms[0] ** 2 + terms[1] ** 2).argmax())
    ax, ay = x[far_a].item(), y[far_a].item()
    far_b = int(((x - ax) ** 2 + (y - ay) ** 2).argmax())
    spread, angle, vertex, _ = _arms_between(x, y, far_a, far_b)
    last = x.size - 1
    # misread: the vertex found is an end of the piece, and its other end a far end
    ends_misread = vertex in (0, last) and {0, last} <= {far_a, far_b, vertex}
    if ends_misread and spread > _SPREAD_TAXELS:
        ends = _arms_between(x, y, 0, last, far_halves=True)
        # (a band's end reads so too: its sides, the arms' far halves, run parallel)
        if ends[1] < _ACUTE and ends[0] <= spread / _MISREAD and ends[3] > _IN_LINE:
            return ends[:2]
    return spread, angle


def _arms_between(
    x: np.ndarray, y: np.ndarray, far_a: int, far_b: int, *, far_halves: bool = False
) -> tuple[float, float, int | None, float]:
    """`two_arms` with the arms' far ends at the points `far_a` and `far_b`, and more.

    Returns the worst arm spread, the interior angle, the vertex and, with `far_halves`,
    the angle [rad, 0 to pi / 2] between the lines through the arms' halves away from the
    vertex (0 where either holds under 3 points; NaN without `far_halves`). The vertex is
    the index of the point taken for it (also where an arm then holds too few points: no
    arms, an infinite spread), None where no point lies off the chord.
    """
    ax, ay = x[far_a].item(), y[far_a].item()
    bx, by = x[far_b].item(), y[far_b].item()
    chord = math.hypot(bx - ax, by - ay)
    if chord == 0:
        return math.inf, math.pi, None, 0.0
    off = np.abs((bx - ax) * (ay - y) - (ax - x) * (by - ay)) / chord
    vertex = int(off.argmax())
    if off[vertex] < _MIN_VERTEX_OFFSET:
        return math.inf, math.pi, None, 0.0
    vx, vy = x[vertex].item(), y[vertex].item()
    # each point joins the arm whose segment it lies nearer to: both arms at once, a row
    # each (the same products and quotients, element by element, as one arm at a time)
    from_x, from_y = x - vx, y - vy
    arms = np.array(
        [
            [ex - vx, ey - vy, max((ex - vx) ** 2 + (ey - vy) ** 2, 1e-12)]
            for ex, ey in ((ax, ay), (bx, by))
        ]
    )
    along_x, along_y, length_sq = arms[:, 0:1], arms[:, 1:2], arms[:, 2:3]
    t = (from_x * along_x + from_y * along_y) / length_sq
    np.minimum(np.maximum(t, 0, out=t), 1, out=t)  # np.clip(t, 0, 1), without its wrapper
    distances = np.hypot(from_x - t * along_x, from_y - t * along_y)
    first = distances[0] <= distances[1]
    count = int(np.count_nonzero(first))
    smaller = min(count, first.size - count)
    if smaller < _MIN_ARM * x.size or smaller < 3:
        return math.inf, math.pi, vertex, 0.0
    other = ~first
    worst = max(_line_spread(x[first], y[first])[0], _line_spread(x[other], y[other])[0])
    arm_a = math.atan2(ay - vy, ax - vx)
    arm_b = math.atan2(by - vy, bx - vx)
    angle = abs((arm_a - arm_b + math.pi) % (2 * math.pi) - math.pi)
    if not far_halves:
        return worst, angle, vertex, math.nan
    # the lines through the far halves of the arms (away from the vertex), and the angle
    # between them (undirected: 0 to 90 degrees)
    outer_a = first & (t[0] > 0.5)
    outer_b = other & (t[1] > 0.5)
    if np.count_nonzero(outer_a) < 3 or np.count_nonzero(outer_b) < 3:
        return worst, angle, vertex, 0.0
    _, cos_a, sin_a = _line_spread(x[outer_a], y[outer_a])
    _, cos_b, sin_b = _line_spread(x[outer_b], y[outer_b])
    return worst, angle, vertex, math.acos(min(abs(cos_a * cos_b + sin_a * sin_b), 1.0))


def corner_score(best_single: float, arms: tuple[float, float]) -> float:
    """Evidence in [0, 1] that an outline is two straight arms rather than one curve."""
    spread, angle = arms
    if not math.isfinite(spread):
        return 0.0
    ratio = best_single / max(spread, 0.1)
    return ramp(ratio, 1.5, 3.0) * ramp(math.pi - angle, _IN_LINE, _BENT)


def bends(arms: tuple[float, float]) -> bool:
    """Whether two arms (from `two_arms`) can score as a corner at all (see `corner_score`)."""
    spread, angle = arms
    return math.isfinite(spread) and math.pi - angle > _IN_LINE


def edge_line(chains: Sequence[tuple[np.ndarray, np.ndarray]]) -> LineFit:
    """The straight edge that free outline pieces lie along (taxel units).

    The direction is the total least squares direction of every piece about its own
    centre (their scatter matrices summed), so that two pieces of one edge, or pieces of
    unequal length or position, do not tilt it as one fit through all their points does;
    the line runs midway between the outermost pieces' offsets (all pieces of one edge
    share an offset). The RMS is the points' distance from that line.
    """
    sxx = sxy = syy = 0.0
    centres = []
    for x, y in chains:
        mean_x, mean_y, _, terms = centred(x, y)
        (xx, xy), (_, yy) = np.einsum("in,jn->ij", terms[:2], terms[:2]).tolist()
        sxx, sxy, syy = sxx + xx, sxy + xy, syy + yy
        centres.append((mean_x, mean_y))
    angle = 0.5 * math.atan2(2 * sxy, sxx - syy) % math.pi
    sine, cosine = math.sin(angle), math.cos(angle)
    offsets = [cosine * mean_y - sine * mean_x for mean_x, mean_y in centres]
    offset = (min(offsets) + max(offsets)) / 2
    squared, count = 0.0, 0
    for x, y in chains:
        distance = cosine * y - sine * x - offset
        squared += dot(distance, distance)
        count += x.size
    return LineFit(angle, offset, math.sqrt(squared / count), count)


def one_side(mask: np.ndarray, line: LineFit) -> bool:
    """Whether the contact lies on one side of a straight free outline: a face's edge.

    A band clipped by the array's border (a short cylinder) has a free outline too, its
    two sides and end, with contact on both sides of the line through them: its line is
    the whole outline's, which holds both sides. Taxels within one taxel of the line are
    the outline's own jitter and are not counted.
    """
    rows, cols = np.nonzero(mask)
    distance = math.cos(line.angle_rad) * rows - math.sin(line.angle_rad) * cols
    distance -= line.offset_m
    above = cv2.countNonZero((distance > 1.0).view(np.uint8))
    below = cv2.countNonZero((distance < -1.0).view(np.uint8))
    return min(above, below) <= _ONE_SIDE * max(above, below, 1)


def free_chains(
    contours: Sequence[np.ndarray],
    shape: tuple[int, int],
    explained: np.ndarray | None,
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
    # the taxels where an outline is free: inside the margin, off the gaps' walls (with no
    # gap, the margin alone, tested on the outline's points)
    allowed = None
    if explained is not None and cv2.countNonZero(explained):
        allowed = np.zeros(shape, np.uint8)
        inner = (slice(margin, rows - margin), slice(margin, cols - margin))
        allowed[inner] = explained[inner] == 0
    chains = []
    for contour in contours:
        count = contour.shape[0]
        if count < _MIN_CHAIN:
            continue
        points = contour.reshape(count, 2)
        if allowed is None:
            inside = (margin, margin), (cols - 1 - margin, rows - 1 - margin)
            free = cast(np.ndarray, cv2.inRange(contour, *inside)).reshape(count)
            free >>= 7  # 255 -> 1, as `allowed` holds
        else:
            free = allowed[points[:, 1], points[:, 0]]
        if not 0 < np.count_nonzero(free) < count:
            continue
        # start on a taxel that is not free, so that no free piece wraps around the end
        start = int(free.argmin())
        free = np.concatenate((free[start:], free[:start], _ZERO), dtype=np.int8)
        # where a free piece begins, and after it ends: from the first, they alternate
        # (`nonzero` of the 1-D comparison: np.flatnonzero's indices, without its wrapper)
        changes = (free[1:] != free[:-1]).nonzero()[0].tolist()
        pieces = [
            (begin, end)
            for begin, end in zip(changes[::2], changes[1::2], strict=True)
            if end - begin >= _MIN_CHAIN
        ]
        if not pieces:
            continue
        # (x, y) as two contiguous float rows, from the start taxel on
        xy = np.concatenate((points[start:], points[:start])).T.astype(float, order="C")
        for begin, end in pieces:
            chains.append((xy[0, begin + 1 : end + 1], xy[1, begin + 1 : end + 1]))
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
