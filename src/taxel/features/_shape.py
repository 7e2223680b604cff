"""Contact type: none, point, line, arc, surface or corner (Ellis seed, section 2.1).

What each type looks like through a compliant cover, and the rule that finds it, in the
order the rules are tried (thresholds in the module constants, each with its reason):

========  ======================================  ========================================
type      physics                                 rule
========  ======================================  ========================================
none      no pressure above the noise             no contact region
surface   a texture (foam, rasp, screen) or a     3 or more regions of >= 5 % of the area,
          multi-point grip: many separate high    or >= 3 high points in the contact, or
          points or a perforated face             >= 2 holes
surface   a face with a hole or a slot            a hole or a slot in the contact
line      a straight edge pressed in (cylinder    a band (length >= 1.5 widths, or a signal
          side, box edge): a long narrow band     4 times as long as wide without the
                                                  cover's blur) whose centre line is straight
arc       a curved edge (drink-can rim)           a band whose centre line is a circle arc
                                                  bowing >= 2 taxels over its length, and
                                                  thinner than half its radius
point     a tip, or a contact too small for the   one compact region (axes within 2:1,
          array to resolve its shape              inside the array) whose size at half its
                                                  peak <= max(`point_size`, 2 pitches)
                                                  (x sqrt(3)/2 unless flat-topped: a Hertz
                                                  contact's half-peak width, but not under
                                                  2 pitches), widened by the cover's blur
corner    a vertex (box corner): the contact      a compact region larger than the point
          spreads along the three edges that      size and 8 taxels whose outline has three
          leave it, a rounded triangle            lobes (3rd harmonic of radius >= 0.08)
line      a face whose straight edge crosses      the free outline is straight over 8
          the array (half-plane)                  taxels or more (its pieces, if several,
                                                  along one line), not an arc bowing by 2
                                                  taxels that a circle fits twice as well
corner    a face with a vertex (wedge)            a free outline of two straight arms
                                                  meeting at <= 150 deg that fit it
                                                  better than one circle
surface   a flat or gently curved face: punch,    everything else (closed outlines, curved
          large sphere, plate, washer             free outlines)
========  ======================================  ========================================

A *free outline* is the part of a contact's outline that is neither near the array's
border (the object continues there; within the cover's depth or blur of it the cover's own
rim presses less) nor the wall of a hole or slot (reported as such). The line of a face's
straight edge (the contact on one side of its free outline) is fitted to the free pieces
alone, each about its own centre, not to the whole outline. A *band*'s centre line and
direction are the weighted principal axis of its taxels (weights: signal above the
baseline), and its circle is the weighted (Taubin) circle of the same taxels, so both edges
and the ridge between them all count. Taxels farther than 0.75 band thicknesses from the
fitted curve are a spur (what a glass scratch leaves where it crosses the band) and the
band is refitted without them.

Given a sensor description (`taxel.sensor.TactileSensor`), the rules use its cover: the
half-maximum width of its response to a point load (the *blur*, from the sensor's own
mechanics) and its depth.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from typing import Any, Unpack

import cv2
import numpy as np

from taxel._validation import check_positive
from taxel.features._contact import Contact, contact_regions
from taxel.features._fitting import (
    CircleFit,
    LineFit,
    centred,
    fit_line_and_circle,
    line_through,
)
from taxel.features._image import Preparation, Prepared, prepare
from taxel.features._measures import (
    band_fits,
    half_region,
    region_measures,
    signal_elongation,
    three_lobes,
    to_metres_circle,
    to_metres_line,
)
from taxel.features._outline import (
    bends,
    circle_spread,
    corner_score,
    curved,
    edge_line,
    free_chains,
    line_spread,
    one_side,
    ramp,
    sagitta,
    tolerance,
    two_arms,
)
from taxel.features._record import record
from taxel.features._sensor import require_square_taxels
from taxel.features._textured import MANY_HIGH_POINTS, textured_gaps

__all__ = ["CONTACT_TYPES", "ContactShape", "classify_contact", "shape_core"]

CONTACT_TYPES = ("none", "point", "line", "arc", "surface", "corner")
_OutlineFit = tuple[LineFit, CircleFit]

_MANY_HOLES = 2
# Band: length (area / thickness) >= 1.5 thicknesses. A round body (sphere, punch, tip)
# makes a round contact (area / thickness^2 = pi / 4 ~ 0.8) and a vertex a rounded
# triangle (~1); only a body with an edge, a line of lowest points, makes a contact half
# again as long as it is wide (a cylinder on its side: its length over its contact width).
_BAND = 1.5
# ... or a region whose signal is 4 times as long as it is wide once the cover's blur is
# taken out (`signal_elongation`): on a coarse array the blur widens a short edge's region
# to nearly its length (a 12-25 mm cylinder on a 2 mm pitch under a 4 mm blur). A round
# body's signal stays under 2 (3 for a pen under noise on 16 x 16); 4 was the better of
# 3 and 4 on the features benchmark (the same on vhdta128, where the regions are long).
_SIGNAL_BAND = 4.0
# Compact: equivalent-ellipse axes within 2:1.
_COMPACT_RATIO = 0.5
_POINT_SIZE = 2.5e-3  # [m]
# ... and never under 2 taxel pitches: the array cannot resolve a shape smaller than that.
# The size is measured on the image at half the contact's peak, and the image is the
# pressure blurred by the cover (the blur being the half-maximum width of its response to
# a point load, from the sensor's own mechanics when a sensor is given, else 0). Where the
# image is a faithful copy of the pressure, widths add in quadrature under blurring (as the
# variances of a convolution do): the limit is sqrt(size^2 + blur^2). Where the sensor
# saturates, the image is clipped and its half-peak contour lies where the blurred pressure
# is half the saturation level: outside the contact by an amount that grows with how far
# the peak is above saturation (a blur width on each side at ~50 times), which the clipped
# image does not tell. The limit adds half the blur to the size: a value chosen on the
# features benchmark (of 0, 1/4, 1/2, 3/4 and 1 blur, the best on both draws of simulated
# frames; it added 1 blur before). A saturated image is flat-topped: its top 10 % covers
# at least a third of its half-maximum area (see `taxel.features._measures`). Both add
# half a pitch: the contact's edge falls part-way into the next taxel.
_POINT_PITCHES = 2.0
_SATURATED_SPREAD = 0.5  # of the blur (chosen on the benchmark, see above)
# A rounded contact (sphere, tip, vertex) is not flat-topped: its pressure falls from the
# centre to the edge, as Hertz's p0 sqrt(1 - r^2 / a^2), which is half its peak at
# r = a sqrt(3) / 2. Its half-peak region is that fraction of its width, so the limit of a
# faithful image compares the half-peak size with sqrt(3) / 2 of the point size, but never
# with less than the 2-pitch floor itself: whatever the pressure, a tip between two
# taxels lights both (a region 2.31 taxels across, within the floor's half-pitch margin).
_HALF_PEAK_RATIO = math.sqrt(3.0) / 2.0
# An arc must bow by at least 2 taxels over its chord, or it is a line at this resolution.
_MIN_SAGITTA = 2.0
# A curved edge (a rim) presses a band much narrower than its radius of curvature: the
# width of an edge's contact grows like sqrt(edge radius x indentation), a few millimetres,
# while a rim's radius is the object's size (0.09-0.21 for drink-can rims on the
# simulator). A curved band as thick as half its radius is part of a face: a washer's ring
# or a face cut by a hole.
_RIM_WIDTH = 0.5
# Three lobes: a rounded triangle blurred by the cover keeps about 1/5 of a sharp
# triangle's 3rd harmonic (0.42); a disk or an ellipse has none beyond noise (< 0.06). The
# pixel grid alone gives outlines up to ~0.1 when they span fewer than 8 taxels, so lobes
# are looked for only on contacts at least that large.
_LOBES = 0.08
_LOBES_TAXELS = 8.0
# A free outline is called straight only over 8 taxels or more: on a shorter piece the
# taxel grid hides a bow (the same resolution as for lobes).
_STRAIGHT_TAXELS = 8.0
# Pieces of one straight outline each run within 15 deg of the line through them all (the
# angle under which a corner's arms still count as in line, `taxel.features._outline`).
_ALONG_LINE = math.radians(15.0)
# Corner: two straight arms meeting at an interior angle <= 150 deg (a straight line is 180).
_CORNER_ANGLE = math.radians(150.0)


@record
class ContactShape:
    """Contact type and the measures it was decided from.

    Attributes
    ----------
    contact_type : str
        One of 'none', 'point', 'line', 'arc', 'surface', 'corner'.
    confidence : float
        How clearly the deciding measure passed its threshold, in [0, 1].
    edge_score : float
        Evidence in [0, 1] that the contact is an edge rather than a surface. A band or a
        compact contact: a ramp of its elongation from 1 (0) to 2 (1). A face reaching the
        array's border: 1 when its free outline is one straight line (the object's edge
        crosses the array), 0 when it is curved or has a vertex. 0 for a texture, a face
        with holes or slots, a face with no free outline, and a wide curved strip.
    corner_score : float
        Evidence in [0, 1] that the contact is a vertex rather than an edge or a surface.
    line : LineFit or None
        For a band, its centre line; for a face's straight edge (a half-plane), that edge,
        fitted to the free outline alone; otherwise the line fitted to the contact's
        outline [m].
    circle : CircleFit or None
        For a band, the circle through its taxels; otherwise the circle fitted to the
        contact's whole outline [m] (for a face's edge too, so it is not the line's fit).
    n_edges : int
        Number of outline curves of the contact (outer outlines and hole walls).
    thickness_m : float
        Diameter of the largest disk inside the main contact region [m].
    elongation : float
        Length (area over thickness) over thickness of the main region.
    concentration : float
        Signal-weighted over unweighted mean square radius of the main region.
    size_m : float or None
        Major axis of the main region above half its peak [m]: the contact's size with
        the blur of the smoothing and most of the cover's removed. Measured on compact
        contacts clear of the array's border only (the point and lobe rules'); None when
        not measured (no contact, a band, a face with a hole, a texture...).
    lobes : float or None
        3rd angular harmonic of the main region's outline at half its peak, measured on
        compact contacts that are not points and span 8 taxels or more at half their
        peak; None when not measured.
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
    size_m: float | None
    lobes: float | None
    rule: str


def _free_outline(
    contours: Sequence[np.ndarray], prepared: Prepared, explained: np.ndarray | None
) -> tuple[str, float, float, str, LineFit | None] | None:
    """Type from the free outline pieces (see the module notes), or None without any.

    Outline taxels closer to the array's border than the cover is deep (and than one
    taxel) are not free: the cover's own rim presses less there. With the type comes the
    straight edge of a face (a half-plane: the contact on one side of its free outline),
    whose line is that edge's (taxel units), else None.
    """
    margin = max(1, math.ceil(prepared.cover_depth / prepared.mean_pitch))
    chains = free_chains(contours, prepared.image.shape, explained, margin)
    if not chains:
        return None
    straight = True
    best_corner = 0.0
    for x, y in chains:
        points = centred(x, y)  # shared by the line, the arms and the circle
        single, extent = line_spread(x, y, points)
        allowed = tolerance(extent)
        if single <= allowed and extent >= _STRAIGHT_TAXELS:
            if not curved(x, y, points, single, extent):
                continue  # straight: no vertex, no curve
            straight = False  # a round rim, a few taxels in radius
            continue
        if single <= allowed:
            straight = False  # too short to tell straight from curved
            continue
        straight = False
        arms = two_arms(x, y, points)
        if not bends(arms):
            continue  # the corner score is 0 whatever the circle, and no corner is found
        round_spread = circle_spread(x, y, points)
        corner = corner_score(min(single, round_spread), arms)
        # a vertex: two straight arms, which fit better than one circle (a curved edge,
        # such as a hole cut by the array's corner, is fitted as well by a circle)
        if arms[0] <= allowed and arms[1] <= _CORNER_ANGLE and arms[0] < round_spread:
            return "corner", max(corner, 0.5), corner, "free outline with a vertex", None
        best_corner = max(best_corner, corner)
    if straight and len(chains) > 1 and not _one_line(chains):
        # straight pieces that no one line runs through: a curved outline clipped by the
        # array (a broad disc's rim left only at the array's corners), not an edge
        return "surface", 0.7, best_corner, "face with a curved free outline", None
    if straight:
        line = edge_line(chains)
        face_edge = line if one_side(prepared.mask, line) else None
        return "line", 0.8, best_corner, "face with a straight free outline", face_edge
    return "surface", 0.7, best_corner, "face with a curved free outline", None


def _one_line(chains: Sequence[tuple[np.ndarray, np.ndarray]]) -> bool:
    """Whether the free outline's pieces lie along one straight line.

    They do where an edge's outline is interrupted (by a gap, or by a stretch near the
    array's border): each piece runs along the line through them all (the spread about
    it alone, of the distances' sizes so that a band's two sides pass, would also pass
    short pieces lying across it), and they lie close to it.
    """
    x = np.concatenate([chain[0] for chain in chains])
    y = np.concatenate([chain[1] for chain in chains])
    angle = line_through(centred(x, y))[0]
    for piece_x, piece_y in chains:
        turn = abs(line_through(centred(piece_x, piece_y))[0] - angle)
        if min(turn, math.pi - turn) > _ALONG_LINE:
            return False
    spread, extent = line_spread(x, y)
    return spread <= tolerance(extent)


def shape_core(
    prepared: Prepared,
    contact: Contact,
    *,
    n_holes: int,
    n_slots: int,
    explained: np.ndarray | None,
    high_point_count: int,
    textured: bool,
    point_size: float = _POINT_SIZE,
    contours: Sequence[np.ndarray] | None = None,
    outline_fit: _OutlineFit | Callable[[], _OutlineFit | None] | None = None,
) -> ContactShape:
    """Classify a prepared image (internal core of `classify_contact`).

    `textured`: whether the contact is a texture, as the gaps were found
    (`_textured.judged_gaps`: computed once). `contours`: the contact's outlines (every taxel), if
    already found; `outline_fit`: the line and circle fitted to them in taxel units, or a
    function that fits them when first called (a band's type does without). Only the
    measures a rule needs are computed; `size_m` and `lobes` are None when not measured.
    """
    require_square_taxels(prepared.pitch, "the contact type", prepared.hexagonal)
    pitch = prepared.mean_pitch
    if not contact.present:
        return ContactShape(
            "none", 1.0, 0.0, 0.0, None, None, 0, 0.0, 0.0, 0.0, None, None, "no contact"
        )
    if contours is None:
        contours, _ = cv2.findContours(prepared.mask, cv2.RETR_LIST, cv2.CHAIN_APPROX_NONE)
    outline = [c for c in contours if c.shape[0] >= 4]
    main, thickness, area, concentration = region_measures(prepared, contact)
    elongation = area / thickness**2
    edge_score = ramp(elongation, 1.0, 2.0)
    size: float | None = None
    three: float | None = None
    line = circle = None

    def result(
        kind: str,
        confidence: float,
        corner: float,
        rule: str,
        edge: float | None = None,
        face_edge: LineFit | None = None,
    ) -> ContactShape:
        fitted_line, fitted_circle = line, circle
        if fitted_line is None:
            fit = outline_fit() if callable(outline_fit) else outline_fit
            if fit is not None:
                fitted_line, fitted_circle = fit
            elif outline:  # the outline's own line and circle
                points = np.concatenate(outline).reshape(-1, 2).astype(float)
                fitted_line, fitted_circle = fit_line_and_circle(points[:, 0], points[:, 1])
        if face_edge is not None:  # the line of a face's edge is that edge's, not the outline's
            fitted_line = face_edge
        if fitted_line is not None:
            assert fitted_circle is not None  # the line and circle are fitted together
            fitted_line = to_metres_line(fitted_line, prepared)
            fitted_circle = to_metres_circle(fitted_circle, prepared)
        return ContactShape(
            kind, float(confidence), edge_score if edge is None else edge, float(corner),
            fitted_line, fitted_circle,
            len(outline), thickness * pitch, float(elongation), concentration,
            None if size is None else size * pitch, None if three is None else float(three),
            rule,
        )  # fmt: skip

    # a face's region is as long as it is thin wherever holes or gaps cut it: its
    # elongation says nothing of an edge, so the rules below that decide a face set it
    if textured:
        if high_point_count >= MANY_HIGH_POINTS:
            return result("surface", 1.0, 0.0, "many high points (texture)", 0.0)
        return result("surface", 1.0, 0.0, "several contacts (texture)", 0.0)
    if n_holes >= _MANY_HOLES:
        return result("surface", 1.0, 0.0, "several holes (perforated face)", 0.0)
    if n_holes or n_slots:
        return result("surface", 1.0, 0.0, "face with a hole or a slot", 0.0)
    if elongation >= _BAND or signal_elongation(prepared, main) >= _SIGNAL_BAND:
        line, circle, length = band_fits(prepared, main, thickness)
        bow = sagitta(circle.radius_m, length)
        if bow >= _MIN_SAGITTA and circle.rms_m < line.rms_m:
            if thickness > _RIM_WIDTH * circle.radius_m:
                return result("surface", 0.7, 0.0, "wide curved strip (part of a face)", 0.0)
            return result("arc", ramp(bow, 1.0, 4.0), 0.0, "curved band")
        return result("line", ramp(elongation, 1.0, 2.0), 0.0, "straight band")
    region = contact.regions[0]
    compact = region.minor_axis_m >= _COMPACT_RATIO * region.major_axis_m
    if compact and not region.touches_border:
        half, origin, size, flat, moments = half_region(prepared, main)
        floor = _POINT_PITCHES * pitch
        smallest = max(point_size, floor)
        if flat:
            limit = smallest + _SATURATED_SPREAD * prepared.blur + 0.5 * pitch
        else:
            widened = math.hypot(_HALF_PEAK_RATIO * smallest, prepared.blur)
            limit = max(widened, floor) + 0.5 * pitch
        if size * pitch <= limit:
            return result("point", ramp(limit / (size * pitch), 1.0, 1.3), 0.0, "small contact")
        corner = 0.0
        if size >= _LOBES_TAXELS:
            three = three_lobes(prepared, half, moments, origin)
            corner = ramp(three, 0.5 * _LOBES, 1.5 * _LOBES)
        if three is not None and three >= _LOBES:
            return result("corner", corner, corner, "three-lobed compact contact (vertex)")
        return result("surface", 1.0 - corner, corner, "compact face")
    decided = _free_outline(contours, prepared, explained)
    if decided is None:
        return result("surface", 1.0, 0.0, "face with a closed or no free outline", 0.0)
    kind, confidence, corner, rule, face_edge = decided
    return result(kind, confidence, corner, rule, 1.0 if kind == "line" else 0.0, face_edge)


def classify_contact(
    image: Any,
    sensor_or_pitch: Any,
    *,
    point_size: float = _POINT_SIZE,
    **preparation: Unpack[Preparation],
) -> ContactShape:
    """Contact type of a tactile image, with edge and corner measures.

    Parameters
    ----------
    image : array_like, shape (rows, cols)
        Raw frame, calibrated reading or pressure map.
    sensor_or_pitch : float, (float, float) or object with ``taxel_pitch``
        Taxel pitch [m], or a sensor description.
    point_size : float, default 2.5e-3
        A compact contact no larger than this [m] (or 2 taxel pitches) is a point: its size
        is read at half its peak, which is sqrt(3)/2 of a rounded (Hertz) contact's width,
        allowing for the cover's blur and for saturation (see the module notes).
    **preparation
        `calibrated`, `smoothing`, `baseline`, `defects`, `noise` and `reference`, passed
        on to `prepare` with its defaults (so that this agrees with `extract`).

    Returns
    -------
    ContactShape

    Notes
    -----
    The seed (section 2.1) classifies from Canny edges, a line fit and a circle fit with
    their RMS errors, and the number of edges. Here the contact region itself is measured:
    its extent (thickness, elongation) separates bands from faces, a band's centre line
    and circle (fitted to all its taxels, weighted by signal) separate lines from arcs by
    how much the band bows, its size at half its peak separates points, the lobes of its
    outline find vertices, and the number of regions, high points and holes separates
    textures. The rules and their thresholds are in the module notes.

    Examples
    --------
    >>> y, x = np.mgrid[:64, :64]
    >>> band = (np.abs(y - 0.5 * x - 16) < 3).astype(float)  # a straight edge pressed in
    >>> shape = classify_contact(band, 0.5e-3)
    >>> shape.contact_type, round(float(np.degrees(shape.line.angle_rad)), 1)
    ('line', 26.7)
    >>> classify_contact(np.zeros((16, 16)), 1e-3).contact_type
    'none'
    """
    point_size = check_positive("point_size", point_size)
    prepared = prepare(image, sensor_or_pitch, **preparation)
    contact = contact_regions(prepared)
    count, textured, (holes, slots, explained) = textured_gaps(prepared, contact)
    return shape_core(
        prepared,
        contact,
        n_holes=len(holes),
        n_slots=len(slots),
        explained=explained,
        high_point_count=count,
        textured=textured,
        point_size=point_size,
    )
