"""Contact regions: presence, centroid, area, force, principal axes, orientation."""

from __future__ import annotations

import math
from dataclasses import replace
from typing import Any, Unpack

import cv2
import numpy as np

from taxel.features._image import Preparation, Prepared, prepare
from taxel.features._moments import binary_moments
from taxel.features._pressure_centre import pressure_centre
from taxel.features._record import record
from taxel.features._window import (
    catchment_reach,
    contact_box,
    contact_window,
    depths_in_taxels,
)

__all__ = [
    "Contact",
    "ContactRegion",
    "catchment_reach",
    "contact_regions",
    "felt_forces",
    "find_contact",
    "region_moments",
    "signal_moments",
]

# The read-back's centre of pressure is kept within this many cover depths of the image's
_APART_DEPTHS = 2.0


@record
class ContactRegion:
    """One connected contact region.

    Attributes
    ----------
    centroid_index : (float, float)
        Centre of pressure as (row, col) taxel indices: the centroid weighted by the
        unsmoothed signal above the baseline (the smoothing mirrors the image at the
        array's border, which pulled a contact there inward: by 0.3 taxel at the default
        smoothing, more with more). Of the only region, given a sensor whose raw frame
        reads back to pressure, the contact's (see `Contact`).
    centroid_m : (float, float)
        The same point (x, y) in the sensor frame [m].
    area_taxels : int
        Number of taxels of the region whose unsmoothed value clears the low threshold.
    area_m2 : float
        Contact area [m^2].
    total_force_n : float or None
        When the image is calibrated, the pressure times taxel area summed over the
        region and the taxels around it that the cover spreads its load into [N] (see
        `find_contact`); else None.
    major_axis_m, minor_axis_m : float
        Full axis lengths of the ellipse with the region's second moments [m]
        (``4 sqrt(lambda)``, as for a uniform ellipse).
    orientation_rad : float
        Angle of the major axis from the sensor's +x towards +y, in (-pi/2, pi/2] [rad].
    peak : float
        Largest input value in the region [image units].
    touches_border : bool
        Whether the region reaches the edge of the array (it may continue beyond).
    """

    centroid_index: tuple[float, float]
    centroid_m: tuple[float, float]
    area_taxels: int
    area_m2: float
    total_force_n: float | None
    major_axis_m: float
    minor_axis_m: float
    orientation_rad: float
    peak: float
    touches_border: bool


@record
class Contact:
    """Contact over the whole image: the union of its regions, and each region.

    Attributes
    ----------
    present : bool
    centroid_index, centroid_m : (float, float) or None
        Centre of pressure of all regions together (taxel indices; sensor frame [m]).
        Given a sensor whose raw frame its transducer reads back to pressure (an FTIR
        camera's, `taxel.transducers.FtirTransducer`), that pressure's centre over the
        contact and as far around it as the noise allows (see `find_contact`); else
        the regions' signal-weighted centroids together.
    area_m2 : float
        Total contact area [m^2].
    total_force_n : float or None
        Total force [N] when the image is calibrated: the regions' forces together.
    major_axis_m, minor_axis_m, orientation_rad : float
        Principal axes of all contact taxels together (see `ContactRegion`).
    regions : tuple of ContactRegion
        Largest first.
    """

    present: bool
    centroid_index: tuple[float, float] | None
    centroid_m: tuple[float, float] | None
    area_m2: float
    total_force_n: float | None
    major_axis_m: float
    minor_axis_m: float
    orientation_rad: float
    regions: tuple[ContactRegion, ...]


def _axes(
    count: np.ndarray, s_r: np.ndarray, s_c: np.ndarray, s_rr, s_cc, s_rc, pitch
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Ellipse axes [m] and orientation from unweighted moment sums (vectorised)."""
    mean_r, mean_c = s_r / count, s_c / count
    # +1/12: a taxel is a unit square, not a point; keeps one taxel's axes at ~1 pitch
    var_y = (s_rr / count - mean_r**2 + 1.0 / 12.0) * pitch[0] ** 2
    var_x = (s_cc / count - mean_c**2 + 1.0 / 12.0) * pitch[1] ** 2
    cov = (s_rc / count - mean_r * mean_c) * pitch[0] * pitch[1]
    half_trace = (var_x + var_y) / 2
    root = np.sqrt(((var_x - var_y) / 2) ** 2 + cov**2)
    major = 4.0 * np.sqrt(half_trace + root)
    minor = 4.0 * np.sqrt(np.maximum(half_trace - root, 0.0))
    angle = 0.5 * np.arctan2(2 * cov, var_x - var_y)
    angle = np.where(angle <= -math.pi / 2 + 1e-12, angle + math.pi, angle)
    return major, minor, angle


def _axes_of(
    count: float, mu20: float, mu02: float, mu11: float, pitch: tuple[float, float]
) -> tuple[float, float, float]:
    """`_axes` for one region, from its central moments (plain floats: no array overhead)."""
    var_y = (mu02 / count + 1.0 / 12.0) * pitch[0] ** 2
    var_x = (mu20 / count + 1.0 / 12.0) * pitch[1] ** 2
    cov = mu11 / count * pitch[0] * pitch[1]
    half_trace = (var_x + var_y) / 2
    root = math.hypot((var_x - var_y) / 2, cov)
    angle = 0.5 * math.atan2(2 * cov, var_x - var_y)
    if angle <= -math.pi / 2 + 1e-12:
        angle += math.pi
    return 4.0 * math.sqrt(half_trace + root), 4.0 * math.sqrt(max(half_trace - root, 0.0)), angle


def region_moments(prepared: Prepared, mask: np.ndarray) -> tuple[dict, dict]:
    """Image moments of a contact region and of its signal above the baseline (internal).

    The binary moments are taken on the contact's window alone (see `binary_moments`); of
    the signal's, m00, m10, m01 and the central moments are those of the whole image.
    With one region, kept in ``prepared.memo`` for the other features.
    """
    if prepared.n_regions == 1 and "moments" in prepared.memo:
        return prepared.memo["moments"]
    rows, cols = contact_window(prepared)
    binary = binary_moments(mask[rows, cols], rows.start, cols.start)
    # the signal is 0 off the contact: its moments are taken in the window's rows (whole
    # rows, so x is unchanged) and moved down to the image's origin; the central moments
    # do not move
    signal = prepared.smooth[rows] - np.float32(prepared.baseline)
    signal *= mask[rows]
    window = cv2.moments(signal)
    weighted = {key: window[key] for key in ("m00", "m10", "mu20", "mu11", "mu02")}
    weighted["m01"] = window["m01"] + rows.start * window["m00"]
    if prepared.n_regions == 1:
        prepared.memo["moments"] = (binary, weighted)
    return binary, weighted


def signal_moments(prepared: Prepared, mask: np.ndarray) -> dict[str, float]:
    """Image moments of the unsmoothed signal above the baseline over `mask` (internal).

    Read in the contact window's rows (whole rows: the columns need no shift), m01 moved
    down to the image's origin; taxels below the baseline weigh 0. With one region, kept in
    ``prepared.memo``.
    """
    one = prepared.n_regions == 1 and mask is prepared.mask
    if one and "signal moments" in prepared.memo:
        return prepared.memo["signal moments"]
    rows = contact_window(prepared)[0]
    signal = prepared.image[rows] - np.float32(prepared.baseline)
    np.maximum(signal, 0.0, out=signal)  # a taxel's noise below the baseline weighs nothing
    signal *= mask[rows]
    moments = cv2.moments(signal)
    moments["m01"] += rows.start * moments["m00"]
    if one:
        prepared.memo["signal moments"] = moments
    return moments


def _signal_centre(prepared: Prepared, mask: np.ndarray) -> tuple[float, float] | None:
    """Centroid (row, col) of the unsmoothed signal above the baseline over `mask`, or None.

    The taxels below the baseline weigh 0, so the centroid lies among the mask's taxels;
    None when no taxel is above it.
    """
    moments = signal_moments(prepared, mask)
    if not moments["m00"] > 0:
        return None
    return moments["m01"] / moments["m00"], moments["m10"] / moments["m00"]


def _one_region(prepared: Prepared) -> Contact:
    """`contact_regions` for one region, from image moments (the usual case, ~5x faster)."""
    mask = prepared.mask
    binary, _ = region_moments(prepared, mask)
    count = binary["m00"]
    centre = _signal_centre(prepared, mask)
    if centre is not None:
        row, col = centre
    else:
        row, col = binary["m01"] / count, binary["m10"] / count
    major, minor, angle = _axes_of(
        count, binary["mu20"], binary["mu02"], binary["mu11"], prepared.pitch
    )
    image = prepared.image
    window = contact_window(prepared)
    inside, within = image[window], mask[window]
    above = (inside >= np.float32(prepared.low)).view(np.uint8) & within
    raw_count = cv2.countNonZero(above) or int(count)
    peak = prepared.memo["peak"] = cv2.minMaxLoc(inside, within)[1]  # (see `half_region`)
    left, top, width, height = contact_box(prepared)
    border = (
        left == 0 or top == 0 or left + width == mask.shape[1] or top + height == mask.shape[0]
    )
    force = None
    if prepared.calibrated:
        force = float(felt_forces(prepared)[0])
    rows, cols = mask.shape
    row_pitch, col_pitch = prepared.pitch
    centroid_m = ((col - (cols - 1) / 2) * col_pitch, (row - (rows - 1) / 2) * row_pitch)
    area = raw_count * prepared.taxel_area
    region = ContactRegion(
        (row, col), centroid_m, int(raw_count), area, force, major, minor, angle,
        float(peak), border,
    )  # fmt: skip
    return Contact(
        True, (row, col), centroid_m, area, force, region.major_axis_m, region.minor_axis_m,
        region.orientation_rad, (region,),
    )  # fmt: skip


def contact_regions(prepared: Prepared) -> Contact:
    """Measure the contact regions of a prepared image (the core of `find_contact`).

    Parameters
    ----------
    prepared : Prepared
        From `taxel.features.prepare`.

    Returns
    -------
    Contact
    """
    n = prepared.n_regions
    if n == 0:
        return Contact(False, None, None, 0.0, None, 0.0, 0.0, 0.0, ())
    contact = _one_region(prepared) if n == 1 else _several_regions(prepared)
    if prepared.read_back is not None:
        centre = pressure_centre(prepared, prepared.read_back)
        # the same contact, weighed two ways: more than two cover depths from the image's
        # centre (6.8 taxels at most on the 1287 vhdta128 frames of the features
        # benchmark, 7.8 taxels to two depths), the read-back weighs what the frame's
        # model gets wrong (uneven lighting, an offset under separate contacts), not the
        # contact
        if centre is not None and contact.centroid_index is not None:
            apart = math.dist(centre, contact.centroid_index)
            if apart <= depths_in_taxels(prepared, _APART_DEPTHS):
                return _centred(contact, centre, prepared)
    return contact


def _centred(contact: Contact, centre: tuple[float, float], prepared: Prepared) -> Contact:
    """`contact` with its centre of pressure at `centre` (row, col); one region's too."""
    rows, cols = prepared.mask.shape
    row_pitch, col_pitch = prepared.pitch
    row, col = centre
    centroid_m = ((col - (cols - 1) / 2) * col_pitch, (row - (rows - 1) / 2) * row_pitch)
    regions = contact.regions
    if len(regions) == 1:
        regions = (replace(regions[0], centroid_index=centre, centroid_m=centroid_m),)
    return replace(contact, centroid_index=centre, centroid_m=centroid_m, regions=regions)


def felt_forces(prepared: Prepared) -> np.ndarray:
    """Force [N] of each region of a calibrated image, its load's tails included.

    Each region takes the taxels within `catchment_reach` of it (chessboard distance)
    that are nearer to it than to another region, grown a taxel at a time: the contact's
    own taxels miss the load the cover spreads around them (a 2 N sphere on vhdta128's
    calibrated frame reads 1.76 N over its contact, 1.99 N with its catchment).
    """
    reach = catchment_reach(prepared)
    image = prepared.image
    if prepared.force_level:  # a given baseline: the pressure above it carries the force
        image = image - np.float32(prepared.force_level)
    square = np.ones((3, 3), np.uint8)
    if prepared.n_regions == 1:
        grown = cv2.dilate(prepared.mask, np.ones((2 * reach + 1,) * 2, np.uint8))
        return np.array([float(cv2.sumElems(image * grown)[0]) * prepared.taxel_area])
    # labels grown a ring at a time into the unlabelled taxels: nearest region first
    labels = prepared.labels.astype(np.float32)  # (exact for any label cv2 can number)
    for _ in range(reach):
        grown = cv2.dilate(labels, square)
        labels = np.where(labels > 0, labels, grown)
    keys = labels.astype(np.int64).ravel()
    sums = np.bincount(keys, weights=image.ravel(), minlength=prepared.n_regions + 1)
    return sums[1:] * prepared.taxel_area


def _region_sums(labels: np.ndarray, size: int, terms: np.ndarray) -> np.ndarray:
    """Sums of each row of `terms` (k, n) per label 1 .. size - 1, shape (k, size - 1).

    One `np.bincount` for all the rows: row j's labels are shifted by j * size, so each sum
    takes the same terms in the same order as a `bincount` of that row alone would.
    """
    count = len(terms)
    keys = (labels + np.arange(0, size * count, size)[:, None]).ravel()
    sums = np.bincount(keys, terms.ravel(), minlength=size * count)
    return sums.reshape(count, size)[:, 1:]


def _label_terms(prepared: Prepared) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The contact taxels' labels, values (float64) and the terms summed per region.

    The terms' rows: 1, row, col, row^2, col^2, row col, the signal above the baseline (w),
    w row, w col.
    """
    labels = prepared.labels
    # the contact taxels in raster order, as np.nonzero(labels) gives them (its search of
    # a boolean image in one dimension is several times quicker), read by their flat indices
    flat = np.flatnonzero(prepared.mask.view(bool))
    rows, cols = np.divmod(flat, labels.shape[1])
    values = prepared.image.ravel().take(flat).astype(np.float64)
    terms = np.empty((9, rows.size))
    terms[0] = 1.0
    rows_f, cols_f, weight = terms[1], terms[2], terms[6]
    rows_f[:], cols_f[:] = rows, cols
    np.square(rows_f, out=terms[3])
    np.square(cols_f, out=terms[4])
    np.multiply(rows_f, cols_f, out=terms[5])
    np.subtract(values, prepared.baseline, out=weight)  # unsmoothed, as `_signal_centre`
    np.maximum(weight, 0.0, out=weight)
    np.multiply(weight, rows_f, out=terms[7])
    np.multiply(weight, cols_f, out=terms[8])
    return labels.ravel().take(flat), values, terms


def _several_regions(prepared: Prepared) -> Contact:
    """`contact_regions` for two regions or more, from sums per region label."""
    labels = prepared.labels
    size = prepared.n_regions + 1
    lab, values, terms = _label_terms(prepared)
    sums = _region_sums(lab, size, terms)
    # the whole contact as one more column: each measure below is then the whole contact's
    # there, by the same operations on its sums
    sums = np.concatenate((sums, sums.sum(axis=1, keepdims=True)), axis=1)
    count, s_r, s_c, s_rr, s_cc, s_rc, s_w, w_r, w_c = sums[:9]
    # the area counts taxels whose unsmoothed value clears the low threshold: smoothing
    # widens a contact by about its sigma, thresholding the raw values does not
    raw_count = np.bincount(lab[values >= prepared.low], minlength=size)[1:]
    raw_count = np.where(raw_count > 0, raw_count, count[:-1])
    areas = (np.append(raw_count, raw_count.sum()) * prepared.taxel_area).tolist()
    safe = np.where(s_w > 0, s_w, 1.0)
    cent_r = np.where(s_w > 0, w_r / safe, s_r / count).tolist()
    cent_c = np.where(s_w > 0, w_c / safe, s_c / count).tolist()
    major, minor, angle = (
        axis.tolist() for axis in _axes(count, s_r, s_c, s_rr, s_cc, s_rc, prepared.pitch)
    )
    peaks = np.full(size, -np.inf)
    np.maximum.at(peaks, lab, values)
    # the labels on the array's border (label 0 included, never read)
    border = np.zeros(size, bool)
    border[np.concatenate((labels[0], labels[-1], labels[:, 0], labels[:, -1]))] = True
    forces: list[float | None] = [None] * size
    if prepared.calibrated:
        region_forces = felt_forces(prepared)
        forces = [*region_forces.tolist(), float(region_forces.sum())]
    half_r, half_c = (labels.shape[0] - 1) / 2, (labels.shape[1] - 1) / 2
    row_pitch, col_pitch = prepared.pitch
    in_frame = [
        ((col - half_c) * col_pitch, (row - half_r) * row_pitch)
        for row, col in zip(cent_r, cent_c, strict=True)
    ]
    # (Python floats: the same values as numpy's scalars, quicker to read)
    taxels, peak, touches = raw_count.tolist(), peaks.tolist(), border.tolist()
    regions = [
        ContactRegion(
            centroid_index=(cent_r[i], cent_c[i]),
            centroid_m=in_frame[i],
            area_taxels=int(taxels[i]),
            area_m2=areas[i],
            total_force_n=forces[i],
            major_axis_m=major[i],
            minor_axis_m=minor[i],
            orientation_rad=angle[i],
            peak=peak[i + 1],
            touches_border=touches[i + 1],
        )
        for i in np.argsort(-count[:-1], kind="stable").tolist()
    ]
    return Contact(
        present=True,
        centroid_index=(cent_r[-1], cent_c[-1]),
        centroid_m=in_frame[-1],
        area_m2=areas[-1],
        total_force_n=forces[-1],
        major_axis_m=major[-1],
        minor_axis_m=minor[-1],
        orientation_rad=angle[-1],
        regions=tuple(regions),
    )


def find_contact(
    image: Any,
    sensor_or_pitch: Any,
    **preparation: Unpack[Preparation],
) -> Contact:
    """Find the contact regions of a tactile image and measure each.

    Parameters
    ----------
    image : array_like, shape (rows, cols)
        Raw frame, calibrated reading or pressure map [Pa]; larger means more pressure.
    sensor_or_pitch : float, (float, float) or object with ``taxel_pitch``
        Taxel pitch [m].
    **preparation
        `calibrated` (the image holds pressure [Pa]: the total force is then reported
        [N]), `smoothing`, `baseline`, `defects`, `noise` and `reference`, passed on to
        `prepare` with its defaults (so that this agrees with `extract`).

    Returns
    -------
    Contact

    Notes
    -----
    Contact taxels are found by hysteresis on the smoothed image: a region is the connected
    set (8-neighbours) above a low threshold that holds at least one taxel above a high
    threshold. Both thresholds are the larger of a multiple of the noise sigma and a
    fraction of the contrast (see `taxel.features.prepare`).

    Given a sensor whose raw frame its transducer reads back to pressure (a textured
    FTIR camera behind an ideal readout, on a frame not calibrated; a tared frame's light
    is its step above the `reference`), the contact's centre of pressure is that
    pressure's, not the image's: the grey level follows the real contact area, which
    saturates, and light contact lies beyond the mask. The frame is read back signed
    (noise below the unloaded level reads negative and averages out), and weighted over
    the mask and over its bounding box grown by 0, 2, 4, 8, ... taxels up to the reach of
    its load (3.5 cover depths); the smallest of these windows is kept whose centre
    agrees with every larger one's within 2.5 noise sigmas (Lepski's rule). Where that
    reach crosses the array's edge and the sensor has a forward model, the windows run on
    into the array grown by it, with what the load on the array that explains the frame
    presses there (`taxel.reconstruction.extend_readings`): the cover spreads a load near
    the edge beyond it, where no taxel feels it. That assumes no load beyond the edge; a
    plate pressed across the edge has some, which is then read as pressing at the edge.

    The read-back assumes the model's unloaded level (its dark level and glass), which the
    background beyond the contact's reach checks: darker than it, or streaked darker
    (another glass), the frame is not the model's and its image is weighed; brighter (or
    darker by up to half a grey level) and lying on a plane (a camera's offset, uneven
    lighting), with half the array or more beyond the reach, the plane is taken out of the
    light when it stands over half a grey level somewhere, its tilts only where they stand
    3 standard errors clear of noise; else its level alone, from 3 standard errors. A
    read-back more than two cover depths from the image's centre is not kept either. A
    raw frame's lighting tilt steep enough to move the contact's cut is taken out before
    segmentation (`prepare`). On 60 of the features benchmark's vhdta128 frames under a
    ramp across the array (median / p95 of the centroid's error, taxels): 1 grey level
    0.18 / 1.4 (0.31 / 3.6 before either), 4 levels 0.19 / 8.7 (1.6 / 16.5), 8 levels
    0.19 / 8.3 (2.8 / 25.7). What is left: a texture or slotted plate over the whole
    array (no background to read the lighting from), and a contact whose reach leaves
    under half the array, whose level is not taken out. Tare such frames (`reference`),
    which measures their unloaded level.

    A calibrated image's force is summed over each region and its catchment: the taxels
    within 3.5 cover depths of it (at least 2 taxels; `catchment_reach`) nearer to it than
    to another region, since the cover spreads a load beyond the contact the image shows
    (`felt_forces`).

    Examples
    --------
    >>> pressure = np.zeros((16, 16)); pressure[4:8, 10:12] = 1e4  # 1 mm pitch, 8 mm^2
    >>> contact = find_contact(pressure, 1e-3, calibrated=True, smoothing=0)
    >>> contact.present, round(contact.area_m2 * 1e6, 3), round(contact.total_force_n, 4)
    (True, 8.0, 0.08)
    >>> [round(v * 1e3, 3) for v in contact.centroid_m]  # x, y [mm]
    [3.0, -2.0]
    """
    return contact_regions(prepare(image, sensor_or_pitch, **preparation))
