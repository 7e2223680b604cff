"""Least-squares line and circle fits to edge points, in metres (Ellis seed, section 2.1)."""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from taxel._validation import as_finite_array
from taxel.features._record import record

__all__ = [
    "CircleFit",
    "LineFit",
    "centred",
    "dot",
    "fit_circle",
    "fit_line",
    "fit_line_and_circle",
    "line_circle_and_distances",
    "line_through",
    "mean",
    "std",
    "taubin_circle",
]

# Gauss-Newton steps after the algebraic fit; 3 bring the geometric RMS to within 1e-6 of
# its minimum on arcs spanning more than 60 degrees.
_GEOMETRIC_STEPS = 3
# Newton steps on Taubin's cubic; it converges quadratically from 0 in 5-8.
_NEWTON_STEPS = 30


def dot(a: np.ndarray, b: np.ndarray) -> float:
    """Inner product of two vectors without BLAS (internal).

    BLAS splits long dot products over threads, which on a busy machine costs milliseconds
    of waiting for a few microseconds of work; einsum's own loop never does.
    """
    return float(np.einsum("i,i->", a, b))


def mean(a: np.ndarray) -> float:
    """``a.mean()`` of a float64 vector, bit for bit, without its Python wrapper (internal)."""
    return float(np.add.reduce(a)) / a.size


def mean32(a: np.ndarray) -> float:
    """``float(a.mean())`` of a float32 vector, bit for bit, without its wrapper (internal).

    NumPy's steps: the sum in float32, divided in float64 by the count, rounded to float32.
    """
    return float(np.float32(float(np.add.reduce(a)) / a.size))


def std(a: np.ndarray) -> float:
    """``np.std(a)`` of a float64 vector, bit for bit, without its Python wrapper (internal).

    The same steps as NumPy's: the mean, the squared deviations, their mean, its root.
    """
    deviation = a - mean(a)
    deviation *= deviation
    return math.sqrt(float(np.add.reduce(deviation)) / a.size)


@record
class LineFit:
    """A straight line ``-sin(a) x + cos(a) y = offset`` fitted to points.

    Attributes
    ----------
    angle_rad : float
        Direction of the line from +x towards +y, in [0, pi) [rad].
    offset_m : float
        Signed distance of the line from the origin along its normal (-sin a, cos a) [m].
    rms_m : float
        Root-mean-square perpendicular distance of the points from the line [m].
    n_points : int
    """

    angle_rad: float
    offset_m: float
    rms_m: float
    n_points: int


@record
class CircleFit:
    """A circle fitted to points by minimising the geometric distance.

    Attributes
    ----------
    center_m : (float, float)
        Centre (x, y) [m].
    radius_m : float
        Radius [m]; inf when the points are collinear.
    rms_m : float
        Root-mean-square distance of the points from the circle [m].
    n_points : int
    """

    center_m: tuple[float, float]
    radius_m: float
    rms_m: float
    n_points: int


def _points(points: Any, minimum: int) -> np.ndarray:
    array = as_finite_array("points", points, ndim=2)
    if array.shape[1] != 2:
        raise ValueError(f"`points` must have shape (n, 2), got {array.shape}")
    if array.shape[0] < minimum:
        raise ValueError(f"`points` must hold at least {minimum} points, got {array.shape[0]}")
    return array


def _normalised(array: np.ndarray) -> tuple[np.ndarray, np.ndarray, tuple[float, float], float]:
    """Points scaled to a largest coordinate of 1 and moved to their mean; the mean and scale.

    Taubin's cubic takes the coordinates to the 8th power: at 1e50 m its coefficients
    overflow and at 1e-80 m they underflow; at unit scale neither happens. The points are
    scaled before they are centred, so that neither their sum nor their differences
    overflow. Returns x and y about the mean, the mean (x, y) and the scale [m].
    """
    scale = float(np.max(np.abs(array)))
    if scale == 0.0:  # all points at the origin
        scale = 1.0
    x, y = array[:, 0] / scale, array[:, 1] / scale
    middle_x, middle_y = float(x.mean()), float(y.mean())
    return x - middle_x, y - middle_y, (middle_x * scale, middle_y * scale), scale


def centred(
    x: np.ndarray, y: np.ndarray, weight: np.ndarray | None = None
) -> tuple[float, float, float, np.ndarray]:
    """Mean x and y of (weighted) points, their total weight, and the centred points.

    Returns the means and total weight as plain floats, and a new (3, n) array whose rows
    0 and 1 hold ``x - mean x`` and ``y - mean y`` (row 2 is left for the caller), so
    that one line fit, circle fit and vertex search can share them (internal).
    """
    if weight is None:
        total = float(x.size)
        mean_x, mean_y = mean(x), mean(y)
    else:
        total = float(np.add.reduce(weight))
        mean_x, mean_y = dot(weight, x) / total, dot(weight, y) / total
    return _about(x, y, mean_x, mean_y, total)


def _about(
    x: np.ndarray, y: np.ndarray, mean_x: float, mean_y: float, total: float
) -> tuple[float, float, float, np.ndarray]:
    """The points about their means, as `centred` returns them (internal)."""
    terms = np.empty((3, x.size))
    np.subtract(x, mean_x, out=terms[0])
    np.subtract(y, mean_y, out=terms[1])
    return mean_x, mean_y, total, terms


def line_through(points: tuple[float, float, float, np.ndarray]) -> tuple[float, float, float]:
    """Direction [rad], offset and sum of squared distances of the total least squares line.

    `points`: unweighted points as `centred` gives them (internal; see `line_fit_core`).
    """
    mean_x, mean_y, _, terms = points
    # the three sums of products in one einsum (the same loop, and sums, as three `dot`s)
    (sxx, sxy), (_, syy) = np.einsum("in,jn->ij", terms[:2], terms[:2]).tolist()
    angle = 0.5 * math.atan2(2 * sxy, sxx - syy)
    angle %= math.pi
    # the smallest eigenvalue of the scatter matrix is the sum of squared distances
    half = (sxx + syy) / 2
    smallest = max(half - math.hypot((sxx - syy) / 2, sxy), 0.0)
    offset = -math.sin(angle) * mean_x + math.cos(angle) * mean_y
    return angle, offset, smallest


def line_fit_core(x: np.ndarray, y: np.ndarray) -> LineFit:
    """Total least squares line through (x, y) (validated arrays; internal)."""
    angle, offset, smallest = line_through(centred(x, y))
    return LineFit(angle, offset, math.sqrt(smallest / x.size), int(x.size))


def circle_fit_algebraic(
    x: np.ndarray, y: np.ndarray, weight: np.ndarray | None = None
) -> CircleFit:
    """Closed-form (Taubin) circle through weighted points (internal).

    Minimises sum w (z - 2 a u - 2 b v - c)^2 with z = u^2 + v^2 (coordinates centred on
    the weighted mean) under Taubin's constraint, which normalises by the mean squared
    gradient of the algebraic distance and removes the pull toward small circles that the
    plain algebraic (Kasa) fit has on short arcs: the weighted moments give a cubic whose
    smallest root, found by Newton's method from 0, yields centre and radius. For the
    taxels of a curved band weighted by their signal, the radius is the band's centre line.
    """
    return fit_line_and_circle(x, y, weight)[1]


def _taubin(
    m_uu: float, m_vv: float, m_uv: float, m_uz: float, m_vz: float, m_zz: float
) -> tuple[float, float, float] | None:
    """Centre (a, b) and radius of Taubin's circle from centred weighted moments, or None."""
    m_z = m_uu + m_vv
    covariance = m_uu * m_vv - m_uv * m_uv
    variance_z = m_zz - m_z * m_z
    # characteristic polynomial of Taubin's generalised eigenproblem, in t
    c3 = 4.0 * m_z
    c2 = -3.0 * m_z * m_z - m_zz
    c1 = variance_z * m_z + 4.0 * covariance * m_z - m_uz * m_uz - m_vz * m_vz
    c0 = (
        m_uz * (m_uz * m_vv - m_vz * m_uv)
        + m_vz * (m_vz * m_uu - m_uz * m_uv)
        - variance_z * covariance
    )
    t = 0.0
    for _ in range(_NEWTON_STEPS):
        slope = c1 + t * (2.0 * c2 + 3.0 * c3 * t)
        if slope == 0:
            break
        step = (c0 + t * (c1 + t * (c2 + t * c3))) / slope
        t -= step
        if abs(step) <= 1e-12 * max(abs(t), m_z):
            break
    determinant = 2.0 * (t * t - t * m_z + covariance)
    if determinant == 0 or not math.isfinite(t):
        return None
    a = (m_uz * (m_vv - t) - m_vz * m_uv) / determinant
    b = (m_vz * (m_uu - t) - m_uz * m_uv) / determinant
    radius_sq = a * a + b * b + m_z
    # a radius 10^4 times the points' spread bows by < 1e-4 of it: collinear, not a circle
    if not math.isfinite(radius_sq) or math.hypot(a, b) > 1e4 * (math.sqrt(m_z) or 1.0):
        return None
    return a, b, math.sqrt(radius_sq)


def _centred_moments(
    points: tuple[float, float, float, np.ndarray], weight: np.ndarray | None
) -> tuple[float, ...]:
    """Moments up to 4th order of (weighted) points as `centred` gives them.

    Fills the third row of the points' array with u^2 + v^2 and returns the weighted means
    (m_uu, m_vv, m_uv, m_uz, m_vz, m_zz) as plain floats.
    """
    _, _, total, terms = points
    u, v, z = terms[0], terms[1], terms[2]  # (indexed: unpacking an array costs more)
    np.multiply(u, u, out=z)
    z += v * v
    weighted = terms if weight is None else terms * weight
    # plain floats from here: scalar arithmetic on NumPy scalars costs several times more
    # (and six divisions of floats cost less than one of the array: the same quotients)
    (s_uu, s_uv, s_uz), (_, s_vv, s_vz), (_, _, s_zz) = np.einsum(
        "in,jn->ij", weighted, terms
    ).tolist()
    return s_uu / total, s_vv / total, s_uv / total, s_uz / total, s_vz / total, s_zz / total


def _from_known(
    x: np.ndarray, y: np.ndarray, weight: np.ndarray, known: Mapping[str, float]
) -> tuple[tuple[float, float, float, np.ndarray], tuple[float, ...]]:
    """`centred` and `_centred_moments` of weighted points whose image moments are known.

    `known`: m00, m10 and m01 of the points as an image weighted by `weight` (as
    `cv2.moments` gives them, summed in double precision as `centred` sums them), which
    give the total weight and the means without summing over the points again. The
    centred moments are still summed over the points: OpenCV forms its central moments
    from raw sums, which loses digits that the faint curvature of a nearly straight band
    lives in.
    """
    total = known["m00"]
    points = _about(x, y, known["m10"] / total, known["m01"] / total, total)
    return points, _centred_moments(points, weight)


def taubin_circle(
    x: np.ndarray, y: np.ndarray, points: tuple[float, float, float, np.ndarray] | None = None
) -> tuple[float, float, float] | None:
    """Centre (x, y) and radius of the circle of `fit_line_and_circle`, without its RMS.

    None where that fit gives no circle (collinear points). `points`: (x, y) as `centred`
    gives them, if already made (its third row is overwritten).
    """
    points = points or centred(x, y)
    solution = _taubin(*_centred_moments(points, None))
    if solution is None:
        return None
    a, b, radius = solution
    return points[0] + a, points[1] + b, radius


def fit_line_and_circle(
    x: np.ndarray,
    y: np.ndarray,
    weight: np.ndarray | None = None,
    known: Mapping[str, float] | None = None,
) -> tuple[LineFit, CircleFit]:
    """Weighted total-least-squares line and Taubin circle from one pass of moments.

    Both fits need the same centred moments up to fourth order; they are formed in one
    ``einsum`` (no BLAS; see `dot`). The line is the weighted principal axis: for the
    taxels of a straight band weighted by their signal, the band's centre line, with
    `rms_m` its half-width over sqrt(3). The circle is Taubin's (see `circle_fit_algebraic`).
    `known`: the weighted points' image moments m00, m10 and m01, when at hand (see
    `_from_known`; with `weight`).
    """
    line, circle, _ = line_circle_and_distances(x, y, weight, known)
    return line, circle


def line_circle_and_distances(
    x: np.ndarray,
    y: np.ndarray,
    weight: np.ndarray | None = None,
    known: Mapping[str, float] | None = None,
) -> tuple[LineFit, CircleFit, np.ndarray | None]:
    """`fit_line_and_circle`, and each point's squared distance from the circle.

    The distances are those the circle's RMS is made of (None when no circle fits).
    """
    n = int(x.size)
    if known is None or weight is None:
        points = centred(x, y, weight)
        moments = _centred_moments(points, weight)
    else:
        points, moments = _from_known(x, y, weight, known)
    mean_x, mean_y, total, terms = points
    m_uu, m_vv, m_uv = moments[:3]
    angle = (0.5 * math.atan2(2 * m_uv, m_uu - m_vv)) % math.pi
    smallest = max((m_uu + m_vv) / 2 - math.hypot((m_uu - m_vv) / 2, m_uv), 0.0)
    offset = -math.sin(angle) * mean_x + math.cos(angle) * mean_y
    line = LineFit(angle, offset, math.sqrt(smallest), n)
    solution = _taubin(*moments)
    if solution is None:
        return line, CircleFit((math.nan, math.nan), math.inf, math.inf, n), None
    a, b, radius = solution
    # squared distances from the circle, (sqrt((u - a)^2 + (v - b)^2) - radius)^2, in place
    residual = terms[0] - a
    residual *= residual
    across = np.subtract(terms[1], b, out=terms[2])
    across *= across
    residual += across
    np.sqrt(residual, out=residual)
    residual -= radius
    residual *= residual
    total_squares = float(np.add.reduce(residual)) if weight is None else dot(weight, residual)
    rms = math.sqrt(total_squares / total)
    return line, CircleFit((mean_x + a, mean_y + b), radius, rms, n), residual


def circle_fit_core(x: np.ndarray, y: np.ndarray) -> CircleFit:
    """Taubin's algebraic circle refined by Gauss-Newton on geometric distance (internal)."""
    start = circle_fit_algebraic(x, y)
    if not math.isfinite(start.radius_m):
        return start
    mean_x, mean_y = float(x.mean()), float(y.mean())
    u, v = x - mean_x, y - mean_y
    scale = math.sqrt((dot(u, u) + dot(v, v)) / u.size) or 1.0
    u, v = u / scale, v / scale
    a, b = (start.center_m[0] - mean_x) / scale, (start.center_m[1] - mean_y) / scale
    radius = start.radius_m / scale
    for _ in range(_GEOMETRIC_STEPS):
        du, dv = u - a, v - b
        distance = np.sqrt(du * du + dv * dv)
        distance = np.where(distance > 1e-12, distance, 1e-12)
        jacobian = np.column_stack((-du / distance, -dv / distance, -np.ones_like(u)))
        residual = distance - radius
        step, *_ = np.linalg.lstsq(jacobian, -residual, rcond=None)
        a, b, radius = a + step[0], b + step[1], abs(radius + step[2])
    # a radius 10^4 times the points' spread bows by < 1e-4 of it: collinear, not a circle
    if not math.isfinite(radius) or radius > 1e4:
        return CircleFit((math.nan, math.nan), math.inf, math.inf, int(x.size))
    residual = np.hypot(u - a, v - b) - radius
    rms = math.sqrt(dot(residual, residual) / u.size)
    center = (float(mean_x + a * scale), float(mean_y + b * scale))
    return CircleFit(center, float(radius * scale), float(rms * scale), int(x.size))


def fit_line(points: Any) -> LineFit:
    """Fit a straight line to 2-D points by total least squares.

    Parameters
    ----------
    points : array_like, shape (n, 2)
        (x, y) [m], n >= 2.

    Returns
    -------
    LineFit

    Notes
    -----
    The direction is the principal eigenvector of the points' scatter matrix; the sum of
    squared perpendicular distances is its smallest eigenvalue.

    Examples
    --------
    >>> fit = fit_line([[0.0, 1.0], [1.0, 2.0], [2.0, 3.0]])
    >>> round(float(np.degrees(fit.angle_rad)), 6), round(fit.offset_m, 6), round(fit.rms_m, 9)
    (45.0, 0.707107, 0.0)
    """
    x, y, centre, scale = _normalised(_points(points, 2))
    fit = line_fit_core(x, y)
    sine, cosine = math.sin(fit.angle_rad), math.cos(fit.angle_rad)
    offset = fit.offset_m * scale + (cosine * centre[1] - sine * centre[0])
    return LineFit(fit.angle_rad, offset, fit.rms_m * scale, fit.n_points)


def fit_circle(points: Any) -> CircleFit:
    """Fit a circle to 2-D points: algebraic start, then geometric least squares.

    Parameters
    ----------
    points : array_like, shape (n, 2)
        (x, y) [m], n >= 3.

    Returns
    -------
    CircleFit
        Radius inf and centre NaN when the points are (nearly) collinear.

    Notes
    -----
    The algebraic fit solves ``x^2 + y^2 = 2 a x + 2 b y + c`` in the least-squares sense
    with Taubin's normalisation (closed form); Gauss-Newton steps then minimise
    sum (|p - centre| - r)^2.

    Examples
    --------
    >>> angle = np.linspace(0, np.pi / 2, 20)
    >>> fit = fit_circle(np.column_stack((2 + 3 * np.cos(angle), -1 + 3 * np.sin(angle))))
    >>> [round(v, 6) for v in fit.center_m], round(fit.radius_m, 6)
    ([2.0, -1.0], 3.0)
    """
    x, y, centre, scale = _normalised(_points(points, 3))
    fit = circle_fit_core(x, y)
    middle = (fit.center_m[0] * scale + centre[0], fit.center_m[1] * scale + centre[1])
    return CircleFit(middle, fit.radius_m * scale, fit.rms_m * scale, fit.n_points)
