"""``taxel reconstruct`` given frames it cannot take: one line naming FRAME, no --out left."""

import json

import numpy as np
import pytest

from taxel.cli import main


def _one_line(capsys) -> str:
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "Traceback" not in err
    return err


@pytest.mark.parametrize("method", ["nonneg", "tv", "support"])
def test_a_batch_for_a_one_frame_method_is_named(frame_file, tmp_path, capsys, method):
    batch, out = tmp_path / "batch.npy", tmp_path / "p.npy"
    np.save(batch, np.stack([np.load(frame_file)] * 3))
    args = ["reconstruct", str(batch), "--sensor", "resistive16", "--out", str(out)]
    assert main([*args, "--method", method]) == 2
    assert _one_line(capsys) == (
        f"taxel reconstruct: error: `FRAME` {str(batch)!r} holds 3 frames, but --method "
        f"{method} reconstructs one frame at a time (tikhonov and tsvd take a batch)\n"
    )
    assert not out.exists()


def test_the_help_says_which_methods_take_a_batch(capsys):
    with pytest.raises(SystemExit):
        main(["reconstruct", "--help"])
    help_text = " ".join(capsys.readouterr().out.split())
    assert "a batch of frames (tikhonov and tsvd)" in help_text


@pytest.mark.parametrize(
    ("content", "message"),
    [
        (np.where(np.eye(16) > 0, np.nan, 1e3), "must be finite at live taxels, got 16 NaN"),
        (np.zeros((0, 16, 16)), "must hold at least one frame, got shape (0, 16, 16)"),
    ],
)
def test_frames_the_solver_refuses_name_the_file(tmp_path, capsys, content, message):
    frame, out = tmp_path / "frame.npy", tmp_path / "p.npy"
    np.save(frame, content)
    assert main(["reconstruct", str(frame), "--sensor", "resistive16", "--out", str(out)]) == 2
    err = _one_line(capsys)
    assert f"error: `FRAME` {str(frame)!r} {message}" in err
    assert "`frame`" not in err and not out.exists()


@pytest.mark.parametrize(
    ("extra", "shown"),
    [
        (["--lambda", "gcv"], "--lambda gcv"),
        (["--lambda", "lcurve", "--method", "nonneg"], "--lambda lcurve"),
        (["--lambda", "0.1"], "--lambda 0.1"),
    ],
)
def test_a_noise_level_no_rule_uses_is_refused(frame_file, tmp_path, capsys, extra, shown):
    # only the discrepancy rule (and --method support's threshold) reads --noise-level: it
    # was ignored without a word
    out = tmp_path / "p.npy"
    args = ["reconstruct", str(frame_file), "--sensor", "resistive16", "--out", str(out)]
    assert main([*args, *extra, "--noise-level", "1000"]) == 2
    assert _one_line(capsys) == (
        f"taxel reconstruct: error: --noise-level is used by --lambda discrepancy (and by "
        f"--method support), not by {shown}: leave it out, or choose the discrepancy rule\n"
    )
    assert not out.exists()
    assert main([*args, *extra, "--method", "support", "--noise-level", "1000"]) == 0


def test_a_solve_that_did_not_converge_says_so_in_the_text(tmp_path, capsys):
    # a frame of negative readings: nonneg gets nowhere in its 1000 iterations
    frame, out = tmp_path / "frame.npy", tmp_path / "p.npy"
    np.save(frame, np.full((16, 16), -1e3))
    args = ["reconstruct", str(frame), "--sensor", "resistive16", "--method", "nonneg"]
    assert main([*args, "--out", str(out), "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["converged"] is False
    assert main([*args, "--out", str(out), "--overwrite"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[0].startswith("nonneg (order 0), lambda = ")
    assert "NOT converged (not converged after 1000 iterations)" in lines[0]
