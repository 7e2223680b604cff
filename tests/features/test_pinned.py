"""Pinned outputs of `extract`: speed work on the features must not change what they find.

Every field of `TactileFeatures` (not only the JSON of `to_dict`) is compared, on frames of
the sensor simulator (stored in ``data/pinned_frames.npz``: ten from the vhdta128 camera
sensor, ten from the 16x16 resistive array, drawn from the features benchmark's set) and
on the synthetic frames the speed benchmark times. Discrete results (types, rules, counts,
flags) must match exactly, numbers to 1e-9 relative: far tighter than any change of method,
loose enough for another build of NumPy or OpenCV. The texture spectrum's fields come from
OpenCV's float32 DFT, whose rounding differs between OpenCV releases (4.x and 5.0 differ by
up to 2e-7 relative): they are held to 1e-5, still far tighter than a change of method.

A deliberate change of results is recorded by running this file as a script
(``python tests/features/test_pinned.py``), which rewrites ``data/pinned_features.json``.
"""

from __future__ import annotations

import dataclasses
import json
import math
import sys
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))
import synthetic

from taxel.features import extract
from taxel.sensor import make_sensor

DATA = Path(__file__).resolve().parent / "data"
FRAMES = DATA / "pinned_frames.npz"
EXPECTED = DATA / "pinned_features.json"
PATTERNS = ["cone", "band", "arc", "washer", "corner", "plate_with_slot", "texture"]
RELATIVE = 1e-9
# fields computed in float32 (`taxel.features._spectrum`): a float32 rounding is ~1e-7
FLOAT32_FIELDS = (".texture.band_energy[", ".texture.spectral_centroid_per_m")
RELATIVE_FLOAT32 = 1e-5


def _sensor(name: str):
    # as in benchmarks/features_scenes.py: the 16x16 array's contacts solved on 0.5 mm cells
    if name == "resistive16":
        return replace(make_sensor("resistive16"), oversampling=4)
    return make_sensor(name)


def _cases() -> dict:
    """Name -> (image, sensor or pitch, keyword options) of every pinned frame."""
    cases = {}
    with np.load(FRAMES) as stored:
        names = sorted(key for key in stored.files if not key.endswith("_pose"))
        sensors = {prefix: _sensor(prefix) for prefix in {name.split("_")[0] for name in names}}
        for name in names:
            image = stored[name]
            if name.startswith("resistive16"):
                image = image.astype(np.int64)  # as the array outputs it
            sensor = sensors[name.split("_")[0]]
            cases[name] = (image, sensor, {"pose": stored[name + "_pose"]})
    for pattern in PATTERNS:
        generator = getattr(synthetic, pattern)
        frame = synthetic.render(generator, ftir=True, noise=0.03, scratches=3, rng=0)
        grid = synthetic.render(generator, (16, 16), noise=0.01, rng=0)
        cases[f"synthetic128_{pattern}"] = (frame, 3.3e-2 / 128, {})
        cases[f"synthetic16_{pattern}"] = (grid, 1.5e-3, {})
        cases[f"synthetic16_calibrated_{pattern}"] = (
            grid * 1e4,
            1.5e-3,
            {"calibrated": True, "pose": np.eye(4), "depth": grid * 1e-4},
        )
    return cases


def _plain(value):
    """A features tree as JSON values: dataclasses to dicts, tuples to lists, NumPy to Python."""
    if dataclasses.is_dataclass(value):
        return {f.name: _plain(getattr(value, f.name)) for f in dataclasses.fields(value)}
    if isinstance(value, list | tuple):
        return [_plain(item) for item in value]
    if isinstance(value, np.generic):
        return value.item()
    return value


def _compare(found, expected, where: str) -> list[str]:
    if isinstance(expected, dict):
        if not isinstance(found, dict) or found.keys() != expected.keys():
            return [f"{where}: keys {sorted(found)} != {sorted(expected)}"]
        return [e for k in expected for e in _compare(found[k], expected[k], f"{where}.{k}")]
    if isinstance(expected, list):
        if not isinstance(found, list) or len(found) != len(expected):
            return [f"{where}: {found!r} != {expected!r}"]
        return [e for i, pair in enumerate(zip(found, expected, strict=True))
                for e in _compare(*pair, f"{where}[{i}]")]  # fmt: skip
    if isinstance(expected, float) and not isinstance(found, bool | str | type(None)):
        relative = RELATIVE_FLOAT32 if any(f in where for f in FLOAT32_FIELDS) else RELATIVE
        same = (math.isnan(expected) and math.isnan(found)) or math.isclose(
            found, expected, rel_tol=relative, abs_tol=1e-300
        )
        return [] if same else [f"{where}: {found!r} != {expected!r}"]
    return (
        []
        if found == expected and type(found) is type(expected)
        else [f"{where}: {found!r} != {expected!r}"]
    )


CASES = _cases()


@pytest.fixture(scope="module")
def expected() -> dict:
    return json.loads(EXPECTED.read_text())


def test_every_case_is_pinned(expected):
    assert sorted(expected) == sorted(CASES)


@pytest.mark.parametrize("name", sorted(CASES))
def test_extract_matches_pinned_output(name, expected):
    image, sensor, options = CASES[name]
    found = json.loads(json.dumps(_plain(extract(image, sensor, **options))))
    differences = _compare(found, expected[name], name)
    assert not differences, "\n".join(differences[:10])


if __name__ == "__main__":
    results = {name: _plain(extract(image, sensor, **options))
               for name, (image, sensor, options) in CASES.items()}  # fmt: skip
    EXPECTED.write_text(json.dumps(results, indent=1, sort_keys=True) + "\n")
    print(f"wrote {len(results)} pinned results to {EXPECTED}")
