"""The contact's centre of pressure through the sensor's response (internal).

A texture or a plate presses lightly over much of the array, where the contact mask, cut
at a threshold, does not reach, and the cover spreads every load beyond it: a centre
weighted over the mask alone misses that pressure. A window grown around the contact takes
it in, and takes in the noise of every background taxel too. The window is chosen by
Lepski's rule (Lepski, Mammen & Spokoiny, Ann. Statist. 25, 1997), the usual answer when
an estimate's bias is unknown but its noise is: the smallest window is kept whose centre
agrees with every larger window's within their noise; where one does not, the larger
windows have seen pressure it missed. No window reaches past the contact's load (3.5 cover
depths), so that a defect far from the contact does not count. The pressure is the frame
read back through the sensor's response (`_response`), signed, so that the background's
noise averages out instead of pulling the centre towards the window's middle. The
background beyond that reach checks the model's unloaded level, which the read-back
assumes (`_background`). Where the reach crosses the array's edge, part of the load's
pressure at the glass lies beyond it, felt by no taxel: the array is grown by the reach,
with what the load on the array that explains the frame presses there
(`taxel.reconstruction.extend_readings`; no load beyond the array), and the windows run
into it. On the features benchmark's 1008 vhdta128 frames that takes the centroid's p95
from 0.56 to 0.43 taxel (0.39 with `_AGREE` chosen anew), below the 0.59 of weighing the
exact felt pressure over the whole array.
"""

from __future__ import annotations

import math

import cv2
import numpy as np

from taxel.features._image import Prepared
from taxel.features._lighting import fit_plane, plane_image
from taxel.features._moments import binary_moments
from taxel.features._response import (
    ROUNDING,
    ReadBack,
    forward_model,
    grey_level_pressure,
    grey_noise,
    light_image,
    light_pressure,
    signed_pressure,
)
from taxel.features._window import catchment_reach, contact_box, contact_window
from taxel.reconstruction import ForwardModelSpec, extend_readings

__all__ = ["pressure_centre"]

# The windows: the contact mask, then its bounding box grown by each of these [taxels]
# short of the reach of the contact's load (3.5 cover depths, see `catchment_reach`), and
# by that reach: beyond it the cover spreads 2 % of a point load
_RADII = (0, 2, 4, 8, 16, 32)
# The background beyond the contact's reach tells a frame the model does not describe,
# when at least `_FAR_TAXELS` taxels lie there (read on every `_SAMPLE`-th of them). Light
# contact only brightens a taxel: a background darker than the unloaded level by over
# `_DARK` grey levels, or with over `_STRAY` of its taxels `_CLIP` noise sigmas below it
# (another glass's scratches: about 4 %), is not the model's, and the image is weighed.
# A brighter camera (another dark level, a drift of the lighting, uneven lighting) adds a
# level to every window, which pulls each towards its brighter side: a background lying
# within `_FLAT` sigmas of a plane (noise alone spreads by 0.9 sigma on vhdta128, a
# texture's light contact by 2.3-2.6) and over `_OFFSET` grey levels somewhere on the
# array is such a level, taken out of the light when the background is half the array
# or more (`pressure_centre`); its tilts only where over `_SIGNIFICANT` standard errors.
# A plane under `_OFFSET` everywhere still has its level, where its points lie, taken out
# from `_SIGNIFICANT` standard errors (a few hundredths of a grey level): two pens far
# apart on a camera -0.2 to 0.45 grey levels off were 2.65-8.0 taxels off under the union
# of their windows, where the offset weighs as much as the pens (2.0 without the offset,
# and now; 0.3 with a ramp of 0.15 across, 9.5 -> 1.6). Its tilt is not: a can's rim lit
# its far background by 0.4 grey levels across, a light contact's faint tail, not the
# camera's, and taking it out put the rim 2.7 taxels off (0.2 left in)
_FAR_TAXELS = 256
_SAMPLE = 3
_DARK = 0.5
_CLIP = 5.0
_STRAY = 0.005
_FLAT = 1.5
_OFFSET = 0.5
_SIGNIFICANT = 3.0
# A taxel whose light is over this many noise sigmas from its 3 x 3 median is a defect
# (`_despiked`): a hot pixel among an edge's windows put it 0.22 taxel off (0.03 without)
_SPIKE = 12.0
# Two centres agree when they lie within this many noise sigmas of their difference (each
# centre's noise over both axes together, added in quadrature). Chosen on the features
# benchmark, windows grown beyond the edges, over 1.5, 2 and 3: centroid p95 / max [taxel]
# and frames over 0.5 taxel on its 1008 vhdta128 frames 0.39 / 1.70 / 32 against
# 0.39 / 1.82 / 33, 0.37 / 1.82 / 28 and 0.43 / 1.91 / 37; on the second draw (280
# frames) 0.34 / 1.29 / 5 against 0.40 / 3.74 / 9, 0.35 / 3.74 / 7 and 0.35 / 1.29 / 5
# (the others with the grown array solved on every taxel, not on blocks: `_grown`; all
# before the later checks, which took the benchmark to 0.39 / 1.63 / 30 and 0.33)
_AGREE = 2.5


def _index_sums(first: int, stop: int) -> tuple[int, int]:
    """Sums of the indices first..stop - 1 and of their squares."""

    def squares(n: int) -> int:  # 0^2 + ... + (n - 1)^2
        return (n - 1) * n * (2 * n - 1) // 6

    return (first + stop - 1) * (stop - first) // 2, squares(stop) - squares(first)


Box = tuple[int, int, int, int]  # (top, left, bottom, right), rows and columns end-exclusive


def _windows(prepared: Prepared, reach: int) -> list[Box]:
    """The contact's bounding box grown by `_RADII` taxels short of `reach`, and by it.

    Not clipped to the array: they may cross its edges by up to `reach`.
    """
    left, top, width, height = contact_box(prepared)
    grown = [*(r for r in _RADII if r < reach), reach]
    return [(top - g, left - g, top + height + g, left + width + g) for g in grown]


def _clipped(box: Box, shape: tuple[int, int]) -> Box:
    """The part of `box` on an array of `shape`."""
    top, left, bottom, right = box
    return max(top, 0), max(left, 0), min(bottom, shape[0]), min(right, shape[1])


def _beyond_reach(prepared: Prepared, reach: int) -> np.ndarray:
    """Flat indices of the taxels beyond `reach` of every contact taxel (chessboard)."""
    side = 2 * reach + 1
    near = cv2.dilate(prepared.mask, cv2.getStructuringElement(cv2.MORPH_RECT, (side, side)))
    return np.flatnonzero(near.ravel() == 0)


def _background(
    light: np.ndarray, far: np.ndarray, grey_noise: float
) -> tuple[float, float, float] | None:
    """The background's level above the unloaded level [grey levels]: a plane, or None.

    Over every `_SAMPLE`-th taxel of `far` (flat indices into `light`, the frame's grey
    levels above the unloaded level, `light_image`), when there are at least `_FAR_TAXELS`
    (else no level): a plane fitted by least squares to those within `_CLIP` noise sigmas
    of their median, then to those within `_CLIP` sigmas of that plane (uneven lighting, a
    ramp, is a plane's tilt). Light contact only brightens a taxel: a background darker
    than the unloaded level by more than `_DARK` on average, or with more than `_STRAY` of
    its taxels `_CLIP` sigmas below the plane (or below the unloaded level, where the plane
    is darker; another glass, whose scratches the model's pattern does not match), is not
    the model's (None): a texture's light contact beyond the reach lifts the median, not
    the unloaded level. The level is that plane when the background lies on it (spread
    within `_FLAT` sigmas, as noise alone is: a camera's offset or uneven lighting, not a
    texture's light contact) and it stands over `_OFFSET` somewhere on the array; else
    its level where its points lie (their mean), without its tilt, when that stands
    `_SIGNIFICANT` standard errors clear of 0; else 0.
    Returned as (level at the first taxel, change per row, change per column);
    `grey_noise` must be positive.
    """
    if far.size < _FAR_TAXELS:
        return (0.0, 0.0, 0.0)
    sampled = far[::_SAMPLE]
    values = light.ravel()[sampled].astype(np.float64)
    rows, cols = np.divmod(sampled, light.shape[1])
    clip = _CLIP * grey_noise
    inside = np.abs(values - np.median(values)) <= clip
    design = np.stack((np.ones(values.size), rows, cols)).astype(np.float64)
    for _ in range(2):
        # centred on the points, for a well-conditioned fit (they may be a narrow band)
        middle = design[:, inside].mean(axis=1)
        middle[0] = 0.0
        coefficients, _, errors = fit_plane(design[:, inside] - middle[:, None], values[inside])
        # a tilt within `_SIGNIFICANT` of its standard errors is noise, which the law would
        # magnify in a bright contact (a can's rim: 0.38 grey levels of tilt across the
        # array at 2 errors put its centre 2.7 taxels off)
        coefficients[1:][np.abs(coefficients[1:]) <= _SIGNIFICANT * errors[1:]] = 0.0
        # (the points' mean lies on the plane: about the first taxel)
        centre_level = values[inside].mean()
        coefficients[0] = centre_level - coefficients[1:] @ middle[1:]
        plane = coefficients @ design
        inside = np.abs(values - plane) <= clip
    dark = np.count_nonzero(values < np.minimum(plane, 0.0) - clip) / values.size
    level = float(plane[inside].mean())
    spread = float((values - plane)[inside].std())
    if level < -_DARK or dark > _STRAY:
        return None
    last_row, last_col = light.shape[0] - 1, light.shape[1] - 1
    corners = [coefficients @ (1.0, r, c) for r in (0, last_row) for c in (0, last_col)]
    if spread <= _FLAT * grey_noise:
        if max(map(abs, corners)) > _OFFSET:
            return (float(coefficients[0]), float(coefficients[1]), float(coefficients[2]))
        # (errors[0]: the error of the level where the points lie, their mean)
        if abs(centre_level) > _SIGNIFICANT * errors[0]:
            return (float(centre_level), 0.0, 0.0)
    return (0.0, 0.0, 0.0)


def _despiked(read: ReadBack, light: np.ndarray, pressure: np.ndarray, limit: float) -> np.ndarray:
    """`pressure`, each taxel whose light is `limit` [DN] off its 3 x 3 median's the median's.

    `light` is the frame's `light_image`, its pressure `light_pressure`'s. A taxel standing out
    alone is a defect (a hot pixel), not load, where the cover smooths the pressure at the
    glass. Compared in grey levels, where the camera's noise grows only about 2-fold by
    full light (shot noise), while the read-back's slope grows 27-fold by 99 % light. A
    3 x 3 median also cuts a ridge's crest: on a noise-free frame (limit 3.5 grey levels)
    a sharp edge's crest loses 2 % of its load (its centre under 0.04 taxel).
    """
    median = cv2.medianBlur(light, 3)
    spikes = np.abs(light - median) > limit
    if not spikes.any():
        return pressure
    pressure = pressure.copy()
    pressure[spikes] = light_pressure(read, median[spikes])
    return pressure


def _mask_sums(prepared: Prepared, pressure: np.ndarray) -> tuple[float, ...]:
    """The window sums of `pressure_centre` over the contact mask itself."""
    mask = prepared.mask
    rows, cols = contact_window(prepared)
    count = binary_moments(mask[rows, cols], rows.start, cols.start)
    weighted = cv2.moments(pressure[rows] * mask[rows])
    w_y = weighted["m01"] + rows.start * weighted["m00"]
    return (
        weighted["m00"], w_y, weighted["m10"],
        count["m00"], count["m01"], count["m10"], count["m02"] + count["m20"],
    )  # fmt: skip


def _first_moment(cumulative: np.ndarray, first: np.ndarray, stop: np.ndarray) -> np.ndarray:
    """Sum of i (c[i + 1] - c[i]) over i = first..stop - 1, down each column (by parts)."""
    columns = np.arange(cumulative.shape[1])
    running = np.zeros((cumulative.shape[0] + 1, cumulative.shape[1]))
    np.cumsum(cumulative, axis=0, out=running[1:])  # running[i]: the sum of c[:i]
    return (
        (stop - 1) * cumulative[stop, columns]
        - first * cumulative[first, columns]
        - (running[stop, columns] - running[first + 1, columns])
    )


def _box_sums(pressure: np.ndarray, boxes: list[Box], origin: int = 0) -> list[tuple[float, ...]]:
    """Pressure, and its first moments by rows and by columns, over each box.

    The boxes are in the array's indices, the array's taxel (0, 0) at `pressure`'s
    (origin, origin) (an array grown by `origin` on every side); so are the moments. From
    the pressure's integral image alone: a box's pressure by rows is the difference of two
    of its columns, whose first moment is then taken by parts (`_first_moment`), and the
    same by columns.
    """
    integral = cv2.integral(pressure, sdepth=cv2.CV_64F)
    r0, c0, r1, c1 = np.array(boxes).T + origin
    total = integral[r1, c1] - integral[r0, c1] - integral[r1, c0] + integral[r0, c0]
    w_y = _first_moment(integral[:, c1] - integral[:, c0], r0, r1) - origin * total
    w_x = _first_moment((integral[r1] - integral[r0]).T, c0, c1) - origin * total
    return list(zip(total.tolist(), w_y.tolist(), w_x.tolist(), strict=True))


def _box_counts(box: Box) -> tuple[int, int, int, int]:
    """Taxels of a box, and the sums of their row, column and squared distance to (0, 0)."""
    top, left, bottom, right = box
    n_r, n_c = bottom - top, right - left
    (s_r, s_rr), (s_c, s_cc) = _index_sums(top, bottom), _index_sums(left, right)
    return n_r * n_c, n_c * s_r, n_r * s_c, n_c * s_rr + n_r * s_cc


def _grown(
    model: ForwardModelSpec, pressure: np.ndarray, reach: int, smoothed: bool = True
) -> np.ndarray:
    """`pressure` on the array grown by `reach` taxels (`extend_readings`).

    What lies beyond the edges is that of the pressure's 3 x 3 median when the cover
    smooths the pressure at the glass over a taxel or more (`smoothed`): a taxel standing
    out alone is then a defect, which the load that explains it would carry far beyond an
    edge (a hot pixel on the edge row put an edge contact 0.46 taxel off, 0.03 without
    it). Solved on 2 x 2 blocks of taxels when the cover spreads a load over 3 pitches or
    more (vhdta128: 3.9), 5 times faster and as good for the centre (centroid p95 0.393
    against 0.394 taxel on the features benchmark), what lies beyond the edges spread
    evenly over each block's taxels, which keeps its centre; odd-sized arrays and thinner
    covers are solved on every taxel, about 4 times slower.
    """
    rows, cols = pressure.shape
    smooth = pressure.astype(np.float32, copy=False)
    if smoothed:
        smooth = np.asarray(cv2.medianBlur(smooth, 3), dtype=np.float32)
    if model.oversampling != 1 or rows % 2 or cols % 2 or model.depth < 3 * model.taxel_pitch:
        grown = extend_readings(model, smooth, reach)
    else:
        coarse = model.with_changes(
            shape=(rows // 2, cols // 2), taxel_pitch=2 * model.taxel_pitch, dead_taxels=()
        )
        half = (reach + 1) // 2
        blocks = smooth.reshape(rows // 2, 2, cols // 2, 2).mean(axis=(1, 3), dtype=np.float64)
        grown = extend_readings(coarse, blocks, half).repeat(2, axis=0).repeat(2, axis=1)
        start = 2 * half - reach
        grown = grown[start : start + rows + 2 * reach, start : start + cols + 2 * reach]
    grown[reach:-reach, reach:-reach] = pressure
    return grown


def pressure_centre(prepared: Prepared, read: ReadBack) -> tuple[float, float] | None:
    """Centre of pressure (row, col) of the contact through the sensor's response, or None.

    The signed pressure (`signed_pressure`) is weighted over each window: the contact mask
    and its bounding box grown by `_RADII` taxels up to the reach of its load (3.5 cover
    depths, `catchment_reach`); where that reach crosses the array's edge, and the sensor
    has a forward model (`forward_model`), on the array grown by it
    (`taxel.reconstruction.extend_readings`). A window's centre moves with the noise by
    sigma times the root of its taxels' sum of squared distances to the centre over its
    total pressure (both axes together; its taxels on the array). The smallest window is
    kept whose centre lies within `_AGREE` times the noise of every larger window's
    (Lepski's rule, see the module notes).
    Windows whose pressure sums to nothing, or whose centre falls off the array, are
    passed over; None when every window is, or when the background beyond the reach is
    not the model's (`_background`: darker than its unloaded level by over half a grey
    level, or another glass's):
    the image is then weighed. A background lying on a plane beyond the reach, brighter or
    (by up to half a grey level) darker, is a camera's offset from the model or its uneven
    lighting, taken out of the light when over half a grey level somewhere (else its level
    alone, when 3 standard errors clear of 0) and half the array or more lies beyond the
    reach (less is too little to tell it from a texture's faint light contact). A raw frame's
    tilt taken out before segmentation (`Prepared.tilt`) is taken out first.
    """
    noise_grey = grey_noise(read, prepared.raw_noise)
    # a camera's grey levels are integers at heart: a noise-free float frame's checks
    # take their rounding's noise
    noise_floor = max(noise_grey, ROUNDING)
    reach = catchment_reach(prepared)
    far = _beyond_reach(prepared, reach)
    # the frame's uneven lighting, as segmentation measured it, is no light contact
    light = light_image(read)
    if prepared.tilt is not None:
        light -= prepared.tilt
    level = _background(light, far, noise_floor)
    if level is None:
        return None
    # a contact whose reach covers half the array or more (a texture) leaves too little
    # background to tell a camera's level from its own faint light contact (foam at 30 N
    # lit the other 23 % by 1.2 grey levels: taken out, 3.1 taxels off). The level is
    # taken out of the light, not of the pressure: the law's slope grows with the light
    levelled = far.size >= light.size / 2 and any(level)
    if levelled:
        light -= plane_image(level, light.shape)
    if levelled or prepared.tilt is not None:
        pressure = light_pressure(read, light)
    else:
        pressure = signed_pressure(read)
    # the cover smooths the pressure at the glass over a taxel or more: a taxel standing
    # out alone is a defect; under a thinner cover a pen's tip may light one taxel alone
    smoothed = prepared.cover_depth >= prepared.mean_pitch
    if smoothed:
        pressure = _despiked(read, light, pressure, _SPIKE * noise_floor)
    noise = noise_grey * grey_level_pressure(read)
    rows, cols = shape = pressure.shape
    boxes = _windows(prepared, reach)
    on_array = [_clipped(box, shape) for box in boxes]
    # the reach crosses an edge: the windows run on into the array grown by it
    model = forward_model(read) if on_array[-1] != boxes[-1] else None
    if model is None:
        weighted = _box_sums(pressure, on_array)
    else:
        weighted = _box_sums(_grown(model, pressure, reach, smoothed), boxes, reach)
    # a window's centre moves with the noise of its taxels on the array; beyond its edges
    # the pressure carries that of the taxels near them, smoothed (white noise: std 0.15
    # of theirs, 0.42 next to the edge, `extend_readings`' tests), which is left out
    candidates = [_mask_sums(prepared, pressure)]
    candidates += [(*w, *_box_counts(box)) for w, box in zip(weighted, on_array, strict=True)]
    centres, moved = [], []
    for total, w_y, w_x, n, s_y, s_x, s_sq in candidates:
        if not total > 0:
            continue
        c_y, c_x = w_y / total, w_x / total
        if not (0.0 <= c_y <= rows - 1 and 0.0 <= c_x <= cols - 1):
            continue
        spread = s_sq - 2.0 * (c_y * s_y + c_x * s_x) + n * (c_y**2 + c_x**2)
        centres.append((c_y, c_x))
        moved.append(noise * math.sqrt(max(spread, 0.0)) / total)
    # Lepski's rule: the smallest window whose centre every larger window's agrees with
    for j, (c_y, c_x) in enumerate(centres):
        if all(
            math.hypot(c_y - o_y, c_x - o_x) <= _AGREE * math.hypot(moved[j], moved[k])
            for k, (o_y, o_x) in enumerate(centres[j + 1 :], j + 1)
        ):
            return c_y, c_x
    return None
