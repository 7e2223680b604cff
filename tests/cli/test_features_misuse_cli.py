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


def test_the_figure_never_replaces_the_pose(tmp_path, capsys, washer):
    # a pose file named *.png was replaced by the figure under --overwrite
    frame, pose = tmp_path / "frame.npy", tmp_path / "pose.png"
    np.save(frame, washer)
    pose.write_text('{"matrix": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]}')
    before = pose.read_bytes()
    args = ["features", str(frame), "--pitch", "1e-3", "--pose", str(pose)]
    assert main([*args, "--figure", str(pose), "--overwrite"]) == 2
    assert _one_line(capsys) == (
        f"taxel features: error: --figure {str(pose)!r} is an input file; choose another\n"
    )
    assert pose.read_bytes() == before


@pytest.mark.parametrize(
    ("content", "message"),
    [
        ("folder", "--reference REF: a folder, not a file"),
        ("archive", "--reference: REF: holds 2 arrays (a, b); give a --reference of one frame"),
        ("huge", "--reference REF: values up to 1e+20, beyond the 1e+15 the features handle"),
    ],
)
def test_reference_errors_name_the_flag_and_file(tmp_path, capsys, washer, content, message):
    np.save(tmp_path / "frame.npy", washer)
    reference = tmp_path / ("rest" if content == "folder" else f"rest.np{content[0]}")
    if content == "folder":
        reference.mkdir()
    elif content == "archive":
        reference = tmp_path / "rest.npz"
        np.savez(reference, a=washer, b=washer)
    else:
        reference = tmp_path / "rest.npy"
        np.save(reference, np.full(washer.shape, 1e20))
    args = ["features", str(tmp_path / "frame.npy"), "--pitch", "1e-3"]
    assert main([*args, "--reference", str(reference)]) == 2
    err = _one_line(capsys)
    assert err.startswith("taxel features: error: ")
    assert message.replace("REF", str(reference)) in err
    assert "`" not in err  # no library parameter named


@pytest.mark.parametrize("shape", [(1, 1), (2, 5)])
def test_an_image_too_small_is_named(tmp_path, capsys, shape):
    path = tmp_path / "small.npy"
    np.save(path, np.ones(shape))
    assert main(["features", str(path), "--pitch", "1e-3"]) == 2
    err = _one_line(capsys)
    assert f"error: {path}: the image must be at least 3x3 taxels, got shape {shape}" in err


def test_a_link_to_a_missing_file_is_not_replaced_without_overwrite(tmp_path, capsys, washer):
    # the link is something the user made: replacing it needs --overwrite, as a file does
    frame, link = tmp_path / "frame.npy", tmp_path / "figure.png"
    np.save(frame, washer)
    link.symlink_to(tmp_path / "elsewhere.png")
    assert main(["features", str(frame), "--pitch", "1e-3", "--figure", str(link)]) == 2
    assert _one_line(capsys) == (
        f"taxel features: error: --figure {str(link)!r} exists; pass --overwrite to replace it\n"
    )
    assert link.is_symlink() and not (tmp_path / "elsewhere.png").exists()


def test_an_empty_figure_name_is_refused(tmp_path, capsys, washer):
    frame = tmp_path / "frame.npy"
    np.save(frame, washer)
    assert main(["features", str(frame), "--pitch", "1e-3", "--figure", ""]) == 2
    assert _one_line(capsys) == "taxel features: error: --figure must name a .png file, got ''\n"
