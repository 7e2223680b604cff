"""Shared preparation of a tactile image: pitch, smoothing, baseline, noise, contact mask.

Every public feature function starts from `prepare`, so that `extract` can prepare an
image once and hand the result to each feature. The thresholds are relative to two scales
measured on the image itself, which makes the features work on raw 8-bit frames,
calibrated readings and pressure maps alike:

- the *noise* sigma of the smoothed image, from the median absolute deviation of the
  high-pass residual (robust to the few taxels that belong to edges or scratches);
- the *contrast*, peak minus baseline of the smoothed image.

Sensor defects are removed first when the sensor's cover is known to be deep: the cover
low-passes the pressure (a point load spreads over a half-maximum width of about 1.1-1.3
times the depth of the sensing plane), so when that depth spans 3 or more taxels no true
pressure feature is narrower than ~3.5 taxels, and bright structures under 3 taxels wide
(scratches on an FTIR sensor's glass, hot pixels) are defects. A grey-level opening with a
3 x 3 square removes them and leaves every wider structure as it was. The argument holds
for readings at the sensing plane only, so by default the opening is left out of calibrated
images: a pressure map recovered at the surface by deconvolution (`taxel.reconstruction`)
can be as sparse as the load itself, which the opening would erase, and a calibrated
reading has its fixed-pattern defects (scratches, dead or stuck taxels) removed by the
calibration already.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any, TypedDict, cast

import cv2
import numpy as np

from taxel._validation import check_finite, check_flag, check_range
from taxel.features._input import LARGEST_VALUE, as_image
from taxel.features._lighting import background_tilt
from taxel.features._noise import (
    RESIDUAL_QUANTUM,
    laplacian_residual,
    smoothing_gain,
    taxel_noise,
)
from taxel.features._response import ReadBack, read_back
from taxel.features._rest import smoothed
from taxel.features._sensor import (
    TAIL_DEPTHS,
    check_image_shape,
    cover_blur,
    cover_depth,
    depths_in_taxels_of,
    hexagonal_resampled,
    pitch_pair,
    raw_falls_with_pressure,
)

__all__ = ["Preparation", "Prepared", "prepare"]

# Contact thresholds, in units of the smoothed image's noise sigma (k) or of the contrast (f).
# The baseline is the minimum of the smoothed image, which lies about 3-4 sigma below the
# mean background on 16x16 to 128x128 images: K_LOW = 8 therefore sits ~4 sigma above it,
# where fewer than 1 in 10^4 background taxels cross by chance.
K_LOW = 8.0
# Seeds must stand ~6-7 sigma above the background mean; a blank noisy image has none.
K_HIGH = 11.0
# ... so where a calibrated or tared image has no background (the whole array pressed), its
# baseline is this many sigma below its known no-load level, 0
_REST_SIGMAS = 3.5
# The extent of a contact is taken where it rises above 12 % of the contrast. Lower would
# follow the cover's blur tail; higher would cut the centre of a flat punch, whose
# pressure there is only ~1/6 of its (singular, discretised) rim peak.
F_LOW = 0.12
# Seeds need 35 % of the contrast, so a weak secondary blob (scratch, crosstalk, a noise
# ridge on a textured field) joins the contact only when it touches a strong one.
F_HIGH = 0.35
# A contrast below this fraction of the image's magnitude is rounding, not contact.
_RELATIVE_FLOOR = 1e-6
# Take a raw frame's uneven lighting out when its array is at least this many taxels a side
# (`background_tilt`; a smaller one has too little background around a contact to fit)
_TILT_SIDE = 32
# Remove defects when the sensing plane lies at least this many taxels under the surface.
_DEFECT_DEPTH = 3.0
# flood fill: 8-connected, writing 1 into its mask
_FILL_8 = 8 | (1 << 8)
# Integer images of at most this many bits: their Laplacian residual is exact in float32.
_EXACT_BITS = 16


class Preparation(TypedDict, total=False):
    """The keywords of `prepare`, which every one-feature function passes on to it."""

    calibrated: bool
    smoothing: float
    baseline: float | None
    defects: bool | None
    noise: float | str | None
    reference: Any


@dataclass(eq=False)
class Prepared:
    """A validated tactile image with its smoothed version and contact mask (internal).

    Read-only by convention: not frozen, since a frozen dataclass sets each of its fields
    through ``object.__setattr__`` and costs microseconds to build.

    Attributes
    ----------
    image : numpy.ndarray (float32)
        The input values [image units], less `tilt`.
    smooth : numpy.ndarray (float32)
        Gaussian-smoothed image.
    pitch : tuple of float
        (row pitch, column pitch) [m].
    baseline, noise, contrast : float
        Background level, noise sigma of `smooth`, and peak minus baseline [image units].
    raw_noise : float
        Noise sigma of `image` itself [image units].
    low, high : float
        Hysteresis thresholds on `smooth` [image units].
    mask : numpy.ndarray (uint8)
        1 on contact taxels.
    labels : numpy.ndarray (int32, or uint8 with one region)
        Connected contact regions numbered 1..n (0 elsewhere); with one region, `mask`.
    n_regions : int
    calibrated : bool
        Whether `image` holds pressure [Pa].
    peak : float
        Largest value of `smooth` [image units].
    defects_removed : bool
        Whether `image` was cleaned of defects narrower than 3 taxels (see the module notes).
    cover_depth : float
        Depth of the sensing plane under the surface [m] (0 without a sensor description).
    blur : float
        Half-maximum width of the cover's response to a point load [m] (0 without a
        sensor description; see `taxel.features._sensor.cover_blur`).
    residual : numpy.ndarray or None
        ``x - mean(4 neighbours)`` of the input on its interior, on rows 1, 1 + step, ...
        (see `residual_step`): the noise, wherever the signal is locally linear.
    residual_step : int
        Row step of `residual` (2 on images over 64 x 64, else 1).
    residual_quantum : float
        The step the values of `residual` are multiples of (1/4 for an integer image), or
        0 (see `noise_from_residual`).
    outlines : tuple of numpy.ndarray or None
        Outlines of the contact (outer boundaries and hole walls, every taxel, as
        `cv2.findContours` gives them), when segmentation found them; else None.
    memo : dict
        Intermediates one feature computes and another reuses (image moments, the
        contact's peak in `image`, bounding box and windows, see `taxel.features._window`).
    left_out : float
        Largest value of `smooth` out of the contact, or a bound it stays under: `low`
        when no region above `low` was left out of `mask` (+inf when not known).
    hexagonal : bool
        Whether `image` is a hexagonal array's frame resampled onto its rectangular grid
        (its rows sqrt(3)/2 of its pitch apart).
    force_level : float
        The pressure that carries no force [Pa]: a calibrated image's `baseline` where it
        was given, else 0 (the no-load level of a pressure).
    read_back : ReadBack or None
        The raw frame and the transducer that reads it back to pressure, when the sensor
        given has one (see `taxel.features._response`): the contact's centre of pressure
        is then read through it.
    tilt : numpy.ndarray (float32) or None
        A raw frame's uneven lighting, taken out of `image` (`background_tilt`).
    """

    image: np.ndarray
    smooth: np.ndarray
    pitch: tuple[float, float]
    baseline: float
    noise: float
    contrast: float
    raw_noise: float
    low: float
    high: float
    mask: np.ndarray
    labels: np.ndarray
    n_regions: int
    calibrated: bool
    peak: float = 0.0
    defects_removed: bool = False
    residual: np.ndarray | None = None
    residual_step: int = 1
    residual_quantum: float = 0.0
    outlines: tuple[np.ndarray, ...] | None = None
    memo: dict[Any, Any] = field(default_factory=dict, repr=False, compare=False)
    blur: float = 0.0
    cover_depth: float = 0.0
    left_out: float = math.inf
    hexagonal: bool = False
    force_level: float = 0.0
    read_back: ReadBack | None = None
    tilt: np.ndarray | None = None

    @property
    def present(self) -> bool:
        """Whether any contact region was found."""
        return self.n_regions > 0

    @property
    def taxel_area(self) -> float:
        """Area of one taxel [m^2]."""
        return self.pitch[0] * self.pitch[1]

    @property
    def mean_pitch(self) -> float:
        """Geometric mean of the row and column pitch [m]."""
        return math.sqrt(self.taxel_area)


def component_outlines(
    region: np.ndarray, outlines: Sequence[np.ndarray], hierarchy: np.ndarray
) -> tuple[np.ndarray, ...]:
    """The outlines of one region, picked from those of a whole image (internal).

    `outlines` and `hierarchy` are ``cv2.findContours(image, cv2.RETR_CCOMP, ...)`` of a
    binary image of which `region` (uint8) is one 8-connected component. Returns the
    region's outer boundary and hole walls in the order ``cv2.findContours(region,
    cv2.RETR_LIST, ...)`` gives them (the holes, then the outer boundary), which saves
    tracing the region again. `tests/features/test_features.py` checks the order.
    """
    links = hierarchy[0].tolist()  # per outline: next, previous, first child, parent
    index = next(
        i
        for i, link in enumerate(links)
        if link[3] < 0 and region[outlines[i][0, 0, 1], outlines[i][0, 0, 0]]
    )
    holes = []
    child = links[index][2]
    while child >= 0:
        holes.append(outlines[child])
        child = links[child][0]
    return (*holes, outlines[index])


def _peak_region(
    candidates: np.ndarray,
    smooth: np.ndarray,
    outlines: Sequence[np.ndarray],
    hierarchy: np.ndarray,
    peak_at: Sequence[int],
) -> tuple[np.ndarray, float] | None:
    """The one region that is no speck, and the largest value left out of it.

    `outlines` and `hierarchy`: ``cv2.findContours(candidates, cv2.RETR_CCOMP, ...)``;
    every region has one outer outline, at the top level. When each other region's
    outline has fewer than 4 points, the region is those points (it has no inner taxel:
    one would need 4 around it), as specks of noise mostly are: returns the candidates
    without them (uint8) and the largest value of `smooth` on them, read point by point.
    None when another region is no speck, or the peak lies in a speck.
    """
    links = hierarchy[0].tolist()  # per outline: next, previous, first child, parent
    largest = None
    for outline, link in zip(outlines, links, strict=True):
        if link[3] < 0 and outline.shape[0] >= 4:
            if largest is not None:
                return None  # (a second region that is no speck)
            largest = outline
    if largest is None:
        return None
    region = candidates.copy()
    left_out = -math.inf
    for outline, link in zip(outlines, links, strict=True):
        if link[3] < 0 and outline is not largest:
            for x, y in outline[:, 0].tolist():
                region[y, x] = 0
                left_out = max(left_out, float(smooth[y, x]))
    return None if region[peak_at[1], peak_at[0]] == 0 else (region, left_out)


def removes_defects(
    sensor_or_pitch: Any,
    defects: bool | None,
    *,
    calibrated: bool = False,
    referenced: bool = False,
) -> bool:
    """Whether defects are removed: as asked, or by default (None) as the module notes say.

    By default: in an uncalibrated image of a sensor whose cover is >= 3 taxels deep, unless
    an unloaded reference frame was subtracted (`referenced`), which removed them already.
    """
    if defects is not None:
        return check_flag("defects", defects)
    if calibrated or referenced:
        return False
    depth = cover_depth(sensor_or_pitch)
    if depth is None:
        return False
    return depth >= _DEFECT_DEPTH * max(pitch_pair(sensor_or_pitch))


def _cuts(level: float, peak: float, noise: float) -> tuple[float, float]:
    """The levels at which the contact is cut and its seeds are taken (`low`, `high`)."""
    contrast = peak - level
    low = level + max(K_LOW * noise, F_LOW * contrast)
    return low, level + max(K_HIGH * noise, F_HIGH * contrast)


def prepare(
    image: Any,
    sensor_or_pitch: Any,
    *,
    calibrated: bool = False,
    smoothing: float = 1.0,
    baseline: float | None = None,
    defects: bool | None = None,
    noise: float | str | None = None,
    reference: Any = None,
) -> Prepared:
    """Validate, clean, smooth and segment a tactile image (the first step of every feature).

    Parameters
    ----------
    image : array_like, shape (rows, cols)
        Raw frame (any integer or float dtype), calibrated reading or pressure map [Pa];
        larger values mean more pressure, except in the raw frame of a sensor whose
        reading falls with pressure (a PVDF array's charge amplifiers swing down under
        compression: ``reading_falls_with_pressure``), which is turned over (negated)
        first, so that its `baseline` and the contact's peak are then in negated units.
        Values beyond +-1e15 are refused (the features compute in float32).
    sensor_or_pitch : float, pair or object with ``taxel_pitch``
        Taxel pitch [m], or a sensor description (a `taxel.sensor.TactileSensor`), whose
        cover depth then decides `defects`; a frame of a hexagonal array (of a sensor or an
        `ArrayGeometry`) is resampled onto the rectangular grid.
    calibrated : bool, default False
        The image holds pressure [Pa]: areas carry a total force. Refused for an integer
        image of a sensor that reads frames (its raw codes).
    smoothing : float, default 1.0
        Sigma of the Gaussian smoothing [taxels], 0 to disable.
    baseline : float, optional
        The no-contact level [image units]; by default the smoothed image's lowest, dead taxels
        read as their neighbours (`_rest`); wrong when the whole sensor is in contact. Without
        it, a raw frame of 32 x 32 taxels or more has its lighting's tilt taken out first when
        the tilt would move the contact's cut (`tilt`, see `taxel.features._lighting`). A
        calibrated or tared (`reference`) image has a known no-load level, 0: when its smoothed
        minimum stands clearly above it (11 noise sigmas: no taxel at rest), the baseline is
        3.5 sigmas below 0, where a background's minimum usually lies. A raw frame cannot tell:
        give it a `reference`. Given for a calibrated image, it is the pressure that carries no
        force: the forces count the pressure above it (an uncorrected offset).
    defects : bool, optional
        Remove bright defects narrower than 3 taxels (glass scratches, hot pixels) with a
        3 x 3 grey-level opening. By default only in an uncalibrated image (a raw frame)
        when `sensor_or_pitch` describes a cover whose sensing plane lies 3 or more taxels
        deep: never in a calibrated image or pressure map (see the module notes).
    noise : float or "sensor", optional
        The noise standard deviation of one taxel [image units], when the sensor's is
        known. By default estimated from the image, which cannot tell a texture as fine
        as the taxels from noise when it covers the whole array; an image with fewer
        than 16 interior taxels (a 4 x 4 array) cannot give it at all, and takes the
        sensor's own noise when `sensor_or_pitch` is a sensor description that reads
        frames (`sensor_noise`; in pascals through its `flat_plate_gain` when the image
        is calibrated); given a bare pitch, it needs `noise`. "sensor" takes the sensor's
        noise on any raw frame; it is only as right as the sensor's model: frames noisier
        than the model then show contacts in their noise.
    reference : array_like, shape (rows, cols), optional
        The sensor's unloaded frame (better, the mean of several), subtracted first: a tare
        that takes away what no contact makes (the scratches of an FTIR sensor's glass,
        each taxel's offset, uneven lighting), which the minimum-based baseline and the
        opening cannot, so that a blank frame reads as blank. `defects` then defaults to
        False. Its noise adds to the frame's (by 1/n of its variance for a mean of n).

    Returns
    -------
    Prepared

    Examples
    --------
    >>> image = np.zeros((9, 9)); image[3:6, 3:6] = 1.0
    >>> prepared = prepare(image, 1e-3)
    >>> prepared.n_regions, int(prepared.mask.sum())
    (1, 21)
    """
    given = as_image(image)
    check_image_shape(given.shape, sensor_or_pitch)
    calibrated = check_flag("calibrated", calibrated)
    reads_frames = callable(getattr(sensor_or_pitch, "frame_from_pressure", None))
    if calibrated and reads_frames and np.asarray(image).dtype.kind in "iu":
        # a sensor's output is integer codes (the command line refuses any integer file)
        raise ValueError(
            f"`image` holds integers ({np.asarray(image).dtype}), the sensor's raw codes, not "
            "pressure [Pa]: leave out calibrated=True for a raw frame, or give a pressure map "
            "in real numbers"
        )
    if reference is not None:
        tare = as_image(reference, "reference")
        if tare.shape != given.shape:
            raise ValueError(
                f"`reference` must have the image's shape {given.shape}, got {tare.shape}"
            )
        given = cv2.subtract(given, tare)
    # a raw frame that falls with pressure (a PVDF array's) is turned over
    inverted = not calibrated and raw_falls_with_pressure(sensor_or_pitch)
    if inverted:
        given = np.negative(given)
    # integer inputs (a raw frame, as it was given) leave an exact quarter-step residual;
    # two of 16 bits differ in 17, which float32 still holds exactly
    dtypes = [np.asarray(array).dtype for array in (image, reference) if array is not None]
    values = hexagonal_resampled(given, sensor_or_pitch)
    resampled = values is not given
    integers = not resampled and all(dtype.kind in "biu" for dtype in dtypes)
    whole = integers and max(dtype.itemsize for dtype in dtypes) * 8 <= _EXACT_BITS
    pitch = pitch_pair(sensor_or_pitch)
    smoothing = check_range("smoothing", smoothing, 0.0, 20.0)
    step = 2 if values.shape[0] > 64 and values.shape[1] > 64 else 1
    residual = laplacian_residual(values, step, whole=whole)
    interior = (values.shape[0] - 2) * (values.shape[1] - 2)
    quantum = RESIDUAL_QUANTUM if integers else 0.0
    raw_noise = taxel_noise(noise, sensor_or_pitch, calibrated, residual, interior, quantum)
    cleaned = removes_defects(
        sensor_or_pitch, defects, calibrated=calibrated, referenced=reference is not None
    )
    # (bright defects removed, and dead taxels read as their neighbours: `_rest`)
    values, smooth, lowest, peak, peak_at = smoothed(values, smoothing, raw_noise, defects=cleaned)
    noise = raw_noise * smoothing_gain(smoothing)
    level = lowest if baseline is None else check_finite("baseline", baseline)
    if baseline is None and (calibrated or reference is not None) and lowest > K_HIGH * noise:
        # no taxel at rest: the whole array is pressed. A pressure's or a tared frame's
        # no-load level is known, 0, and its background's minimum would lie ~3.5 sigma below
        level = -_REST_SIGMAS * noise
    if inverted and baseline is not None:
        level = -level
    if abs(level) > LARGEST_VALUE:
        raise ValueError(f"`baseline` must lie within +-{LARGEST_VALUE:.0e}, got {level:.3g}")
    low, high = _cuts(level, peak, noise)
    # uneven lighting: a raw frame's background tilt is taken out before the contact is cut
    lit = not calibrated and reference is None and baseline is None and not resampled
    tilt = None
    if lit and min(values.shape) >= _TILT_SIDE:
        depth, mean_pitch = cover_depth(sensor_or_pitch) or 0.0, 0.5 * (pitch[0] + pitch[1])
        reach = depths_in_taxels_of(depth, mean_pitch, TAIL_DEPTHS)  # (`catchment_reach`)
        tilt = background_tilt(smooth, low, high, level, noise, reach)
        if tilt is not None:
            values, smooth = values - tilt, smooth - tilt
            level, peak, _, peak_at = cv2.minMaxLoc(smooth)
            low, high = _cuts(level, peak, noise)
    contrast = peak - level
    floor = max(_RELATIVE_FLOOR * max(abs(peak), abs(level)), 1e-30)
    common: dict[str, Any] = {
        "image": values, "smooth": smooth, "pitch": pitch, "baseline": level, "noise": noise,
        "contrast": contrast, "raw_noise": raw_noise, "low": low, "high": high,
        "calibrated": calibrated, "peak": peak, "defects_removed": cleaned,
        "force_level": level if calibrated and baseline is not None else 0.0,
        "residual": residual, "residual_step": step, "residual_quantum": quantum,
        "blur": cover_blur(sensor_or_pitch),
        "cover_depth": cover_depth(sensor_or_pitch) or 0.0, "hexagonal": resampled,
        "tilt": tilt,
        "read_back": None if resampled else read_back(
            sensor_or_pitch, np.asarray(image), calibrated=calibrated,
            tare=None if reference is None else np.asarray(reference),
        ),
    }  # fmt: skip
    if contrast <= max(K_HIGH * noise, floor):
        empty = np.zeros(values.shape, np.uint8)
        return Prepared(mask=empty, labels=empty.astype(np.int32), n_regions=0, **common)
    candidates = (smooth >= low).view(np.uint8)
    # outer boundaries and hole walls in a two-level hierarchy: one outer boundary is one
    # region (an island inside a hole is put at the top level too), the usual case, and
    # it is seeded by the peak itself; its outlines serve every later feature
    outlines, hierarchy = cv2.findContours(candidates, cv2.RETR_CCOMP, cv2.CHAIN_APPROX_NONE)
    if len(outlines) == 1 or hierarchy[0][:, 3].tolist().count(-1) == 1:
        return Prepared(
            mask=candidates,
            labels=candidates,
            n_regions=1,
            left_out=low,
            outlines=cast(tuple[np.ndarray, ...], outlines),  # cv2 gives a tuple
            **common,
        )
    # several candidate regions (a contact and specks of noise, scratches), usually one
    # seeded: the peak's, which is the candidates but the specks, or else a flood fill
    # from the peak (either costs less than labelling)
    # the largest value left out: of the other candidates (the rest lies under `low`);
    # under `high` (in float32, as the seeds' comparison), none of them holds a seed
    picked = _peak_region(candidates, smooth, outlines, hierarchy, peak_at)
    if picked is None:
        filled = np.zeros((values.shape[0] + 2, values.shape[1] + 2), np.uint8)
        cv2.floodFill(candidates, filled, peak_at, 1, 0, 0, _FILL_8 | cv2.FLOODFILL_MASK_ONLY)
        region = np.ascontiguousarray(filled[1:-1, 1:-1])
        left_out = cv2.minMaxLoc(smooth, candidates ^ region)[1]
    else:
        region, left_out = picked
    if left_out < np.float32(high):
        found = component_outlines(region, outlines, hierarchy)
        return Prepared(
            mask=region, labels=region, n_regions=1, outlines=found, left_out=left_out, **common
        )
    seeds = (smooth >= high).view(np.uint8)
    count, labels = cv2.connectedComponents(candidates, connectivity=8, ltype=cv2.CV_32S)
    seeded = np.bincount(labels[seeds.view(bool)], minlength=count) > 0
    seeded[0] = False
    keep = np.cumsum(seeded).astype(np.int32) * seeded
    labels = keep.take(cast(np.ndarray, labels))  # (`keep[labels]`, at half the cost)
    mask = (labels > 0).view(np.uint8)
    return Prepared(mask=mask, labels=labels, n_regions=int(seeded.sum()), **common)
