"""``taxel active recognize``: an object touched up to three times, against a model library.

The library is loaded from ``--library`` when that file exists (refused when made on
another sensor, at another force, or of other features than this version's touches), else
built (and saved there).
"""

from __future__ import annotations

import argparse
from typing import Any

from taxel.cli._active_procedures import _check_forces, _check_made_on, _emit
from taxel.cli._files import building, file_or_build
from taxel.cli._main import CommandLineError

__all__ = ["recognize"]

_TOUCH_FORCE = 15.0  # taxel.active's DEFAULT_TOUCH_FORCE, of recognition's touches


def _recognition_library(path: str) -> Any:
    """The model library in `path`, refused (naming `path`) unless of recognition's features."""
    from taxel.active import DESCRIPTOR_NAMES, ModelLibrary

    library = ModelLibrary.load(path)
    if tuple(library.feature_names) != DESCRIPTOR_NAMES:
        raise ValueError(
            f"`path` {path!r} holds a library of {len(library.feature_names)} other features "
            f"than the {len(DESCRIPTOR_NAMES)} of this version's touches: build it again"
        )
    return library


def recognize(arguments: argparse.Namespace) -> int:
    from taxel.active import build_model_library, recognize_object

    force = _TOUCH_FORCE if arguments.force is None else arguments.force
    _check_forces("--force", [force], arguments.sensor)
    built: list[str] = []
    bar = not arguments.no_progress
    library = file_or_build(
        arguments.library,
        _recognition_library,
        lambda path, progress: build_model_library(
            sensor=arguments.sensor, normal_force=force, path=path, progress=progress
        ),
        "model library",
        "--library",
        built,
        unit="pose",
        bar=bar,
    )
    if library is not None:
        _check_made_on("--library", arguments.library, library.sensor, arguments.sensor)
        if arguments.force is not None and library.normal_force != force:
            raise CommandLineError(
                f"--force {force:g}: the --library {arguments.library} was made with "
                f"{library.normal_force:g} N; give that or another --library"
            )
        force = library.normal_force
    else:  # (with no --force, the library recognize_object makes by default)
        with building("model library", "pose", bar=bar) as progress:
            library = build_model_library(
                sensor=arguments.sensor, normal_force=force, progress=progress
            )
    result = recognize_object(
        arguments.object,
        library=library,
        sensor=arguments.sensor,
        rng=arguments.seed,
        stop_early=not arguments.three_touches,
    )
    lines = [
        f"touched a {arguments.object} {result.n_touches} time(s) at {force:g} N on "
        f"{arguments.sensor}",
        "ranked candidates:",
    ]
    lines += [f"  {name:12} score {score:.3f}" for name, score, _ in result.candidates]
    lines.append(f"recognized as: {result.message}")
    return _emit(arguments, result.to_dict(), lines, built)
