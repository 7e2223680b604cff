"""A slip detection in one figure: the pattern's displacement, the statistics, the events."""

from __future__ import annotations

import math
import os
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import numpy as np

from taxel.viz._saving import save_figure

__all__ = ["plot_slip"]

# the colour of each channel's statistic, its threshold and its events
_COLOURS = {
    "displacement": "black",
    "piezo": "tab:purple",
    "onset": "tab:green",
    "speed": "tab:red",
    "late": "tab:brown",
}
_TRUTH_STYLES: tuple[Any, ...] = (":", "-.", (0, (5, 2, 1, 2, 1, 2)))
_NAMES = {
    "piezo": "piezo CUSUM",
    "onset": "onset filter",
    "speed": "speed run-ahead",
    "late": "late run-ahead",
}


def plot_slip(
    detection: Any,
    detector: Any = None,
    *,
    truth: Any = None,
    path: str | os.PathLike[str] | None = None,
    overwrite: bool = False,
    ax: Any = None,
) -> Any:
    """Draw a slip detection: the pattern's displacement and the statistics that decide slip.

    The upper panel shows the displacement of the contact pattern from its held position
    (x, y and the size of its 3-frame mean, which incipient slip compares with
    ``incipient_threshold`` position-noise standard deviations over sqrt(3), drawn dashed).
    The lower panel shows the gross-slip statistics in noise units on a symmetric log
    scale, each channel the detector uses with its threshold dashed in the same colour:
    the piezo CUSUM and the onset filter (with PVDF frames), the speed run-ahead (without
    them, or past the backup threshold with them) and the late run-ahead. The backup and
    late channels count only once their reference window lies after the incipient
    decision; before that they are drawn faint. The warm-up is shaded, events are vertical
    lines labelled with their kind and channel, truth frames are dotted with a triangle.

    Parameters
    ----------
    detection : taxel.active.SlipDetection
        From `taxel.active.detect_slip` or `SlipDetector.run`.
    detector : taxel.active.SlipDetector, optional
        The detector that made `detection` (its thresholds and warm-up are drawn); the
        default detector when omitted, with the warm-up read from the statistics.
    truth : int, sequence of int or mapping of str to int, optional
        True frames to mark (e.g. a `SlipSequence`'s ``gross_frame``); a mapping names
        them (``{"gross": 345}``). None entries are skipped.
    path : str or path-like, optional
        Also save the figure there, in the format its suffix names (PNG for a suffix
        matplotlib does not know), written beside it and renamed once complete.
    overwrite : bool, default False
        Replace an existing `path`.
    ax : pair of matplotlib.axes.Axes, optional
        The (displacement, statistics) axes to draw on, of one figure; a new figure is
        made when omitted.

    Returns
    -------
    matplotlib.figure.Figure

    Raises
    ------
    TypeError
        When `detection`, `detector`, `ax` or `path` is of the wrong type.
    ValueError
        When a `truth` frame lies outside the sequence, or `path` cannot be written.
    FileExistsError
        When `path` exists and `overwrite` is False.

    Examples
    --------
    The blob of `taxel.active.detect_slip`'s example, still for 60 frames, then sliding:

    >>> import numpy as np
    >>> from taxel.active import detect_slip
    >>> rows, cols = np.mgrid[:16, :16] * 2e-3
    >>> centre = np.where(np.arange(120) < 60, 0.0, 30e-3 * (np.arange(120) - 60) / 1000)
    >>> frames = np.array([1000 * np.exp(-((cols - 0.014 - c) ** 2 + (rows - 0.015) ** 2)
    ...                    / 2 / 0.004**2) for c in centre])
    >>> frames += np.random.default_rng(0).normal(0, 2, frames.shape)
    >>> figure = plot_slip(detect_slip(frames, frame_rate=1000.0), truth={"gross": 60})
    >>> [axes.get_ylabel() for axes in figure.axes]
    ['displacement [mm]', 'statistic [noise units]']
    >>> [text.get_text() for text in figure.axes[0].texts]
    ['incipient (displacement), 61 ms', 'gross (speed), 61 ms']
    """
    from matplotlib.figure import Figure  # no pyplot: no GUI backend, no global state

    from taxel.active import SlipDetection, SlipDetector

    _check_type("detection", detection, SlipDetection, "a SlipDetection")
    if detector is not None:
        _check_type("detector", detector, SlipDetector, "a SlipDetector")
    target = None if path is None else _checked_path(path, overwrite)
    n = detection.displacement.shape[0]
    marks = _truth_frames(truth, n)
    if ax is None:
        figure = Figure(figsize=(11, 6.5), layout="constrained")
        upper, lower = figure.subplots(2, 1, sharex=True, height_ratios=(2, 3))
    else:
        upper, lower = _checked_axes(ax)
        figure = upper.figure
    if detector is None:  # the default thresholds, over the detection's own warm-up
        detector = SlipDetector(warm_up=_warm_up(detection))
    warm_up = detector.warm_up
    milliseconds = np.arange(n) / detection.frame_rate * 1e3
    _draw_displacement(upper, detection, detector, milliseconds)
    _draw_statistics(lower, detection, detector, milliseconds)
    for axes in (upper, lower):
        axes.axvspan(
            -0.5e3 / detection.frame_rate,
            (warm_up - 0.5) / detection.frame_rate * 1e3,
            color="0.85",
            zorder=0,
            label="warm-up",
        )
        axes.grid(alpha=0.3)
    _draw_events(upper, lower, detection)
    _draw_truth(upper, lower, marks, detection.frame_rate)
    lower.set_xlabel("time [ms]")
    lower.set_xlim(milliseconds[0], milliseconds[-1])
    for axes in (upper, lower):  # beside the axes: the statistics fill their panel
        axes.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize="small")
    state = detection.initial_state
    if state != "holding":  # `SlipDetector.decide` reports no onset then
        state += " (no onset is reported)"
    upper.set_title(
        f"{n} frames at {detection.frame_rate:g} Hz; initial state {state}; "
        f"position noise {detection.position_noise * 1e6:.3g} um",
        fontsize=10,
        pad=12,  # above the truth's triangles
    )
    if target is not None:
        save_figure(figure, target)
    return figure


def _check_type(name: str, value: Any, kind: type, what: str) -> None:
    if not isinstance(value, kind):
        raise TypeError(f"`{name}` must be {what}, got {value!r}")


def _checked_path(path: Any, overwrite: Any) -> Path:
    from taxel.io import check_new_file

    if not isinstance(path, str | os.PathLike):
        raise TypeError(f"`path` must be a file path, got {path!r}")
    if not isinstance(overwrite, bool):
        raise TypeError(f"`overwrite` must be True or False, got {overwrite!r}")
    return check_new_file(path, overwrite=overwrite)


def _checked_axes(ax: Any) -> tuple[Any, Any]:
    from matplotlib.axes import Axes

    pair = tuple(ax) if isinstance(ax, list | tuple | np.ndarray) else (ax,)
    if len(pair) != 2 or not all(isinstance(item, Axes) for item in pair):
        raise TypeError(f"`ax` must be two Axes (displacement, statistics), got {ax!r}")
    if pair[0].figure is not pair[1].figure:
        raise ValueError("`ax` must be two Axes of one figure")
    return pair[0], pair[1]


def _truth_frames(truth: Any, n: int) -> list[tuple[str, int]]:
    """The truth frames to mark, each with its legend label."""
    if truth is None:
        return []
    if isinstance(truth, Mapping):
        items = [(f"true {name}", frame) for name, frame in truth.items()]
    elif isinstance(truth, list | tuple | np.ndarray):
        items = [("truth", frame) for frame in truth]
    else:
        items = [("truth", truth)]
    marks = []
    for label, frame in items:
        if frame is None:
            continue
        if isinstance(frame, bool) or not isinstance(frame, int | np.integer):
            raise TypeError(f"`truth` must hold frame numbers (integers), got {frame!r}")
        if not 0 <= frame < n:
            raise ValueError(f"`truth` frame {frame} lies outside the sequence's {n} frames")
        marks.append((label, int(frame)))
    return marks


def _warm_up(detection: Any) -> int:
    """The warm-up: the statistics are NaN during it (the speed run-ahead never after)."""
    finite = np.flatnonzero(np.isfinite(detection.speed_statistic))
    return int(finite[0]) if finite.size else detection.displacement.shape[0]


def _draw_displacement(axes: Any, detection: Any, detector: Any, milliseconds: np.ndarray) -> None:
    moved = (detection.displacement - detector.held_position(detection)) * 1e3
    axes.plot(milliseconds, moved[:, 0], color="tab:blue", lw=1, label="x")
    axes.plot(milliseconds, moved[:, 1], color="tab:orange", lw=1, label="y")
    # what incipient slip compares: the size of the mean of the last 3 frames
    mean3 = np.full(len(moved), np.nan)
    cumulative = np.cumsum(moved, axis=0)
    mean3[3:] = np.linalg.norm(cumulative[3:] - cumulative[:-3], axis=1) / 3.0
    colour = _COLOURS["displacement"]
    limit = detector.incipient_threshold * detection.position_noise / math.sqrt(3.0) * 1e3
    label = "size (3-frame mean)"
    if math.isfinite(limit) and limit > 0:
        label += f", threshold {limit * 1e3:.3g} um dashed"
        axes.axhline(limit, color=colour, ls="--", lw=1)
        # linear within about the threshold, logarithmic beyond: the microns of the
        # Cattaneo-Mindlin shift and the millimetres of sliding both show
        axes.set_yscale("symlog", linthresh=10.0 ** math.floor(math.log10(limit)))
    axes.plot(milliseconds, mean3, color=colour, lw=1.2, label=label)
    axes.set_ylabel("displacement [mm]")


def _channels(detection: Any, detector: Any) -> list[tuple[str, np.ndarray, float, int]]:
    """The detector's channels (`SlipDetector.channels`) that have a statistic to draw."""
    return [item for item in detector.channels(detection) if not np.all(np.isnan(item[1]))]


def _draw_statistics(axes: Any, detection: Any, detector: Any, milliseconds: np.ndarray) -> None:
    for channel, statistic, threshold, start in _channels(detection, detector):
        colour = _COLOURS[channel]
        name = _NAMES[channel]
        if start > 0:  # before it is armed, the channel decides nothing: faint
            axes.plot(
                milliseconds[: start + 1], statistic[: start + 1], color=colour, lw=0.8, alpha=0.3
            )
            when = (
                "never armed"
                if start >= len(statistic)
                else (f"armed from {milliseconds[start]:.4g} ms")
            )
            name = f"{name} ({when})"
        label = f"{name}, threshold {threshold:g} dashed"
        axes.plot(milliseconds[start:], statistic[start:], color=colour, lw=1.2, label=label)
        axes.axhline(threshold, color=colour, ls="--", lw=1)
    axes.set_yscale("symlog", linthresh=1.0)
    axes.set_ylabel("statistic [noise units]")


def _draw_events(upper: Any, lower: Any, detection: Any) -> None:
    from matplotlib.transforms import blended_transform_factory

    for number, event in enumerate(detection.events):
        time = event.time * 1e3
        colour = _COLOURS.get(event.channel, "black")
        for axes in (upper, lower):
            axes.axvline(time, color=colour, lw=1.5, alpha=0.8)
        # at most one incipient and one later (or same-frame) gross event: the first is
        # labelled left of its line, the second right of it, so that they never overlap
        left = number == 0 and len(detection.events) > 1
        upper.text(
            time,
            0.97,
            f"{event.kind} ({event.channel}), {time:.4g} ms",
            transform=blended_transform_factory(upper.transData, upper.transAxes),
            rotation=90,
            ha="right" if left else "left",
            va="top",
            fontsize="small",
            color=colour,
            bbox={"facecolor": "white", "edgecolor": "none", "alpha": 0.8, "pad": 1},
        )


def _draw_truth(upper: Any, lower: Any, marks: list[tuple[str, int]], rate: float) -> None:
    styles: dict[str, Any] = {}  # one line style for each label
    for label, frame in marks:
        time = frame / rate * 1e3
        shown = None if label in styles else label
        style = styles.setdefault(label, _TRUTH_STYLES[len(styles) % len(_TRUTH_STYLES)])
        for axes in (upper, lower):
            axes.axvline(time, color="magenta", ls=style, lw=1.5, label=shown)
            shown = None
            axes.plot(
                [time],
                [1.0],
                "v",
                color="magenta",
                markersize=8,
                clip_on=False,
                transform=axes.get_xaxis_transform(),
            )
