"""A run that runs out of memory (a fine grid on a small machine) is one line, not a traceback."""

import numpy as np

from taxel.cli import main


def _no_memory(*args, **kwargs):
    raise MemoryError("Unable to allocate 128. MiB for an array with shape (4095, 4095)")


def test_out_of_memory_is_one_line(tmp_path, capsys, monkeypatch):
    frame = tmp_path / "frame.npy"
    np.save(frame, np.full((16, 16), 1e3))
    monkeypatch.setattr("taxel.reconstruction.reconstruct", _no_memory)
    out = tmp_path / "p.npy"
    assert main(["reconstruct", str(frame), "--sensor", "resistive16", "--out", str(out)]) == 2
    assert capsys.readouterr().err == (
        "taxel reconstruct: error: not enough memory (Unable to allocate 128. MiB for an array "
        "with shape (4095, 4095)); a smaller --oversampling or input needs less\n"
    )
    assert not out.exists()
