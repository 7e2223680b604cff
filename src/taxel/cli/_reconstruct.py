"""``taxel reconstruct``: a pressure map from one tactile frame (issue 4)."""

from __future__ import annotations

import argparse
import json
import math
import sys
from pathlib import Path

import numpy as np

from taxel.cli._arguments import integer_in, positive
from taxel.cli._files import writing
from taxel.cli._progress import add_no_progress, solving_on
from taxel.cli._reconstruct_input import load_readings

__all__ = ["register"]

_RULES = ("gcv", "lcurve", "discrepancy")
_BATCH_METHODS = ("tikhonov", "tsvd")  # the others solve one frame at a time
# the presets `taxel.reconstruction.forward_model_preset` builds (a test keeps them equal)
INVERTIBLE_PRESETS = (
    "vhdta128",
    "harmon10x20",
    "resistive16",
    "capacitive4x4",
    "piezo8x8",
    "reflective8x8",
)


def _rule_or_lambda(text: str) -> str | float:
    """--lambda: a rule's name, or a finite lambda >= 0."""
    if text in _RULES:
        return text
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"must be one of {', '.join(_RULES)} or a number >= 0, got {text!r}"
        ) from None
    from taxel.reconstruction import LARGEST_REGULARIZATION  # only for a number

    if not (math.isfinite(value) and 0 <= value <= LARGEST_REGULARIZATION):
        raise argparse.ArgumentTypeError(
            f"must be a number from 0 to {LARGEST_REGULARIZATION:g}, got {text}"
        )
    return value


def _order(arguments: argparse.Namespace) -> int:
    """--order, 0 by default; total variation penalizes the gradient, so tv takes no other."""
    if arguments.method == "tv" and arguments.order not in (None, 1):
        raise ValueError(
            f"--method tv penalizes the gradient (order 1); got --order {arguments.order}"
        )
    return 0 if arguments.order is None else arguments.order


def _run(arguments: argparse.Namespace) -> int:
    from taxel.reconstruction import (
        FORWARD_MODEL_PRESETS,
        forward_model_preset,
        reconstruct,
    )

    if arguments.sensor not in FORWARD_MODEL_PRESETS:
        raise ValueError(
            f"`--sensor` must be one of {', '.join(FORWARD_MODEL_PRESETS)}; "
            f"got {arguments.sensor!r}{_why_not_invertible(arguments.sensor)}"
        )
    _check_noise_level_is_used(arguments)
    from taxel.io import check_new_file, write_frame

    path = Path(arguments.frame)
    check_new_file(
        arguments.out, suffix=".npy", overwrite=arguments.overwrite, name="--out", inputs=(path,)
    )
    frame, warnings, excluded = load_readings(path, arguments.sensor, arguments.calibration)
    _check_batch(path, frame, arguments.method)
    for warning in warnings:
        sys.stderr.write(f"taxel reconstruct: warning: {warning}\n")
    spec = forward_model_preset(arguments.sensor, oversampling=arguments.oversampling)
    if arguments.noise_level is not None:
        try:
            spec.check_noise_level(arguments.noise_level)
        except ValueError:
            unit = f" {spec.reading_unit}".rstrip()
            raise ValueError(
                f"--noise-level must be below the full-scale reading of {arguments.sensor} "
                f"({spec.full_scale:.4g}{unit}), got {arguments.noise_level:g}"
            ) from None
    # only the iterative methods (nonneg, tv) report progress; the others draw no bar
    try:
        with solving_on(spec.load_shape, arguments.method, bar=not arguments.no_progress) as bar:
            result = reconstruct(
                frame,
                spec,
                method=arguments.method,
                order=_order(arguments),
                regularization=arguments.regularization,
                noise_level=arguments.noise_level,
                dead_taxels=excluded,
                progress=bar,
            )
    except ValueError as error:  # the library names its `frame`; the user gave FRAME
        raise ValueError(str(error).replace("`frame`", f"`FRAME` {str(path)!r}")) from None
    centre = result.centroid_m
    n_excluded = 0 if excluded is None else int(np.count_nonzero(excluded))
    second, second_rule = _support_stage(result)
    first = result.regularization if second is None else result.first_regularization
    summary = {
        "sensor": arguments.sensor,
        "method": result.method,
        "order": result.order,
        "rule": result.rule,
        "regularization": _finite_or_none(first),
        "at_bound": np.asarray(result.at_bound, dtype=bool).tolist(),
        "message": result.message,
        "support_regularization": None if second is None else _finite_or_none(second),
        "support_rule": second_rule,
        "residual_norm": _finite_or_none(result.residual_norm),
        "solution_norm": _finite_or_none(result.solution_norm),
        "normal_force_n": _finite_or_none(result.normal_force),
        "centroid_m": _finite_or_none(centre),
        "load_shape": list(spec.load_shape),
        "load_pitch_m": spec.load_pitch,
        "excluded_taxels": n_excluded,
        "converged": result.converged,
        "out": str(arguments.out),
    }
    if arguments.json:
        text = json.dumps(summary) + "\n"
    else:
        text = (
            f"{result.method} (order {result.order}), lambda = "
            f"{_format(first)} ({result.rule}{_bound_text(result)}){_unconverged_text(result)}"
            f"{_support_text(second, second_rule)}\n"
            f"residual norm {_format(result.residual_norm)}{_unit(spec.reading_unit)}, "
            f"solution norm {_format(result.solution_norm)}{_unit(_penalty_unit(result))}, "
            f"force {_format(result.normal_force)} N{_centre_text(centre)}\n"
            f"{_excluded_text(n_excluded, arguments.calibration)}"
            f"pressure map {result.pressure.shape} [Pa] written to {arguments.out}\n"
        )
    # written last: a run that fails before leaves no --out behind
    with writing("--out", arguments.out):
        write_frame(arguments.out, result.pressure, overwrite=arguments.overwrite, inputs=(path,))
    sys.stdout.write(text)
    return 0


def _excluded_text(count: int, calibration: str | None) -> str:
    """A line naming the taxels the calibration left out of the fit, or '' for none."""
    if not count:
        return ""
    taxels = "taxel" if count == 1 else "taxels"
    return f"{count} {taxels} excluded by --calibration {calibration} (left out of the fit)\n"


def _check_noise_level_is_used(arguments: argparse.Namespace) -> None:
    """Refuse --noise-level where nothing reads it (a rule other than discrepancy)."""
    rule = arguments.regularization
    if arguments.noise_level is None or rule == "discrepancy" or arguments.method == "support":
        return
    shown = rule if isinstance(rule, str) else f"{rule:g}"
    raise ValueError(
        f"--noise-level is used by --lambda discrepancy (and by --method support), not by "
        f"--lambda {shown}: leave it out, or choose the discrepancy rule"
    )


def _check_batch(path: Path, frame: np.ndarray, method: str) -> None:
    """Refuse a batch of frames for a method that reconstructs one frame at a time."""
    if frame.ndim <= 2 or method in _BATCH_METHODS:
        return
    count = math.prod(frame.shape[:-2])
    frames = "a batch of 1 frame" if count == 1 else f"{count} frames"
    raise ValueError(
        f"`FRAME` {str(path)!r} holds {frames}, but --method {method} reconstructs one frame "
        f"at a time ({' and '.join(_BATCH_METHODS)} take a batch)"
    )


def _why_not_invertible(name: str) -> str:
    """For a sensor preset the reconstruction cannot invert, ' (why)'; else ''."""
    from taxel.reconstruction import spec_from_sensor
    from taxel.sensor import PRESET_NAMES, make_sensor

    if name not in PRESET_NAMES:
        return ""
    try:
        spec_from_sensor(make_sensor(name))
    except ValueError as error:
        return f" ({str(error).removeprefix('`sensor` ')})"
    return ""


def _support_stage(result) -> tuple[float | None, str | None]:
    """(lambda, how chosen) of the second stage of method support; (None, None) for others.

    The ridge on the support is chosen by GCV ("gcv"); when the support is too large the
    non-negative solve at the first stage's lambda stands in ("first stage"); with no cell
    found pressed there is no second stage ("none", lambda 0).
    """
    if result.first_regularization is None:
        return None, None
    if result.support is None:
        return float(result.regularization), "first stage"
    if not result.support.any():
        return 0.0, "none"
    return float(result.regularization), "gcv"


def _bound_text(result) -> str:
    """', at its bound: WHY' when the rule took the end of its range of lambda, else ''."""
    if not np.any(result.at_bound):
        return ""
    _, _, why = result.message.partition("lambda held at the ")
    if why:
        return f", at its bound: the {why}"
    _, _, why = result.message.partition("found no mu with its target residual: ")  # tv
    return f", at its bound: no mu reaches the target, {why}" if why else ", at its bound"


def _unconverged_text(result) -> str:
    """', NOT converged (WHY)' for an iterative solve that stopped short, else ''."""
    if np.all(result.converged):
        return ""
    return f", NOT converged ({result.message.split(';')[0]})"


def _support_text(second: float | None, rule: str | None) -> str:
    """'; support ridge lambda = .. (gcv)' for method support, else ''."""
    if second is None:
        return ""
    if rule == "none":
        return "; no cell found pressed, no support stage"
    if rule == "first stage":
        return "; support too large: non-negative solve at the first stage's lambda"
    return f"; support ridge lambda = {_format(second)} ({rule})"


def _finite_or_none(value):
    """As `_plain`, with NaN or inf (a centroid without force) as None: JSON has neither."""
    plain = _plain(value)
    if isinstance(plain, float):
        return plain if np.isfinite(plain) else None
    return [_finite_or_none(item) for item in plain]


def _centre_text(centroid) -> str:
    """', centre of pressure (x, y) = (.., ..) mm' for one frame with force, else ''."""
    centre = np.asarray(centroid, dtype=float)
    if centre.ndim != 1 or not np.isfinite(centre).all():
        return ""
    return f", centre of pressure (x, y) = ({centre[0] * 1e3:.3f}, {centre[1] * 1e3:.3f}) mm"


def _plain(value):
    array = np.asarray(value, dtype=float)
    return float(array) if array.ndim == 0 else array.tolist()


def _unit(unit: str) -> str:
    """A unit after a number, or nothing for a dimensionless one (a strain)."""
    return f" {unit}" if unit else ""


def _penalty_unit(result) -> str:
    """The unit of |L x|: pressure per load cell to the penalty's order."""
    return ("Pa", "Pa/cell", "Pa/cell^2")[result.order]


def _format(values) -> str:
    """The first four of the values (one per frame, of a batch of any shape), then '...'."""
    flat = np.ravel(values)
    text = ", ".join(f"{v:.4g}" for v in flat[:4])
    return text + (", ..." if flat.size > 4 else "")


def register(commands: argparse._SubParsersAction) -> None:
    """Add ``taxel reconstruct`` to the command line."""
    parser = commands.add_parser(
        "reconstruct",
        help="recover the pressure map behind a tactile frame (regularized inverse)",
        description="Recover the pressure on the load grid from calibrated taxel readings, "
        "with regularization chosen automatically: one frame (.npy), or a batch of frames "
        "(tikhonov and tsvd), an array of any shape ending in the sensor's frame shape.",
    )
    parser.add_argument(
        "frame",
        metavar="FRAME.npy",
        help="raw codes with --calibration, or calibrated readings: the pressure felt at the "
        "taxels' depth [Pa], or for reflective8x8 the surface displacement [m]",
    )
    parser.add_argument(
        "--sensor",
        required=True,
        metavar="PRESET",
        # (taxel.reconstruction.FORWARD_MODEL_PRESETS, not imported to build the parser)
        help="the frame's sensor: " + ", ".join(INVERTIBLE_PRESETS),
    )
    parser.add_argument(
        "--method",
        default="tikhonov",
        choices=("tikhonov", "tsvd", "nonneg", "tv", "support"),
        help="tikhonov (default), tsvd (truncated SVD), nonneg (pressure >= 0), tv (total "
        "variation, for sharp-edged contacts), support (force and centroid of compact "
        "contacts: non-negative fit on the cells found pressed)",
    )
    parser.add_argument(
        "--order",
        type=int,
        choices=(0, 1, 2),
        help="penalty order: 0 identity (default), 1 gradient, 2 Laplacian; tv is order 1",
    )
    parser.add_argument(
        "--lambda",
        dest="regularization",
        type=_rule_or_lambda,
        default="discrepancy",
        metavar="gcv|lcurve|discrepancy|VALUE",
        help="parameter rule, or lambda >= 0 (mu [Pa] for tv); default discrepancy, with "
        "the noise estimated from the frame unless --noise-level is given",
    )
    parser.add_argument(
        "--noise-level",
        type=positive,
        default=None,
        metavar="SIGMA",
        help="noise std of one calibrated reading, in its unit (Pa; m for reflective8x8), "
        "for the discrepancy rule and --method support's threshold; estimated from the frame "
        "if omitted",
    )
    parser.add_argument(
        "--oversampling",
        type=integer_in(1, 8),  # taxel.reconstruction's ForwardModelSpec takes 1..8
        default=1,
        metavar="K",
        help="load cells per taxel along each axis (1-8)",
    )
    parser.add_argument("--out", required=True, metavar="PRESSURE.npy", help="output map")
    parser.add_argument(
        "--calibration",
        metavar="CAL.npz",
        help="per-taxel calibration of raw frames (from `taxel calibrate`); piezo8x8 has "
        "none (it senses only changes of load): give it the stress change [Pa]",
    )
    parser.add_argument("--overwrite", action="store_true", help="replace an existing --out")
    parser.add_argument(
        "--json",
        action="store_true",
        help="print a JSON summary (SI units; a key's unit is its suffix, as normal_force_n "
        "and centroid_m; the norms are in the readings' and the pressure's own units)",
    )
    add_no_progress(parser)
    parser.set_defaults(handler=_run)
