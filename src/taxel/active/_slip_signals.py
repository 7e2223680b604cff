r"""The signals behind slip detection: pattern registration and the PVDF motion innovation.

- `register` (`register_frame` for one frame): the shift of the contact pattern of a
  static array from a held reference image, by iterated Lucas-Kanade least squares over all
  taxels (with white readout noise of equal variance on every taxel, the least-squares
  shift is the maximum-likelihood one).
- `restore_charge`: undo the leak of a charge amplifier (eq. 25.17 with R_f across C_f, a
  first-order high-pass of time constant tau = R_f C_f), so that a PVDF frame reads the
  stress change since the first frame instead of a change that fades within tau.
- `motion_innovation`: how far each PVDF frame departs from the stick-phase prediction,
  along the direction in which the contact pattern has been moving (see the notes there).
- `run_ahead` (`track_deviation` for one frame): how far the registered pattern runs
  ahead of its extrapolated track.
- `position_noise`, `step_noise`: the warm-up's noise levels (static and PVDF).
- `cusum`: Page's one-sided CUSUM.
- `matched_filter`: the correlation of a white N(0, 1) sequence with a known shape.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from functools import lru_cache
from typing import Any

import numpy as np

from taxel.active._spline_shift import spline_shifter

__all__ = [
    "HELD_FRAMES",
    "armed_from",
    "charge_leak",
    "cusum",
    "matched_filter",
    "motion_innovation",
    "position_noise",
    "register",
    "register_frame",
    "restore_charge",
    "robust_sigma",
    "run_ahead",
    "step_noise",
    "track_deviation",
]

# the last warm-up frames averaged into the reference image and the held position
HELD_FRAMES = 10
_REFERENCE = 15  # frames in the reference window of the speed
_GAP = 3  # frames between the reference window and the current frame
_LATE_GAP = 12  # the same for the late channel (1.5 times the slowest friction relaxation)
_LEAST_WARM_UP = _REFERENCE + _LATE_GAP - 1


def register(frames: np.ndarray, reference: np.ndarray, pitch: tuple[float, float]) -> np.ndarray:
    """Shift (x, y) [m] of the pattern of each frame from the reference image, (n, 2).

    Iterated Lucas-Kanade: the reference is re-sampled (cubic splines) at the current estimate
    and the residual shift solved by least squares over the image; each frame starts from
    the previous frame's estimate, so the pattern is followed over many taxels.
    """
    shifts = np.zeros((frames.shape[0], 2))
    estimate = np.zeros(2)  # (columns, rows) in taxels
    shifted = spline_shifter(reference)
    for index, frame in enumerate(frames):
        estimate = register_frame(frame, shifted, estimate)
        shifts[index] = estimate
    return shifts * np.array([pitch[1], pitch[0]])


def register_frame(
    frame: np.ndarray, shifted: Callable[[float, float], np.ndarray], estimate: np.ndarray
) -> np.ndarray:
    """One frame's shift (columns, rows) [taxels] from the reference, starting at `estimate`.

    The step of `register` for one frame (at most 4 Lucas-Kanade iterations), shared with
    the online `SlipMonitor` so that both give the same numbers; `shifted` re-samples the
    reference image at a shift (rows, cols) [taxels] (`spline_shifter`).
    """
    rows = np.empty((3, frame.size))  # the gradients and the change, one row each
    for _ in range(4):
        moved = shifted(estimate[1], estimate[0])
        _gradient(moved, rows[1].reshape(moved.shape), rows[0].reshape(moved.shape))
        np.subtract(frame.ravel(), moved.ravel(), out=rows[2])
        # every sum the step needs in one product: [[xx, xy, xc], [., yy, yc], ...]
        sums = (rows[:2] @ rows.T).tolist()
        (xx, xy, xc), (_, yy, yc) = sums
        # the 2 x 2 normal equations by Cramer's rule: a LAPACK call costs ~20 us here
        det = xx * yy - xy * xy
        if det <= 1e-12 * max(xx + yy, 1e-300) ** 2:
            break  # no contact pattern to follow
        step_x, step_y = (yy * xc - xy * yc) / det, (xx * yc - xy * xc) / det
        estimate = estimate - np.array([step_x, step_y])
        if max(abs(step_x), abs(step_y)) < 1e-3:
            break
    return estimate


def position_noise(displacement: np.ndarray, warm_up: int) -> tuple[float, np.ndarray]:
    """The position noise sigma [m] of one frame over the warm-up, and its trend [m/frame].

    A line is fitted to the positions of frames 1 .. `warm_up` - 1; sigma is the robust
    standard deviation about it (the root mean square of x and y, at least 1 nm), and the
    line's slope (x, y) says whether the contact is held.
    """
    held = displacement[1:warm_up]
    trend = np.polynomial.polynomial.polyfit(np.arange(held.shape[0]), held, 1)
    residual = held - np.polynomial.polynomial.polyval(np.arange(held.shape[0]), trend).T
    sigma = max(float(np.sqrt(np.mean(robust_sigma(residual) ** 2))), 1e-9)
    return sigma, trend[1]


def step_noise(frames: np.ndarray) -> float:
    """Readout noise of one taxel from the frame-to-frame changes of (n, taxels) frames.

    The median absolute deviation over all taxels of the changes about each taxel's median
    change, divided by sqrt(2) (a change carries the noise of two frames).
    """
    steps = np.diff(frames, axis=0)
    return float(robust_sigma(steps - np.median(steps, axis=0), axis=None)) / np.sqrt(2)


def _gradient(image: np.ndarray, grad_y: np.ndarray, grad_x: np.ndarray) -> None:
    """`np.gradient` of an image (unit spacing, first-order edges) into `grad_y`, `grad_x`.

    The same numbers faster: `np.gradient` spends most of its time on generality, and the
    registration calls it up to 4 times a frame in the sensor loop.
    """
    grad_y[1:-1] = (image[2:] - image[:-2]) / 2.0
    grad_y[0] = (image[1] - image[0]) / 1.0
    grad_y[-1] = (image[-1] - image[-2]) / 1.0
    grad_x[:, 1:-1] = (image[:, 2:] - image[:, :-2]) / 2.0
    grad_x[:, 0] = (image[:, 1] - image[:, 0]) / 1.0
    grad_x[:, -1] = (image[:, -1] - image[:, -2]) / 1.0


def robust_sigma(values: np.ndarray, axis: int | None = 0) -> np.ndarray:
    """Standard deviation from the median absolute deviation (normal data)."""
    deviation = np.abs(values - np.median(values, axis=axis, keepdims=True))
    return np.median(deviation, axis=axis) / 0.6745


def cusum(z: np.ndarray, start: int, drift: float) -> np.ndarray:
    """Page's CUSUM S_k = max(0, S_{k-1} + z_k - drift) from frame `start` (NaN before)."""
    statistic = np.full(z.shape, np.nan)
    total = 0.0
    for k in range(start, z.size):
        total = max(0.0, total + z[k] - drift)
        statistic[k] = total
    return statistic


def matched_filter(z: np.ndarray, template: Any, start: int) -> np.ndarray:
    r"""Correlation of `z` with `template` ending at each frame, in noise units, (n,).

    :math:`m_k = \sum_i s_i z_{k - L + 1 + i} / \lVert s \rVert` for the L-frame template s:
    N(0, 1) where z is white and N(0, 1), and largest (in expectation) where the frames
    just before k follow the template's shape. NaN before frame `start` (and where the
    window reaches before the first frame); NaN values of z count as 0.

    Examples
    --------
    >>> matched_filter(np.array([0.0, 1.0, -2.0, 0.0]), [1.0, -2.0], 1).round(3).tolist()
    [nan, -0.894, 2.236, -0.894]
    """
    shape = np.asarray(template, dtype=float)
    length = shape.size
    values = np.nan_to_num(np.asarray(z, dtype=float))
    statistic = np.full(values.shape, np.nan)
    if length == 0 or values.size < length:
        return statistic
    total = sum(
        weight * values[index : values.size - length + 1 + index]
        for index, weight in enumerate(shape)
    )
    statistic[length - 1 :] = total / np.linalg.norm(shape)
    statistic[: max(start, 0)] = np.nan
    return statistic


def restore_charge(frames: np.ndarray, *, frame_rate: float, time_constant: float) -> np.ndarray:
    r"""PVDF frames (n, taxels) with the charge amplifier's leak undone [same units].

    The amplifier's recursion is :math:`V_k = a V_{k-1} - g \Delta Q_k / C_f` with
    :math:`a = e^{-\Delta t / \tau}` and :math:`g = (\tau / \Delta t)(1 - a)` (see
    `taxel.transducers.charge_amplifier_output`), so :math:`(V_k - a V_{k-1}) / g` is the
    charge step of frame k, in output units; their running sum is the stress change since
    the first frames, whose mean is taken as the rest level.
    """
    decay, gain = charge_leak(frame_rate=frame_rate, time_constant=time_constant)
    level = frames - frames[: min(5, frames.shape[0])].mean(axis=0)
    steps = level.copy()
    steps[1:] -= decay * level[:-1]
    return np.cumsum(steps, axis=0) / gain


def charge_leak(*, frame_rate: float, time_constant: float) -> tuple[float, float]:
    """The amplifier's decay a per frame and gain g (see `restore_charge`)."""
    decay = np.exp(-1.0 / (frame_rate * time_constant))
    return float(decay), float(frame_rate * time_constant * (1.0 - decay))


@lru_cache(maxsize=8)
def _line_weights(prediction: int) -> np.ndarray:
    """Least-squares weights of the straight line through `prediction` frames, at the next."""
    steps = np.arange(prediction) - prediction
    design = np.stack([np.ones(prediction), steps.astype(float)], axis=1)
    weights = np.linalg.pinv(design)[0]  # the line's value at step 0
    weights.flags.writeable = False  # shared by every call
    return weights


def motion_innovation(
    frames: np.ndarray, *, window: int, prediction: int, sigma: float
) -> np.ndarray:
    r"""Innovation of each frame along the pattern's direction of motion, in noise units.

    Parameters
    ----------
    frames : numpy.ndarray
        (n, taxels) frames of the stress change (restored PVDF frames).
    window : int
        W, frames over which the direction of motion is taken.
    prediction : int
        M, past frames from which a straight line predicts the current frame.
    sigma : float
        Readout noise of one taxel [frame units].

    Returns
    -------
    numpy.ndarray
        (n,) z_k, N(0, 1) while the contact follows its stick-phase track (NaN where the
        history is too short).

    Notes
    -----
    While the object sticks, the pattern moves smoothly (the pad's tangential compliance)
    and each frame is predicted by the straight line through the previous M frames,
    :math:`\hat F_k = \sum_j w_j F_{k-M+j}` (least-squares weights). The innovation
    :math:`e_k = F_k - \hat F_k` is projected on the unit direction
    :math:`u_k \propto F_{k-M-1} - F_{k-M-1-W}` along which the pattern has been moving
    (older frames than the prediction's, so that the two carry independent noise):
    :math:`z_k = u_k \cdot e_k / (\sigma \sqrt{1 + \sum w_j^2})`. The onset of gross slip
    departs from the line along that direction, but not at first forward: the friction
    drops from mu_s N to mu_k N, and the traction's own stress under the pad with it, so
    the first frames after the onset read as braking (z < 0; on simulated trials the mean z
    is about -2.5 and -2.2 one and two frames after the onset). The forward innovations of
    the sliding pattern and of its stick-slip vibrations follow from about 4 frames after
    the onset. Both are innovations the straight line cannot follow, which is why the
    detector squares z rather than test its sign. Projecting keeps one degree of freedom
    instead of one per taxel: the energy of a direction known in advance is seen
    sqrt(taxels) times more clearly than the energy of the whole frame.
    """
    n = frames.shape[0]
    weights = _line_weights(prediction)
    scale = sigma * np.sqrt(1.0 + weights @ weights)
    z = np.full(n, np.nan)
    first = prediction + 1 + window
    if n <= first:
        return z
    predicted = sum(
        weight * frames[first - prediction + j : n - prediction + j]
        for j, weight in enumerate(weights)
    )
    innovation = frames[first:] - predicted
    direction = frames[first - prediction - 1 : n - prediction - 1] - frames[: n - first]
    norm = np.linalg.norm(direction, axis=1)
    norm[norm == 0] = np.inf
    z[first:] = np.einsum("ij,ij->i", direction, innovation) / norm / scale
    return z


def run_ahead(
    displacement: np.ndarray, sigma: float, warm_up: int, reference: int, gap: int
) -> np.ndarray:
    """How far the pattern runs ahead of its extrapolated track, in noise units, (n,).

    A line fitted to the positions of `reference` frames ending `gap` frames before frame k
    is extrapolated to k; the deviation along the direction of travel (that of the
    displacement from the held position, the mean of the last 10 warm-up frames) is divided
    by the position noise `sigma` [m] and averaged over 2 frames. While the pattern is
    within 3 sigma of its held position, the size of the deviation (centred, 2 degrees of
    freedom) is used instead. NaN during the warm-up.
    """
    n = displacement.shape[0]
    held = displacement[warm_up - HELD_FRAMES : warm_up].mean(axis=0)
    ahead = np.full(n, np.nan)
    for k in range(warm_up, n):
        window = displacement[k - gap - reference + 1 : k - gap + 1]
        ahead[k] = track_deviation(window, displacement[k], held, sigma, reference, gap)
    smooth = ahead.copy()
    smooth[warm_up + 1 :] = 0.5 * (ahead[warm_up + 1 :] + ahead[warm_up:-1])
    return smooth


def track_deviation(
    window: np.ndarray,
    position: np.ndarray,
    held: np.ndarray,
    sigma: float,
    reference: int,
    gap: int,
) -> float:
    """One frame's run-ahead before smoothing (see `run_ahead`), in noise units.

    `window` holds the (reference, 2) positions [m] of the reference window, which ends
    `gap` frames before the frame at `position`; `held` is the held position [m].
    """
    steps, spread = _centred_steps(reference)
    lever = (reference - 1) / 2 + gap
    slope = steps @ window / spread
    deviation_x, deviation_y = (position - (window.mean(axis=0) + lever * slope)).tolist()
    moved_x, moved_y = (position - held).tolist()
    # (Python floats: a 2-vector's norm and dot cost NumPy ~5 us each, in the sensor loop)
    moved = math.hypot(moved_x, moved_y)
    if moved > 3 * sigma:
        return (deviation_x * moved_x + deviation_y * moved_y) / moved / sigma
    return math.hypot(deviation_x, deviation_y) / sigma - 1.25


@lru_cache(maxsize=8)
def _centred_steps(reference: int) -> tuple[np.ndarray, float]:
    """Frame steps of a reference window about its middle, and their sum of squares."""
    steps = np.arange(reference) - (reference - 1) / 2
    steps.flags.writeable = False  # shared by every call
    return steps, float(steps @ steps)


def armed_from(incipient: int | None, gap: int | None, never: int) -> int:
    """The first frame a channel counts from: 0 without a gap; `never` without incipient slip.

    With a gap, the channel's reference window (`_REFERENCE` frames ending `gap` before the
    frame) must start at or after the incipient decision: the track it extrapolates is then
    the loaded contact's, not the rest before the load began (whose end is incipient slip).
    """
    if gap is None:
        return 0
    return never if incipient is None else incipient + _REFERENCE + gap - 1
