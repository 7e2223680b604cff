"""The average cross-section of a straight edge pressed on the sensor (Ellis seed, section 2.2).

"The cross-section analysis was performed by extracting the edges and fitting to a curve (in
this case, the best fit was to a line). The cross-section was estimated by taking an average
normal to the fitted curve; the width of the cross-section was determined by the mean width
... This average cross-section was then fit to an arc." This module does exactly that on one
tactile image, and returns the numbers the edge-radius table is made of.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from scipy import ndimage

from taxel._validation import as_finite_array, check_positive
from taxel.features import detect_edges, fit_circle, fit_line, pitch_pair

__all__ = ["SECTION_DESCRIPTORS", "EdgeCrossSection", "check_section_fits", "edge_cross_section"]

# what the table compares, in this order (widths and areas in m, the peak in image units)
SECTION_DESCRIPTORS: tuple[str, ...] = (
    "area",
    "peak",
    "width_25",
    "width_50",
    "width_75",
    "arc_radius",
)
_HALF_SPAN = 7.0e-3  # the cross-section is sampled this far either side of the line [m]
_SAMPLES_PER_TAXEL = 4
_REFINEMENTS = 3
_MARGIN = 1.5  # taxels kept clear of the image border when sampling
_ARC_HEIGHT = 1.0e-3  # length scale of the normalised intensity in the arc fit [m]
_END_MARGIN = 3e-3  # the profile is averaged this far inside the ends of the edge's chord [m]
_TRIM = 0.2  # fraction cut from each end before averaging the lines
_COVERED = 0.8  # share of the fitted line that must be in contact for a straight edge


@dataclass(frozen=True)
class EdgeCrossSection:
    """The average cross-section of a straight edge in one tactile image.

    Attributes
    ----------
    angle_rad : float
        Direction of the edge's line in the sensor frame, in [0, pi) [rad].
    offset_m : float
        Signed distance of the line from the sensor's centre along its normal
        (-sin, cos) [m].
    chord_m : float
        Length of the line inside the active area [m].
    normal_force : float
        Force of the press [N].
    force_per_length : float
        normal_force / loaded_length_m [N/m], the line load that sets the cross-section.
    positions : numpy.ndarray
        Distances across the line at which the profile is sampled [m].
    profile : numpy.ndarray
        Mean image value above the baseline at each position [image units].
    baseline : float
        No-contact level of the image [image units].
    n_lines : int
        Image lines (one taxel apart along the edge) averaged into the profile.
    descriptors : dict of str to float
        ``area`` (integral of the profile [units m]), ``peak`` [units], ``width_25``,
        ``width_50``, ``width_75`` (widths at 25, 50 and 75 % of the peak [m]) and
        ``arc_radius`` (radius of the arc fitted to the top of the profile [m]).
    loaded_length_m : float, optional
        The length of edge that carries the force [m], read off the imprint: its signal
        summed along the whole edge over the cross-section's. Shorter than the chord, since
        the load falls off where the edge leaves the pad, and by how much depends on how
        it leaves it (square to a side, or into a corner). None: the chord.
    """

    angle_rad: float
    offset_m: float
    chord_m: float
    normal_force: float
    force_per_length: float
    positions: np.ndarray = field(repr=False)
    profile: np.ndarray = field(repr=False)
    baseline: float
    n_lines: int
    descriptors: dict[str, float] = field(default_factory=dict)
    loaded_length_m: float | None = None

    def vector(self) -> np.ndarray:
        """The descriptors as an array in the order of `SECTION_DESCRIPTORS`."""
        return np.array([self.descriptors[name] for name in SECTION_DESCRIPTORS])


def _chord(angle: float, offset: float, half_x: float, half_y: float) -> float:
    """Length of the line {offset n + t d} inside the rectangle |x| <= half_x, |y| <= half_y."""
    direction = (math.cos(angle), math.sin(angle))
    point = (-math.sin(angle) * offset, math.cos(angle) * offset)
    low, high = -math.inf, math.inf
    for axis, half in ((0, half_x), (1, half_y)):
        if abs(direction[axis]) < 1e-12:
            if abs(point[axis]) > half:
                return 0.0
            continue
        t1 = (-half - point[axis]) / direction[axis]
        t2 = (half - point[axis]) / direction[axis]
        low, high = max(low, min(t1, t2)), min(high, max(t1, t2))
    return max(high - low, 0.0)


def _normal_lines(
    shape: tuple[int, ...],
    pitch: tuple[float, float],
    angle: float,
    offset: float,
    across: np.ndarray,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Lines normal to the edge, one taxel apart along all of it: (along, rows, columns).

    `along` [m] is each line's position along the edge; the rows and columns (fractional
    image indices, shape (n_lines, n_across)) are where its `across` samples fall.
    """
    rows, cols = shape
    step = min(pitch)
    reach = math.hypot(rows * pitch[0], cols * pitch[1]) / 2
    along = np.arange(-reach, reach + step / 2, step)
    direction = np.array([math.cos(angle), math.sin(angle)])
    normal = np.array([-math.sin(angle), math.cos(angle)])
    points = offset * normal + along[:, None, None] * direction + across[None, :, None] * normal
    col = points[..., 0] / pitch[1] + (cols - 1) / 2
    row = points[..., 1] / pitch[0] + (rows - 1) / 2
    return along, row, col


def _sample(
    image: np.ndarray,
    pitch: tuple[float, float],
    angle: float,
    offset: float,
    across: np.ndarray,
) -> tuple[np.ndarray, np.ndarray]:
    """Image values on lines normal to the edge, one taxel apart; (n_lines, n_across)."""
    rows, cols = image.shape
    along, row, col = _normal_lines(image.shape, pitch, angle, offset, across)
    inside = (
        (col >= _MARGIN)
        & (col <= cols - 1 - _MARGIN)
        & (row >= _MARGIN)
        & (row <= rows - 1 - _MARGIN)
    ).all(axis=1)
    # keep clear of where the edge leaves the pad: the load is not uniform there
    centre_col, centre_row = col[:, col.shape[1] // 2], row[:, row.shape[1] // 2]
    clear = _END_MARGIN / min(pitch)
    inside &= (
        (centre_col >= clear)
        & (centre_col <= cols - 1 - clear)
        & (centre_row >= clear)
        & (centre_row <= rows - 1 - clear)
    )
    if not inside.any():
        return np.zeros((0, across.size)), along[:0]
    values = ndimage.map_coordinates(
        image, [row[inside].ravel(), col[inside].ravel()], order=1, mode="nearest"
    )
    return values.reshape(-1, across.size), along[inside]


def _loaded_length(
    image: np.ndarray,
    pitch: tuple[float, float],
    line: tuple[float, float],
    across: np.ndarray,
    profile: np.ndarray,
    ceiling: float,
) -> float:
    """Length of edge that carries the load [m]: the imprint's signal over the profile's.

    Every line normal to the edge, one taxel apart along the whole edge (outside the image
    reads no signal), is summed across and the sum integrated along the edge; over the area
    of the mean `profile` (a line's worth) this is the length of a uniform load of the same
    total. Each sample is capped at the profile plus `ceiling`, so that bright defects
    (glass scratches) along or across the edge add nothing: the imprint itself only falls
    below the profile towards the edge's ends.
    """
    _, row, col = _normal_lines(image.shape, pitch, *line, across)
    step = min(pitch)
    values = ndimage.map_coordinates(
        image, [row.ravel(), col.ravel()], order=1, mode="constant", cval=0.0
    ).reshape(row.shape)
    section = profile.clip(0.0, None)
    capped = np.minimum(values, section + ceiling)
    return float(capped.sum() * step / section.sum())


def _width(positions: np.ndarray, profile: np.ndarray, level: float) -> float:
    """Distance between the outermost crossings of `level`, interpolated linearly."""
    above = np.flatnonzero(profile > level)
    if above.size == 0:
        return 0.0
    first, last = int(above[0]), int(above[-1])
    if first == 0 or last == profile.size - 1:
        return float(positions[-1] - positions[0])
    left = np.interp(level, profile[first - 1 : first + 1], positions[first - 1 : first + 1])
    right = np.interp(level, profile[last : last + 2][::-1], positions[last : last + 2][::-1])
    return float(right - left)


def _arc_radius(positions: np.ndarray, profile: np.ndarray, peak: float) -> float:
    """Radius of the circle fitted to the profile's top half, heights in units of _ARC_HEIGHT."""
    top = profile > 0.5 * peak
    if np.count_nonzero(top) < 3:
        return 0.0
    heights = _ARC_HEIGHT * profile[top] / peak
    fit = fit_circle(np.column_stack((positions[top], heights)))
    return float(fit.radius_m) if math.isfinite(fit.radius_m) else 0.0


def section_reach(shape: tuple[int, int], pitch: tuple[float, float]) -> float:
    """How far [m] from the image's centre an edge's line may lie for its cross-section to fit.

    The section is sampled `_HALF_SPAN` either side of the line, kept `_MARGIN` taxels clear of
    the border; along the image's shorter side that leaves this much for the line's offset,
    less one taxel for the fitted line's error (it lies up to a taxel outward near the
    border, where the imprint is cut).
    """
    rows, cols = shape
    usable = min((rows - 1 - 2 * _MARGIN) * pitch[0], (cols - 1 - 2 * _MARGIN) * pitch[1])
    return max(usable / 2 - _HALF_SPAN - max(pitch), 0.0)


def check_section_fits(name: str, shape: tuple[int, int], pitch: tuple[float, float]) -> None:
    """Raise naming `name` when an image of `shape` cannot hold a whole cross-section.

    A cross-section is sampled 7 mm either side of the edge and kept 1.5 taxels clear of the
    image's border; an array narrower than that in either direction cannot show one along
    every orientation.
    """
    rows, cols = shape
    usable = min((rows - 1 - 2 * _MARGIN) * pitch[0], (cols - 1 - 2 * _MARGIN) * pitch[1])
    if usable < 2 * _HALF_SPAN:
        raise ValueError(
            f"`{name}` is too small for an edge cross-section: {rows} x {cols} taxels at "
            f"{pitch[0] * 1e3:g} x {pitch[1] * 1e3:g} mm leave {max(usable, 0.0) * 1e3:.1f} mm "
            f"clear of the border across the edge, and the section needs "
            f"{2 * _HALF_SPAN * 1e3:g} mm"
        )


def _centres(values: np.ndarray, across: np.ndarray, baseline: float) -> np.ndarray:
    """Centre of the part of each sampled line above a quarter of the image's contrast."""
    signal = values - baseline
    weights = np.clip(signal - 0.25 * signal.max(), 0.0, None)
    total = weights.sum(axis=1)
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(total > 0, (weights * across).sum(axis=1) / total, np.nan)


def edge_cross_section(
    image: Any, sensor_or_pitch: Any, *, normal_force: float
) -> EdgeCrossSection:
    """The average cross-section of a straight edge in a tactile image.

    Parameters
    ----------
    image : array_like, shape (rows, cols)
        A raw tactile frame (larger values: more pressure).
    sensor_or_pitch : float, (float, float) or object with ``taxel_pitch``
        Taxel pitch [m] or the sensor.
    normal_force : float
        Force of the press [N], to give the line load.

    Returns
    -------
    EdgeCrossSection

    Raises
    ------
    ValueError
        When the image shows no straight edge crossing the sensor.

    Notes
    -----
    1. Canny edges (`taxel.features.detect_edges`) and a total-least-squares line through
       them (`fit_line`): the two borders of the edge's imprint give its centre line.
    2. The line is refined three times by fitting a line to the intensity centres of the
       image sampled normal to it (robust to stray edges such as glass scratches).
    3. The image is sampled (bilinear) on lines normal to the edge, one taxel apart along
       it (keeping 3 mm clear of where the edge leaves the pad) and a quarter taxel apart
       across it, and averaged with a 20 % trimmed mean (glass scratches crossing the
       edge touch few lines): the cross-section. The baseline is the median of the
       profile's outer eighth on either side.
    4. Descriptors: the area under the profile, its peak, its widths at 25, 50 and 75 % of
       the peak, and the radius of a circle fitted (`fit_circle`) to its top half, the
       intensity scaled to a height of 1 mm at the peak.

    5. The loaded length: the imprint's signal summed over every line normal to the edge,
       one taxel apart along its whole chord, over the profile's area (each sample capped
       at the profile plus three standard deviations of the lines about it, so that glass
       scratches add nothing).

    The force is shared along the edge, so the cross-section depends on the line load
    F / loaded length rather than on F alone; the edge radius table interpolates in it.
    The load falls off over the last few millimetres where the edge leaves the pad, by
    an amount that depends on how it leaves it: an edge along the pad's diagonal ends in
    two corners and carries about 6 % more load per length in its middle than its chord
    gives, one at another angle 3-4 %. The loaded length follows that; the chord does not.

    Examples
    --------
    >>> rows, cols = np.mgrid[:64, :64]
    >>> ridge = 20 + 80 * np.exp(-((rows - 30.0) ** 2) / 8.0)  # an edge along x at row 30
    >>> section = edge_cross_section(ridge, 0.25e-3, normal_force=10.0)
    >>> round(math.degrees(section.angle_rad) % 180, 1), round(section.chord_m * 1e3, 2)
    (0.0, 16.0)
    >>> # the Gaussian's FWHM is 4.71 taxels; bilinear sampling of the taxels widens it a little
    >>> round(section.descriptors["width_50"] / 0.25e-3, 2)
    4.76
    """
    array = as_finite_array("image", image, ndim=2)
    normal_force = check_positive("normal_force", normal_force)
    pitch = pitch_pair(sensor_or_pitch)
    rows, cols = array.shape
    check_section_fits("image", (rows, cols), pitch)
    edges = detect_edges(array, pitch)
    if edges.points_m.shape[0] < 10:
        raise ValueError(
            f"`image` shows no edge to fit a line to ({edges.points_m.shape[0]} edge taxels)"
        )
    line = fit_line(edges.points_m)
    angle, offset = line.angle_rad, line.offset_m
    step = min(pitch) / _SAMPLES_PER_TAXEL
    across = np.arange(-_HALF_SPAN, _HALF_SPAN + step / 2, step)
    baseline = float(np.percentile(ndimage.uniform_filter(array, 3), 10))
    for _ in range(_REFINEMENTS):
        values, along = _sample(array, pitch, angle, offset, across)
        if values.shape[0] == 0:  # the line runs too near the border to sample
            break
        centres = _centres(values, across, baseline)
        good = np.isfinite(centres)
        if np.count_nonzero(good) < 10:
            break
        slope, intercept = np.polyfit(along[good], centres[good], 1)
        residual = centres[good] - (slope * along[good] + intercept)
        spread = 3.0 * max(float(np.median(np.abs(residual))), 0.05 * min(pitch))
        keep = np.abs(residual) <= spread
        slope, intercept = np.polyfit(along[good][keep], centres[good][keep], 1)
        # the line's point at `along` = 0 moves by `intercept` along the old normal
        old_normal = np.array([-math.sin(angle), math.cos(angle)])
        angle = (angle + math.atan(slope)) % math.pi
        normal = np.array([-math.sin(angle), math.cos(angle)])
        offset = float((offset + intercept) * old_normal @ normal)
    values, along = _sample(array, pitch, angle, offset, across)
    chord = _chord(angle, offset, cols * pitch[1] / 2, rows * pitch[0] / 2)
    if values.shape[0] < 5 and chord >= 0.5 * min(rows * pitch[0], cols * pitch[1]):
        raise ValueError(
            f"`image` shows its edge {abs(offset) * 1e3:.1f} mm from the sensor's centre, too "
            f"near the border: the cross-section is read {_HALF_SPAN * 1e3:g} mm either side "
            "of the edge, along 5 lines or more"
        )
    if chord < 0.5 * min(rows * pitch[0], cols * pitch[1]):
        raise ValueError(
            "`image` shows no straight edge across the sensor: the fitted line crosses "
            f"{chord * 1e3:.1f} mm of the active area"
        )
    # an edge presses all along its chord; a ball or a corner only in part of it. The lines
    # lie a taxel apart, and an oblique edge's load falls on a staircase of cells: a line
    # that passes between two steps reads low while its neighbours read the edge, so a line
    # counts as pressed when it or a neighbour is
    line_peaks = ndimage.maximum_filter1d(values.max(axis=1) - baseline, 3, mode="nearest")
    covered = float(np.mean(line_peaks > 0.5 * line_peaks.max()))
    if covered < _COVERED:
        raise ValueError(
            "`image` shows no straight edge across the sensor: contact covers "
            f"{covered:.0%} of the fitted line"
        )
    # a trimmed mean along the edge: glass scratches crossing it touch few of the lines
    from scipy import stats  # (about 0.2 s to import: only the cross-section needs it)

    mean = stats.trim_mean(values, _TRIM, axis=0)
    quarter = max(across.size // 8, 2)
    baseline = float(np.median(np.concatenate((mean[:quarter], mean[-quarter:]))))
    profile = mean - baseline
    peak = float(profile.max())
    if peak <= 0:
        raise ValueError("`image` shows no contact along the fitted edge")
    descriptors = {
        "area": float(profile.clip(0.0, None).sum() * step),
        "peak": peak,
        "width_25": _width(across, profile, 0.25 * peak),
        "width_50": _width(across, profile, 0.50 * peak),
        "width_75": _width(across, profile, 0.75 * peak),
        "arc_radius": _arc_radius(across, profile, peak),
    }
    # the cap over the profile: three standard deviations of a line's samples about it
    spread = 1.4826 * float(np.median(np.abs(values - mean)))
    loaded = _loaded_length(
        array - baseline, pitch, (angle, offset), across, profile, 3.0 * spread
    )
    return EdgeCrossSection(
        angle_rad=float(angle),
        offset_m=float(offset),
        chord_m=float(chord),
        normal_force=normal_force,
        force_per_length=normal_force / loaded,
        positions=across,
        profile=profile,
        baseline=baseline,
        n_lines=int(values.shape[0]),
        descriptors=descriptors,
        loaded_length_m=loaded,
    )
