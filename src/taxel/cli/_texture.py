"""``taxel texture``: fit a texture classifier on sliding recordings, and classify new ones.

``taxel texture fit DIR... --out MODEL.json`` reads every FabricSlide recording in the
folders (the fabric of each is in its file name), computes its spatial-frequency texture
features and stores a nearest-neighbour model as JSON. ``taxel texture classify FILE...
--model MODEL.json`` prints the predicted fabric of each recording (a folder stands for
the recordings in it), computing its features
with the settings stored in the model. A model written before these settings existed
(format version 1) holds none of them and gets the features of that time: "static"
normalisation, no load decorrelation, per-taxel levels.
"""

from __future__ import annotations

import argparse
import json
import re
import sys
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import numpy as np

from taxel.cli._arguments import NORMALIZATIONS, integer_in, positive_in, real_in
from taxel.cli._files import reading, writing

__all__ = ["register"]

_SIGNATURE_SETTINGS = (
    "band_edges",
    "segment_length",
    "trim_fraction",
    "normalization",
    "decorrelate_load",
)


# the library's names of the settings, as `fit`'s flags and as the settings of a model
_FLAGS = {
    "segment_length": "--segment-length",
    "trim_fraction": "--trim-fraction",
    "normalization": "--normalization",
}
_MODEL_SETTINGS = {name: f"the model's {name}" for name in _SIGNATURE_SETTINGS}


def _features(path: Path, settings: Mapping[str, Any], names: Mapping[str, str]) -> np.ndarray:
    """Texture features of one recording; an error names the recording.

    `names`: what each setting is called in errors, by its library name (the flags of
    `fit`, or the model's settings); each is replaced wherever the error names it.
    """
    from taxel.active import texture_features, texture_signature
    from taxel.io import read_fabricslide

    recording = read_fabricslide(path)
    options = {name: settings[name] for name in _SIGNATURE_SETTINGS if name in settings}
    try:
        signature = texture_signature(
            recording.readings, recording.time, recording.sliding_velocity, **options
        )
        return texture_features(signature, per_taxel=bool(settings.get("per_taxel", True)))
    except (ValueError, TypeError) as error:  # a model's setting may be of the wrong type
        message = re.sub(
            r"`readings` must have at least (\d+) steps, got (\d+)",
            r"it holds \2 readings of each taxel; a recording needs at least \1",
            str(error),
        )
        for name, shown in names.items():
            message = message.replace(f"`{name}`", shown)
        raise type(error)(f"{path}: {message}") from None


def _check_model(path: str, settings: Mapping[str, Any]) -> None:
    """Refuse a --model whose settings `_features` cannot follow as they are written."""
    reader = settings.get("reader", "fabricslide")
    if reader != "fabricslide":
        raise ValueError(
            f"--model {path}: fitted on {reader!r} recordings; taxel texture reads FabricSlide "
            "ones"
        )
    per_taxel = settings.get("per_taxel", True)
    if not isinstance(per_taxel, bool):  # (bool("no") is True)
        raise ValueError(
            f"--model {path}: its per_taxel must be true or false, got {json.dumps(per_taxel)}"
        )


def _check_features(path: str, features: np.ndarray, examples: np.ndarray) -> None:
    """Refuse features of another length than the model's examples (an edited model)."""
    given, fitted = features.shape[-1], examples.shape[-1]
    if given != fitted:
        raise ValueError(
            f"--model {path}: its settings give {given} features per recording, but it was "
            f"fitted on {fitted}: an edited or damaged model file"
        )


def _recordings_in(folder: str, argument: str = "DIR") -> list[Path]:
    """The FabricSlide recordings in `folder`; an error names the `argument` it was given as."""
    from taxel.io import list_fabricslide_files

    if not Path(folder).exists():
        raise FileNotFoundError(f"{argument} {folder}: no such folder")
    try:
        return list_fabricslide_files(folder)
    except ValueError as error:  # "FOLDER: not a directory", "FOLDER: holds no ..."
        raise ValueError(f"{argument} {error}") from None


def _fit(arguments: argparse.Namespace) -> int:
    from taxel.active import DEFAULT_BAND_EDGES, fit_texture_classifier
    from taxel.io import check_new_file, parse_fabricslide_name

    # a folder named twice is read once
    files = list(
        dict.fromkeys(
            path.resolve() for folder in arguments.directories for path in _recordings_in(folder)
        )
    )
    if arguments.neighbors > len(files):  # the library's `n_neighbors` bound, as the flag
        raise ValueError(
            f"--neighbors {arguments.neighbors}: the classifier votes among the {len(files)} "
            f"recordings it is fitted on; give at most {len(files)}"
        )
    out = check_new_file(
        arguments.out,
        suffix=".json",
        overwrite=arguments.overwrite,
        name="--out",
        inputs=tuple(files),
    )
    settings = {
        "reader": "fabricslide",
        "band_edges": [float(edge) for edge in DEFAULT_BAND_EDGES],
        "segment_length": arguments.segment_length,
        "trim_fraction": arguments.trim_fraction,
        "normalization": arguments.normalization,
        "decorrelate_load": not arguments.keep_load_coherent,
        "per_taxel": not arguments.pooled_only,
    }
    features = np.array([_features(path, settings, _FLAGS) for path in files])
    labels = [str(parse_fabricslide_name(path)["fabric"]) for path in files]
    if len(set(labels)) < 2:  # the library's "`labels` must name at least 2 classes"
        folders = " ".join(arguments.directories)
        raise ValueError(
            f"DIR {folders}: holds recordings of one fabric only ({labels[0]}, "
            f"{len(labels)} recording{'s' if len(labels) > 1 else ''}); a classifier tells "
            "fabrics apart: give folders with recordings of at least 2 fabrics"
        )
    model = fit_texture_classifier(
        features, labels, n_neighbors=arguments.neighbors, settings=settings
    )
    with writing("--out", out):
        model.save(out, overwrite=arguments.overwrite)
    counts = ", ".join(f"{label} {labels.count(label)}" for label in model.classes)
    print(f"fitted {len(files)} recordings of {len(model.classes)} classes ({counts}) -> {out}")
    return 0


def _classify(arguments: argparse.Namespace) -> int:
    from taxel.active import TextureClassifier

    # a folder stands for the recordings in it, as for `fit`
    for name in arguments.files:  # before the model is read: the likelier mistake
        if not Path(name).exists():
            raise FileNotFoundError(f"FILE {name}: no such file or folder")
    files = [
        found
        for name in arguments.files
        for found in (_recordings_in(name, "FILE") if Path(name).is_dir() else [Path(name)])
    ]
    with reading("--model", arguments.model):
        model = TextureClassifier.load(arguments.model)
    _check_model(arguments.model, model.settings)
    features = np.array([_features(path, model.settings, _MODEL_SETTINGS) for path in files])
    _check_features(arguments.model, features, model.examples)
    predictions = model.predict(features)
    if arguments.json:
        rows = [
            {"file": str(path), "predicted": str(label)}
            for path, label in zip(files, predictions, strict=True)
        ]
        json.dump(rows, sys.stdout, indent=2)
        sys.stdout.write("\n")
    else:
        for path, label in zip(files, predictions, strict=True):
            print(f"{path}\t{label}")
    return 0


def register(commands: Any) -> None:
    """Add the ``texture`` command and its ``fit`` and ``classify`` subcommands.

    Parameters
    ----------
    commands : argparse._SubParsersAction
        The subcommand registry of the ``taxel`` parser.
    """
    texture = commands.add_parser(
        "texture",
        help="classify fabrics from sliding recordings",
        description="Texture classification from sliding recordings (FabricSlide csv).",
    )
    actions = texture.add_subparsers(dest="texture_command", metavar="ACTION", required=True)
    fit = actions.add_parser(
        "fit",
        help="fit a classifier on labelled recordings",
        description="Fit a nearest-neighbour texture classifier on every FabricSlide "
        "recording in the folders; the fabric of each comes from its file name.",
    )
    fit.add_argument("directories", nargs="+", metavar="DIR", help="folders of recordings")
    fit.add_argument("--out", required=True, metavar="MODEL.json", help="model file to write")
    fit.add_argument("--overwrite", action="store_true", help="replace an existing model file")
    fit.add_argument(
        "--neighbors", type=integer_in(1), default=1, metavar="K", help="neighbours that vote (1)"
    )
    fit.add_argument(
        "--segment-length",
        type=positive_in(0.0, 100.0),
        default=0.2,
        metavar="METRES",
        help="travel per spectral segment [m] (0.2): at least 8 samples' travel and at most "
        "a recording's",
    )
    fit.add_argument(
        "--trim-fraction",
        type=real_in(0.0, 0.45),
        default=0.1,
        metavar="FRACTION",
        help="fraction of each recording dropped at each end (0.1)",
    )
    fit.add_argument(
        "--normalization",
        choices=NORMALIZATIONS,
        default="load",
        help="'load': spectra of each taxel's share of the load at every step, unchanged by "
        "the force and its fluctuations (default); 'static': spectra of the readings, "
        "levels relative to the squared mean reading (the features of format version 1)",
    )
    fit.add_argument(
        "--keep-load-coherent",
        action="store_true",
        help="keep the part of each taxel's signal that follows the load fluctuation "
        "(by default it is removed)",
    )
    fit.add_argument(
        "--pooled-only",
        action="store_true",
        help="use only the taxel-averaged band levels, not each taxel's",
    )
    fit.set_defaults(handler=_fit)
    classify = actions.add_parser(
        "classify",
        help="predict the fabric of recordings",
        description="Print the predicted fabric of each FabricSlide recording.",
    )
    classify.add_argument(
        "files",
        nargs="+",
        metavar="FILE",
        help="recordings to classify, or folders of them (each recording in a folder)",
    )
    classify.add_argument("--model", required=True, metavar="MODEL.json", help="fitted model")
    classify.add_argument("--json", action="store_true", help="print JSON instead of text")
    classify.set_defaults(handler=_classify)
