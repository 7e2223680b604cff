"""Contact type: none, point, line, arc, surface or corner (Ellis seed, section 2.1).

What each type looks like on a compliant cover, and the rule that finds it (thresholds in
the module constants, each with its reason):

========  ====================================  ==========================================
type      physics                               rule, in order
========  ====================================  ==========================================
none      no pressure above the noise           no contact region
surface   a textured face or several contacts   3 or more regions of >= 5 % of the area,
                                                or more than 8 edge segments
point     a tip (pen, cone) or a body whose     one compact region (axes within 2:1, no
          contact the array cannot resolve:     hole, inside the array) that is small
          pressure peaks at the centre          (<= `point_size`) or centre-heavy
line      a straight edge pressed in (cylinder  a band (length >= 3 x thickness) whose
          side, box edge): a long narrow band;  edges are parallel lines; or a broad region
          or a face whose straight edge         whose only free outline is straight
          crosses the array (half-plane)
arc       a curved edge (drink-can rim): a      a band whose edges are concentric circles,
          curved narrow band                    curved enough to resolve (sagitta >= 2 taxels)
corner    a vertex: two straight edges meeting  a band bent in a V, or a free outline made
          (box corner): a wedge or a bent band  of two straight arms meeting at <= 150 deg
surface   a flat or gently curved face: punch,  everything else in contact (closed outlines,
          large sphere, plate, washer           holes, slots, curved free outlines)
========  ====================================  ==========================================

A *free outline* is the part of a contact's outline that is neither on the array's border
(the object continues there) nor the wall of a hole or slot (reported as such).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import cv2
import numpy as np

from taxel._validation import check_positive
from taxel.features._contact import Contact, contact_regions
from taxel.features._edges import Edges, edges_core
from taxel.features._fitting import CircleFit, LineFit, circle_fit_core, line_fit_core
from taxel.features._gaps import gaps_core
from taxel.features._image import Prepared, prepare

__all__ = ["CONTACT_TYPES", "ContactShape", "classify_contact", "shape_core"]

CONTACT_TYPES = ("none", "point", "line", "arc", "surface", "corner")

# Several contacts: a region counts when it holds >= 5 % of the contact area; three such
# regions (or more than 8 edge segments) is a texture or a multi-point grip, not one shape.
_MINOR_REGION = 0.05
_MANY_REGIONS = 3
_MANY_EDGES = 8
# Point: compact means equivalent-ellipse axes within 2:1. Centre-heavy means the
# pressure-weighted mean square radius is below 0.70 of the unweighted one: a uniform disk
# gives 1, a flat punch more (rim peaks), a Hertz dome 0.8, a blurred unresolved contact
# ~0.67 and a cone ~0.5.
_COMPACT_RATIO = 0.5
_CONCENTRATION = 0.70
_POINT_SIZE = 2.5e-3  # [m]; a contact this small is a point whatever its profile
_POINT_TAXELS = 5.0  # ... and so is one under 5 taxels, the blur footprint of a single taxel
# Band: length (area / thickness) >= 3 thicknesses; thickness = inscribed diameter.
_BAND = 3.0
# Straight / concentric: the spread of |residual| (both edges of a band sit at the same
# distance from its centre line) under 0.75 taxel or 1.5 % of the length; edge jitter on a
# noisy frame is ~0.3-0.5 taxel.
_SPREAD_TAXELS = 0.75
_SPREAD_RELATIVE = 0.015
# An arc must bow by at least 2 taxels over its chord, or it is a line at this resolution.
_MIN_SAGITTA = 2.0
# Corner: two straight arms meeting at an interior angle <= 150 deg (a straight line is 180),
# each arm >= 20 % of the outline; the vertex must lie >= 2 taxels off the chord.
_CORNER_ANGLE = math.radians(150.0)
_MIN_ARM = 0.2
# Free outline pieces shorter than this many taxels are ignored (blur-rounded corners).
_MIN_CHAIN = 6


@dataclass(frozen=True)
class ContactShape:
    """Contact type and the measures it was decided from.

    Attributes
    ----------
    contact_type : str
        One of 'none', 'point', 'line', 'arc', 'surface', 'corner'.
    confidence : float
        How clearly the deciding measure passed its threshold, in [0, 1].
    edge_score : float
        Evidence in [0, 1] that the contact is an edge (a long narrow band) rather than a
        gently curved surface: a ramp of the elongation from 1.5 (0) to 4.5 (1).
    corner_score : float
        Evidence in [0, 1] that the contact is a vertex rather than an edge or a surface:
        a ramp of how much two straight arms beat one line and a circle, times a ramp of
        the arms' turn (15 deg: 0, 35 deg: 1).
    line : LineFit or None
        Line fitted to all edge taxels [m].
    circle : CircleFit or None
        Circle fitted to all edge taxels [m].
    n_edges : int
        Number of edge segments.
    thickness_m : float
        Diameter of the largest disk inside the main contact region [m].
    elongation : float
        Length (area over thickness) over thickness of the main region.
    concentration : float
        Pressure-weighted over unweighted mean square radius of the main region.
    rule : str
        The rule that decided the type (see the module notes).
    """

    contact_type: str
    confidence: float
    edge_score: float
    corner_score: float
    line: LineFit | None
    circle: CircleFit | None
    n_edges: int
    thickness_m: float
    elongation: float
    concentration: float
    rule: str


def _ramp(value: float, low: float, high: float) -> float:
    return float(min(max((value - low) / (high - low), 0.0), 1.0))


def _spread(residual: np.ndarray) -> float:
    """Spread of |residual|: ~0 for one curve or two parallel/concentric ones."""
    return float(np.std(np.abs(residual)))


def _line_spread(x: np.ndarray, y: np.ndarray) -> tuple[float, float]:
    """Band-aware spread about the best line, and the points' length along it."""
    fit = line_fit_core(x, y)
    direction = (math.cos(fit.angle_rad), math.sin(fit.angle_rad))
    residual = -direction[1] * x + direction[0] * y - fit.offset_m
    along = direction[0] * x + direction[1] * y
    return _spread(residual), float(np.ptp(along))


def _circle_spread(x: np.ndarray, y: np.ndarray) -> tuple[float, CircleFit]:
    fit = circle_fit_core(x, y)
    if not math.isfinite(fit.radius_m):
        return math.inf, fit
    residual = np.hypot(x - fit.center_m[0], y - fit.center_m[1]) - fit.radius_m
    return _spread(residual), fit


def _two_arms(x: np.ndarray, y: np.ndarray) -> tuple[float, float]:
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
    if off[vertex] < 2.0:
        return math.inf, math.pi
    vx, vy = x[vertex], y[vertex]
    # each point joins the arm whose segment it lies nearer to
    distances = []
    for ex, ey in ((ax, ay), (bx, by)):
        length_sq = max((ex - vx) ** 2 + (ey - vy) ** 2, 1e-12)
        t = np.clip(((x - vx) * (ex - vx) + (y - vy) * (ey - vy)) / length_sq, 0, 1)
        distances.append(np.hypot(x - vx - t * (ex - vx), y - vy - t * (ey - vy)))
    first = distances[0] <= distances[1]
    if (
        min(first.sum(), (~first).sum()) < _MIN_ARM * x.size
        or min(first.sum(), (~first).sum()) < 3
    ):
        return math.inf, math.pi
    worst = max(_line_spread(x[first], y[first])[0], _line_spread(x[~first], y[~first])[0])
    arm_a = math.atan2(ay - vy, ax - vx)
    arm_b = math.atan2(by - vy, bx - vx)
    angle = abs((arm_a - arm_b + math.pi) % (2 * math.pi) - math.pi)
    return worst, angle


def _free_chains(prepared: Prepared, explained: np.ndarray) -> list[tuple[np.ndarray, np.ndarray]]:
    """Open pieces of the contacts' outlines, as (cols, rows) taxel arrays.

    Closed outlines (a contact wholly inside the array) return nothing: they outline a
    finite face or tip, not an edge of the object crossing the array.
    """
    contours, _ = cv2.findContours(prepared.mask, cv2.RETR_LIST, cv2.CHAIN_APPROX_NONE)
    rows, cols = prepared.mask.shape
    chains = []
    for contour in contours:
        if contour.shape[0] < _MIN_CHAIN:
            continue
        x, y = contour[:, 0, 0], contour[:, 0, 1]
        free = (x > 0) & (x < cols - 1) & (y > 0) & (y < rows - 1) & (explained[y, x] == 0)
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


def _tolerance(length: float) -> float:
    return max(_SPREAD_TAXELS, _SPREAD_RELATIVE * length)


def _sagitta(radius: float, chord: float) -> float:
    if not math.isfinite(radius):
        return 0.0
    half = chord / 2
    return radius if half >= radius else radius - math.sqrt(radius**2 - half**2)


def _corner_score(best_single: float, arms: tuple[float, float]) -> float:
    spread, angle = arms
    if not math.isfinite(spread):
        return 0.0
    ratio = best_single / max(spread, 0.1)
    return _ramp(ratio, 1.5, 3.0) * _ramp(math.pi - angle, math.radians(15), math.radians(35))


def _main_region(prepared: Prepared) -> tuple[np.ndarray, np.ndarray, int]:
    counts = np.bincount(prepared.labels.ravel(), minlength=prepared.n_regions + 1)
    counts[0] = 0
    label = int(np.argmax(counts))
    rows, cols = np.nonzero(prepared.labels == label)
    return rows, cols, label


def shape_core(
    prepared: Prepared,
    contact: Contact,
    edges: Edges,
    *,
    has_gaps: bool,
    explained: np.ndarray,
    point_size: float = _POINT_SIZE,
) -> ContactShape:
    """Classify a prepared image (internal core of `classify_contact`)."""
    pitch = prepared.mean_pitch
    line = circle = None
    if edges.rows.size >= 3:
        line = line_fit_core(edges.points_m[:, 0], edges.points_m[:, 1])
        circle = circle_fit_core(edges.points_m[:, 0], edges.points_m[:, 1])
    if not contact.present:
        return ContactShape("none", 1.0, 0.0, 0.0, line, circle, 0, 0.0, 0.0, 0.0, "no contact")
    rows, cols, label = _main_region(prepared)
    depth = cv2.distanceTransform((prepared.labels == label).view(np.uint8), cv2.DIST_L2, 3)
    thickness = 2.0 * float(depth.max()) + 1.0  # [taxels]; +1: taxel centres, not edges
    length = rows.size / thickness
    elongation = length / thickness
    edge_score = _ramp(elongation, 1.5, 4.5)
    weight = np.maximum(prepared.smooth[rows, cols] - prepared.baseline, 0.0).astype(float)
    radius_sq = (rows - rows.mean()) ** 2 + (cols - cols.mean()) ** 2
    concentration = float(weight @ radius_sq) / max(float(weight.sum()) * radius_sq.mean(), 1e-30)
    if radius_sq.mean() == 0:
        concentration = 0.0
    main = contact.regions[0]

    def result(kind: str, confidence: float, corner: float, rule: str) -> ContactShape:
        return ContactShape(
            kind, float(confidence), edge_score, float(corner), line, circle, edges.n_edges,
            thickness * pitch, float(elongation), concentration, rule,
        )  # fmt: skip

    total = sum(region.area_taxels for region in contact.regions)
    major_regions = sum(region.area_taxels >= _MINOR_REGION * total for region in contact.regions)
    if major_regions >= _MANY_REGIONS or edges.n_edges > _MANY_EDGES:
        return result("surface", 1.0, 0.0, "several contacts or many edges (texture)")
    compact = main.minor_axis_m >= _COMPACT_RATIO * main.major_axis_m
    if compact and not has_gaps and not main.touches_border:
        if main.major_axis_m <= max(point_size, _POINT_TAXELS * pitch):
            return result("point", 1.0, 0.0, "small compact contact")
        if concentration < _CONCENTRATION:
            margin = _ramp(_CONCENTRATION - concentration, 0.0, 0.15)
            return result("point", 0.5 + 0.5 * margin, 0.0, "centre-heavy compact contact")
    if elongation >= _BAND and not has_gaps:
        if edges.rows.size >= 8:
            x, y = edges.cols.astype(float), edges.rows.astype(float)
        else:
            x, y = cols.astype(float), rows.astype(float)
        line_spread, extent = _line_spread(x, y)
        circle_spread, fit = _circle_spread(x, y)
        tolerance = _tolerance(extent)
        arms = _two_arms(x, y)
        corner = _corner_score(min(line_spread, circle_spread), arms)
        if line_spread <= tolerance:
            return result("line", 1.0 - 0.5 * line_spread / tolerance, corner, "straight band")
        sagitta = _sagitta(fit.radius_m, extent)
        if circle_spread <= tolerance and sagitta >= _MIN_SAGITTA:
            return result("arc", 1.0 - 0.5 * circle_spread / tolerance, corner, "curved band")
        if arms[0] <= tolerance and arms[1] <= _CORNER_ANGLE:
            return result("corner", max(corner, 0.5), corner, "bent band")
        kind = "line" if line_spread <= circle_spread or sagitta < _MIN_SAGITTA else "arc"
        return result(kind, 0.5, corner, "irregular band, nearer fit")
    chains = _free_chains(prepared, explained)
    if not chains:
        return result("surface", 1.0, 0.0, "face with a closed or no free outline")
    straight = True
    best_corner = 0.0
    for x, y in chains:
        line_spread, extent = _line_spread(x, y)
        tolerance = _tolerance(extent)
        arms = _two_arms(x, y)
        circle_spread, _ = _circle_spread(x, y)
        corner = _corner_score(min(line_spread, circle_spread), arms)
        if arms[0] <= tolerance and arms[1] <= _CORNER_ANGLE and line_spread > tolerance:
            return result("corner", max(corner, 0.5), corner, "free outline with a vertex")
        best_corner = max(best_corner, corner)
        straight &= line_spread <= tolerance
    if straight:
        return result("line", 0.8, best_corner, "face with a straight free outline")
    return result("surface", 0.7, best_corner, "face with a curved free outline")


def classify_contact(
    image: Any,
    sensor_or_pitch: Any,
    *,
    smoothing: float = 1.0,
    point_size: float = _POINT_SIZE,
) -> ContactShape:
    """Contact type of a tactile image, with edge and corner measures.

    Parameters
    ----------
    image : array_like, shape (rows, cols)
        Raw frame, calibrated reading or pressure map.
    sensor_or_pitch : float, (float, float) or object with ``taxel_pitch``
        Taxel pitch [m].
    smoothing : float, default 1.0
        Gaussian sigma [taxels].
    point_size : float, default 2.5e-3
        A compact contact whose major axis is at most this [m] (or 5 taxels) is a point.

    Returns
    -------
    ContactShape

    Notes
    -----
    The seed (section 2.1) classifies from Canny edges, a line fit and a circle fit with
    their RMS errors, and the number of edges. Here the fits are to all edge taxels, and
    their *band-aware* spread (the standard deviation of the absolute residual) replaces
    the RMS in the tests, because both edges of a band lie at the same distance from its
    centre line: the RMS measures the band's width, the spread its straightness. The
    extent (thickness, elongation) separates bands from faces, the number of regions and
    edges separates textures. The rules and their thresholds are in the module notes.

    Examples
    --------
    >>> y, x = np.mgrid[:64, :64]
    >>> band = (np.abs(y - 0.5 * x - 16) < 3).astype(float)  # a straight edge pressed in
    >>> shape = classify_contact(band, 0.5e-3)
    >>> shape.contact_type, round(float(np.degrees(shape.line.angle_rad)), 1)
    ('line', 27.1)
    >>> classify_contact(np.zeros((16, 16)), 1e-3).contact_type
    'none'
    """
    point_size = check_positive("point_size", point_size)
    prepared = prepare(image, sensor_or_pitch, smoothing=smoothing)
    contact = contact_regions(prepared)
    edges = edges_core(prepared)
    holes, slots, explained = gaps_core(prepared)
    return shape_core(
        prepared,
        contact,
        edges,
        has_gaps=bool(holes or slots),
        explained=explained,
        point_size=point_size,
    )
