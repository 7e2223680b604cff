"""Validation of frames and of the regularization argument, shared by every solver."""

from __future__ import annotations

from typing import Any

import numpy as np

from taxel._validation import check_positive, refuse_complex
from taxel.reconstruction._choice import RULES
from taxel.reconstruction._spec import ForwardModelSpec

__all__ = ["LARGEST_REGULARIZATION", "as_frames", "parse_regularization", "restore_batch"]

# The largest lambda taken: the solvers use its square, which must stay a finite float.
LARGEST_REGULARIZATION = 1e150


def as_frames(frames: Any, spec: ForwardModelSpec) -> tuple[np.ndarray, tuple[int, ...]]:
    """Frames as a float (B, rows, cols) array and the original batch shape.

    NaN or inf is allowed only at dead taxels (they are excluded from every fit and set to
    zero here); anywhere else it is an error naming `frame`.
    """
    refuse_complex("frame", frames)
    try:
        array = np.array(frames, dtype=np.float64)
    except (TypeError, ValueError):
        raise TypeError(f"`frame` must be numeric, got {type(frames).__name__}") from None
    if array.ndim < 2 or array.shape[-2:] != spec.shape:
        raise ValueError(
            f"`frame` must have shape {spec.shape} (or a batch of them) for this sensor, "
            f"got {array.shape}"
        )
    batch = array.shape[:-2]
    if array.size == 0:
        raise ValueError(f"`frame` must hold at least one frame, got shape {array.shape}")
    array = array.reshape(-1, *spec.shape)
    if np.isfinite(array).all():  # (the usual frame: the dead taxels' mask is not needed)
        if spec.dead_taxels:
            array[:, ~spec.live_taxels] = 0.0
        return array, batch
    live = spec.live_taxels
    bad = ~np.isfinite(array) & live
    if bad.any():
        raise ValueError(
            f"`frame` must be finite at live taxels, got {int(bad.sum())} NaN or inf value(s)"
        )
    array[:, ~live] = 0.0
    return array, batch


def one_frame(frame: Any, spec: ForwardModelSpec, method: str) -> np.ndarray:
    """A single frame as a float (rows, cols) array (see `as_frames`); a batch is an error."""
    frames, batch = as_frames(frame, spec)
    if batch != ():
        raise ValueError(f"`frame` must be one frame {spec.shape} for {method}")
    return frames[0]


def restore_batch(values: np.ndarray, batch: tuple[int, ...]) -> Any:
    """Per-frame values (B, ...) back to the caller's batch shape; scalars for one frame."""
    if batch == ():
        item = values[0]
        return float(item) if np.ndim(item) == 0 else item
    return values.reshape(*batch, *values.shape[1:])


def parse_regularization(value: Any) -> tuple[str, float | None]:
    """("given", lambda) for a number >= 0, (rule, None) for a rule name."""
    if isinstance(value, str):
        if value in RULES:
            return value, None
        try:
            value = float(value)
        except ValueError:
            raise ValueError(
                f"`regularization` must be a number >= 0 or one of {', '.join(RULES)}; "
                f"got {value!r}"
            ) from None
    value = check_positive("regularization", value, allow_zero=True)
    if value > LARGEST_REGULARIZATION:
        raise ValueError(
            f"`regularization` must be <= {LARGEST_REGULARIZATION:g} (the solvers square it), "
            f"got {value:g}"
        )
    return "given", value
