"""Synthetic tactile images of the indenters of issue 5, with known answers.

Each pattern returns a pressure-like field (arbitrary units, 0 off contact) shaped as an
elastic half-space would give it: square-root edges for smooth bodies (Hertz), inverse
square-root peaks at the sharp edges of flat faces, logarithmic peaks under cones and
wedges. `render` samples it by area averaging, blurs it like a cover, and optionally maps it
to an 8-bit FTIR-like frame (saturating brightness, baseline, camera noise, scratches).
Coordinates are in taxels: ``x`` along columns, ``y`` along rows, origin at the image centre.
"""

from __future__ import annotations

import numpy as np
from scipy import ndimage

SUPERSAMPLE = 3


def _grid(shape, supersample=SUPERSAMPLE):
    rows, cols = shape
    step = 1.0 / supersample
    y = (np.arange(rows * supersample) + 0.5) * step - 0.5 - (rows - 1) / 2
    x = (np.arange(cols * supersample) + 0.5) * step - 0.5 - (cols - 1) / 2
    return np.meshgrid(x, y)


def _edge_peak(distance, scale):
    """Inverse square-root rise toward a sharp edge (distance >= 0 inside the face)."""
    return 1.0 / np.sqrt(np.clip(distance / scale, 0.02, None) + 0.02)


def _rotate(x, y, centre, angle):
    dx, dy = x - centre[0], y - centre[1]
    c, s = np.cos(angle), np.sin(angle)
    return c * dx + s * dy, -s * dx + c * dy


def cone(x, y, centre=(0.0, 0.0), radius=3.0):
    r = np.hypot(x - centre[0], y - centre[1])
    return np.where(r < radius, np.arccosh(radius / np.clip(r, 0.05, None).clip(max=radius)), 0)


def sphere(x, y, centre=(0.0, 0.0), radius=10.0):
    r2 = (x - centre[0]) ** 2 + (y - centre[1]) ** 2
    return np.sqrt(np.clip(1 - r2 / radius**2, 0, None))


def flat_punch(x, y, centre=(0.0, 0.0), radius=15.0):
    r = np.hypot(x - centre[0], y - centre[1])
    return np.where(r < radius, _edge_peak(radius - r, radius) * 0.25, 0)


def band(x, y, centre=(0.0, 0.0), angle=0.0, half_width=2.0, length=np.inf, wedge=False):
    along, across = _rotate(x, y, centre, angle)
    inside = (np.abs(across) < half_width) & (np.abs(along) < length / 2)
    if wedge:
        profile = np.arccosh(half_width / np.clip(np.abs(across), 0.05, half_width))
    else:
        profile = np.sqrt(np.clip(1 - (across / half_width) ** 2, 0, None))
    return np.where(inside, profile, 0)


def arc(x, y, centre=(0.0, -60.0), radius=60.0, half_width=2.0):
    r = np.hypot(x - centre[0], y - centre[1])
    return np.sqrt(np.clip(1 - ((r - radius) / half_width) ** 2, 0, None))


def washer(x, y, centre=(0.0, 0.0), inner=8.0, outer=16.0):
    r = np.hypot(x - centre[0], y - centre[1])
    inside = (r > inner) & (r < outer)
    peak = _edge_peak(np.minimum(r - inner, outer - r), outer - inner) * 0.3
    return np.where(inside, peak, 0)


def half_plane(x, y, centre=(0.0, 0.0), angle=0.0):
    """Face covering the side y' > 0 of a line through `centre` at `angle`."""
    _, across = _rotate(x, y, centre, angle)
    return np.where(across > 0, _edge_peak(across, 40.0) * 0.3, 0)


def corner(x, y, centre=(0.0, 0.0), angle=0.0, opening=np.pi / 2):
    """Face inside the wedge of the given opening whose bisector points along `angle`."""
    first, second = angle - opening / 2, angle + opening / 2
    _, d1 = _rotate(x, y, centre, first)
    _, d2 = _rotate(x, y, centre, second)
    d1, d2 = d1, -d2
    inside = (d1 > 0) & (d2 > 0)
    return np.where(inside, _edge_peak(np.minimum(d1, d2), 40.0) * 0.3, 0)


def plate_with_hole(x, y, centre=(0.0, 0.0), radius=10.0):
    r = np.hypot(x - centre[0], y - centre[1])
    return np.where(r > radius, _edge_peak(r - radius, 40.0) * 0.3, 0)


def plate_with_slot(x, y, centre=(0.0, 0.0), angle=0.0, width=8.0, length=60.0):
    along, across = _rotate(x, y, centre, angle)
    gap_along = np.abs(along) - length / 2
    gap_across = np.abs(across) - width / 2
    outside = (gap_along > 0) | (gap_across > 0)
    distance = np.maximum(gap_along, gap_across)
    return np.where(outside, _edge_peak(np.clip(distance, 0, None), 40.0) * 0.3, 0)


def texture(x, y, rng, count=40, spike=1.0, width=2.0, base=0.3):
    """A flat face with bumps: foam (wide, low), rasp (sharp, high), screen-like."""
    field = np.full_like(x, base)
    half_x, half_y = np.ptp(x) / 2, np.ptp(y) / 2
    for _ in range(count):
        cx, cy = rng.uniform(-half_x, half_x), rng.uniform(-half_y, half_y)
        field += spike * np.exp(-((x - cx) ** 2 + (y - cy) ** 2) / (2 * width**2))
    return field


def render(
    pattern,
    shape=(128, 128),
    *,
    blur=1.0,
    noise=0.0,
    ftir=False,
    scratches=0,
    rng=None,
    **parameters,
):
    """Sample `pattern` on a (rows, cols) array, blur, add noise; optionally an 8-bit frame.

    Returns float64 in [0, ~1] (a pressure map normalised to peak 1) or, with `ftir`, uint8
    with a baseline of 24 and brightness saturating toward 120 as in the seed's images.
    """
    rng = np.random.default_rng(rng)
    x, y = _grid(shape)
    if pattern is texture:
        parameters.setdefault("rng", rng)
    fine = pattern(x, y, **parameters)
    image = fine.reshape(shape[0], SUPERSAMPLE, shape[1], SUPERSAMPLE).mean(axis=(1, 3))
    if blur > 0:
        image = ndimage.gaussian_filter(image, blur, mode="nearest")
    image = image / max(image.max(), 1e-12)
    if ftir:
        image = 24 + 96 * (1 - np.exp(-2.5 * image))
        image += rng.normal(scale=noise * 255, size=shape)
        for _ in range(scratches):
            row = rng.integers(0, shape[0])
            image[row, :] += 6.0
        return np.clip(np.round(image), 0, 255).astype(np.uint8)
    return image + rng.normal(scale=noise, size=shape)
