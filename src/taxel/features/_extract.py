"""All passive features of one tactile image in one call, as a JSON-ready result."""

from __future__ import annotations

import json
import math
from dataclasses import fields
from typing import Any

import numpy as np

from taxel._validation import check_positive, check_range
from taxel.features._contact import Contact, contact_regions
from taxel.features._fitting import CircleFit, LineFit, fit_line_and_circle
from taxel.features._gaps import HoleReport, SlotReport
from taxel.features._holes import diameter_test, outline_contours, outline_taxels
from taxel.features._image import prepare
from taxel.features._record import record
from taxel.features._shape import ContactShape, shape_core
from taxel.features._surface import ContactPlane, checked_depth, plane_core
from taxel.features._texture import TEXTURE_SIGMA, Texture, texture_core
from taxel.features._textured import judged_gaps
from taxel.frames import as_pose

__all__ = ["ContactPose", "TactileFeatures", "extract"]


@record
class ContactPose:
    """Where the contact is and how it lies, in the sensor frame and the robot's base frame.

    Attributes
    ----------
    position_sensor_m : (float, float, float)
        Centre of pressure on the cover's surface in the sensor frame [m] (z = -depth there
        when a depth map is given, else 0).
    position_base_m : (float, float, float) or None
        The same point in the base frame [m]; None without a pose.
    axis_base : (float, float, float) or None
        Unit vector of the contact's major axis (or the fitted line) in the base frame.
    normal_base : (float, float, float) or None
        Unit contact normal in the base frame: the fitted plane's normal, else the sensor's
        +z (pointing from the sensor towards the object).
    """

    position_sensor_m: tuple[float, float, float]
    position_base_m: tuple[float, float, float] | None
    axis_base: tuple[float, float, float] | None
    normal_base: tuple[float, float, float] | None


@record
class TactileFeatures:
    """The passive features of one tactile image (Ellis seed, section 2.1).

    Attributes
    ----------
    contact : Contact
        Presence, regions, centroid, area, force, principal axes.
    pose : ContactPose or None
        The contact located in 3-D (None without contact).
    shape : ContactShape
        Contact type, edge and corner scores, the line and circle fits.
    holes : HoleReport
    slots : SlotReport
    plane : ContactPlane
        Planarity and, given depth, the contact plane's normal.
    texture : Texture
    """

    contact: Contact
    pose: ContactPose | None
    shape: ContactShape
    holes: HoleReport
    slots: SlotReport
    plane: ContactPlane
    texture: Texture

    @property
    def contact_type(self) -> str:
        """One of 'none', 'point', 'line', 'arc', 'surface', 'corner'."""
        return self.shape.contact_type

    def to_dict(self) -> dict[str, Any]:
        """Plain dictionary of the features (the JSON layout of ``taxel features --json``).

        Returns
        -------
        dict
            Keys: contact, contact_type, contact_confidence, contact_rule, contact_size_m,
            lobes, edge_score, corner_score,
            n_edges, line, circle, holes, slots, planarity, normal, texture, regions.
            Infinite or undefined numbers become None, as do contact_size_m and lobes when
            they were not measured (see `ContactShape`).
        """
        contact, shape, pose = self.contact, self.shape, self.pose
        line = shape.line
        circle = shape.circle
        data = {
            "contact": {
                "present": contact.present,
                "centroid_m": contact.centroid_m,
                "centroid_index": contact.centroid_index,
                "area_m2": contact.area_m2,
                "total_force_n": contact.total_force_n,
                "major_axis_m": contact.major_axis_m,
                "minor_axis_m": contact.minor_axis_m,
                "orientation_rad": contact.orientation_rad,
                "position_sensor_m": pose.position_sensor_m if pose else None,
                "centroid_base_m": pose.position_base_m if pose else None,
                "axis_base": pose.axis_base if pose else None,
                "normal_base": pose.normal_base if pose else None,
            },
            "contact_type": shape.contact_type,
            "contact_confidence": shape.confidence,
            "contact_rule": shape.rule,
            "contact_size_m": shape.size_m,
            "lobes": shape.lobes,
            "edge_score": shape.edge_score,
            "corner_score": shape.corner_score,
            "n_edges": shape.n_edges,
            "line": {
                "angle_rad": line.angle_rad if line else None,
                "offset_m": line.offset_m if line else None,
                "rms_m": line.rms_m if line else None,
            },
            "circle": {
                "center_m": circle.center_m if circle else None,
                "radius_m": circle.radius_m if circle else None,
                "rms_m": circle.rms_m if circle else None,
            },
            "holes": {
                "present": self.holes.present,
                "count": self.holes.count,
                "diameter_test": self.holes.diameter_test,
                "items": [_fields(hole) for hole in self.holes.items],
            },
            "slots": {
                "present": self.slots.present,
                "count": self.slots.count,
                "items": [_fields(slot) for slot in self.slots.items],
            },
            "planarity": self.plane.planarity,
            "uniformity": self.plane.uniformity,
            "fill": self.plane.fill,
            "normal": self.plane.normal,
            "tilt_rad": self.plane.tilt_rad,
            "texture": _fields(self.texture),
            "regions": [_fields(region) for region in contact.regions],
        }
        return _clean(data)

    def to_json(self, **options: Any) -> str:
        """The features as a JSON string (`to_dict`); `options` go to `json.dumps`."""
        return json.dumps(self.to_dict(), **options)


_FIELD_NAMES: dict[type, tuple[str, ...]] = {}  # per record class, its fields' names


def _fields(item: Any) -> dict[str, Any]:
    """A record's fields by name: ``dataclasses.asdict`` of a record of plain values.

    The fields hold numbers, strings, None and tuples of them, which `_clean` copies
    anyway: ``asdict``'s deep copy of each value (most of the time `to_dict` took) gives
    nothing more.
    """
    names = _FIELD_NAMES.get(type(item))
    if names is None:
        names = _FIELD_NAMES[type(item)] = tuple(field.name for field in fields(item))
    return {name: getattr(item, name) for name in names}


def _clean(value: Any) -> Any:
    """Tuples to lists, NumPy scalars to Python, non-finite floats to None."""
    if type(value) is float:  # (most values: tested first)
        return value if math.isfinite(value) else None
    if isinstance(value, dict):
        return {key: _clean(item) for key, item in value.items()}
    if isinstance(value, list | tuple):
        return [_clean(item) for item in value]
    if isinstance(value, np.generic):
        value = value.item()
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value


def _locate(
    contact: Contact,
    shape: ContactShape,
    plane: ContactPlane,
    depth: np.ndarray | None,
    pose: np.ndarray | None,
) -> ContactPose | None:
    if not contact.present or contact.centroid_m is None or contact.centroid_index is None:
        return None
    z = 0.0
    if depth is not None:
        row, col = (int(round(v)) for v in contact.centroid_index)
        z = -float(depth[row, col])
    position = (contact.centroid_m[0], contact.centroid_m[1], z)
    if pose is None:
        return ContactPose(position, None, None, None)
    # an edge's direction is the fitted line's; otherwise the contact's major axis
    use_line = shape.contact_type == "line" and shape.line is not None
    angle = shape.line.angle_rad if use_line and shape.line else contact.orientation_rad
    axis = (math.cos(angle), math.sin(angle), 0.0)
    normal = plane.normal if plane.normal is not None else (0.0, 0.0, 1.0)
    # `pose` was checked by `as_pose`: apply it as `transform_points` and
    # `transform_directions` do, without checking it again for each vector
    rotation_t = pose[:3, :3].T
    return ContactPose(
        position,
        tuple((np.asarray(position, np.float64) @ rotation_t + pose[:3, 3]).tolist()),
        tuple((np.asarray(axis, np.float64) @ rotation_t).tolist()),
        tuple((np.asarray(normal, np.float64) @ rotation_t).tolist()),
    )


def extract(
    image: Any,
    sensor_or_pitch: Any,
    *,
    pose: Any = None,
    depth: Any = None,
    calibrated: bool = False,
    smoothing: float = 1.0,
    baseline: float | None = None,
    point_size: float = 2.5e-3,
    texture_sigma: float = TEXTURE_SIGMA,
    defects: bool | None = None,
    noise: float | str | None = None,
    reference: Any = None,
) -> TactileFeatures:
    """Every passive feature of one tactile image, located on the sensor and in the base frame.

    Parameters
    ----------
    image : array_like, shape (rows, cols)
        A raw frame (8 or 16 bit), a calibrated reading or a pressure map [Pa] of any
        array geometry; larger values mean more pressure.
    sensor_or_pitch : float, (float, float) or object with ``taxel_pitch``
        Taxel pitch [m], a (row, column) pair, or a sensor description (a
        `taxel.sensor.TactileSensor`: its cover depth then decides `defects`, and an
        FTIR camera's raw frame is read back to pressure for the centre of pressure, see
        `find_contact`). The taxels
        must be square to 1 %: the contact type and the holes are measured in taxels
        (resample an image of oblong taxels first; `find_contact` takes any pitch).
    pose : array_like, shape (4, 4), optional
        ``T_BS``, the sensor frame in the robot's base frame (see `taxel.frames`).
    depth : array_like, shape (rows, cols), optional
        Indentation of the cover's surface [m], positive into the cover, for sensors that
        measure displacement or depth: gives the contact plane's normal and the contact's z
        (within +-1 m).
    calibrated : bool, default False
        The image holds pressure [Pa], so areas carry a total force [N] (refused for an
        integer image of a sensor that reads frames: its raw codes).
    smoothing : float, default 1.0
        Gaussian sigma before segmentation and edges [taxels].
    baseline : float, optional
        No-contact level [image units]; estimated as the smoothed image's minimum if omitted
        (a dead taxel near it read as its neighbours: see `prepare`).
    point_size : float, default 2.5e-3
        Compact contacts up to this size [m] are points, their size read at half their
        peak (see `classify_contact`).
    texture_sigma : float, default 2.0
        Gaussian sigma before counting texture maxima [taxels].
    defects : bool, optional
        Remove bright sensor defects narrower than 3 taxels (scratches on an FTIR sensor's
        glass, hot pixels) first; by default only in an uncalibrated image of a sensor whose
        cover is 3 or more taxels deep, never in a calibrated reading or a pressure map
        (which a deconvolution can make as sparse as the load; see `prepare`).
    noise : float or "sensor", optional
        Noise standard deviation of one taxel [image units], when the sensor's is known;
        estimated from the image if omitted (a texture as fine as the taxels over the whole
        array then reads as noise), except on an image too small to give it (under 16
        interior taxels), which takes the sensor's, or needs `noise` given a bare pitch.
        "sensor": the noise of the sensor's raw frames (`sensor_noise`) on any raw frame
        (see `prepare`).
    reference : array_like, shape (rows, cols), optional
        The sensor's unloaded frame, or the mean of several, subtracted first (a tare):
        it removes the fixed pattern no contact makes (an FTIR glass's scratches, taxel
        offsets), so that blank frames read as blank; `defects` then defaults to False.

    Returns
    -------
    TactileFeatures
        Convert with ``.to_dict()`` or ``.to_json()``.

    Notes
    -----
    The image is validated, cleaned, smoothed and segmented once (`prepare`), which also
    finds the contact's outlines; the contact's moments, its outlines and one line and
    circle fitted to them are then shared by the contact type, the gaps, the seed's hole
    test and the plane, and each rule computes only the measures it needs. See each
    feature's function for its method: `find_contact`, `classify_contact`, `detect_holes`,
    `detect_slots`, `contact_plane`, `texture_measures`. (The seed's Canny edges remain
    available from `detect_edges`; the features use the contact's outline instead.)

    Examples
    --------
    >>> y, x = np.mgrid[:64, :64]
    >>> frame = np.where(np.abs(y - 32) < 3, 200, 20).astype(np.uint8)  # a straight edge
    >>> features = extract(frame, 0.25e-3, pose=np.eye(4))
    >>> features.contact_type, features.holes.present, features.slots.present
    ('line', False, False)
    >>> [round(v * 1e3, 3) for v in features.pose.position_base_m]  # on the sensor's centre
    [0.0, 0.125, 0.0]
    """
    prepared = prepare(
        image,
        sensor_or_pitch,
        calibrated=calibrated,
        smoothing=smoothing,
        baseline=baseline,
        defects=defects,
        noise=noise,
        reference=reference,
    )
    point_size = check_positive("point_size", point_size)
    texture_sigma = check_range("texture_sigma", texture_sigma, 0.0, 20.0, low_inclusive=False)
    pose_matrix = None if pose is None else as_pose(pose)
    depth_map = checked_depth(depth, prepared.image.shape)
    contact = contact_regions(prepared)
    texture = texture_core(prepared, sigma=texture_sigma)
    textured, (holes, slots, explained) = judged_gaps(
        prepared, contact, texture.maxima_count, texture_sigma
    )
    contours = list(outline_contours(prepared))
    cols, rows = outline_taxels(prepared, contours)
    fits: list[tuple[LineFit, CircleFit] | None] = []

    def outline_fit() -> tuple[LineFit, CircleFit] | None:
        # one line and circle through the outline, for the type and the hole test, fitted
        # when first asked for: a band's type and a convex contact's hole test do without
        if not fits:
            x, y = cols.astype(float), rows.astype(float)
            fits.append(fit_line_and_circle(x, y) if cols.size >= 3 else None)
        return fits[0]

    shape = shape_core(
        prepared,
        contact,
        n_holes=len(holes),
        n_slots=len(slots),
        explained=explained,
        high_point_count=texture.maxima_count,
        textured=textured,
        point_size=point_size,
        contours=contours,
        outline_fit=outline_fit,
    )
    plane = plane_core(prepared, depth_map, contours=contours)
    # the outline's circle, if the type fitted it; else the test fits the circle alone
    circle = fits[0][1] if fits and fits[0] else None
    test = diameter_test(prepared, cols, rows, circle, contours=contours)
    hole_report = HoleReport(bool(holes), len(holes), tuple(holes), test)
    slot_report = SlotReport(bool(slots), len(slots), tuple(slots))
    located = _locate(contact, shape, plane, depth_map, pose_matrix)
    return TactileFeatures(contact, located, shape, hole_report, slot_report, plane, texture)
