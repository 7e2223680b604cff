"""``taxel features`` given what a hurried user gives: its inputs kept, its errors one line."""

import numpy as np
import pytest

from taxel.cli import main


def _one_line(capsys) -> str:
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "Traceback" not in err
    return err


@pytest.fixture
def washer():
    y, x = np.mgrid[:64, :64] - 31.5
    r = np.hypot(x, y)
    return np.where((r < 24) & (r > 10), 200, 24).astype(np.uint8)


def test_the_figure_never_replaces_the_reference(tmp_path, capsys, washer):
    import cv2

    frame, reference = tmp_path / "frame.png", tmp_path / "rest.png"
    cv2.imwrite(str(frame), washer)
    cv2.imwrite(str(reference), np.full_like(washer, 24))
    before = reference.read_bytes()
    args = ["features", str(frame), "--pitch", "1e-3", "--reference", str(reference)]
    assert main([*args, "--figure", str(reference), "--overwrite"]) == 2
    assert _one_line(capsys) == (
        f"taxel features: error: --figure {str(reference)!r} is an input file; choose another\n"
    )
    assert reference.read_bytes() == before
