"""``taxel calibrate``: where the calibration goes is checked before the presses."""

from taxel.cli import main


def _must_not_run(*args, **kwargs):
    raise AssertionError("the calibration ran before its --out was checked")


def test_an_upper_case_suffix_is_refused_before_the_work(tmp_path, capsys, monkeypatch):
    # Calibration.save takes only '.npz'; it used to be refused after the whole calibration
    monkeypatch.setattr("taxel.sensor.calibrate", _must_not_run)
    out = tmp_path / "C.NPZ"
    assert main(["calibrate", "--sensor", "capacitive4x4", "--out", str(out)]) == 2
    assert capsys.readouterr().err == (
        "taxel calibrate: error: --out must name a .npz file (in lower case), "
        f"got {str(out)!r}\n"
    )
    assert list(tmp_path.iterdir()) == []


def test_a_failed_save_names_out(tmp_path, capsys, monkeypatch):
    from taxel.sensor import Calibration

    def disk_full(self, path, **kwargs):
        raise OSError(28, "No space left on device", str(path))

    monkeypatch.setattr(Calibration, "save", disk_full)
    out = tmp_path / "cal.npz"
    assert main(["calibrate", "--sensor", "capacitive4x4", "--out", str(out)]) == 2
    assert capsys.readouterr().err == (
        f"taxel calibrate: error: --out {out} cannot be written (No space left on device)\n"
    )


def test_calibrate_writes_a_loadable_file(tmp_path, capsys):
    from taxel.sensor import Calibration

    out = tmp_path / "cal.npz"
    assert main(["calibrate", "--sensor", "capacitive4x4", "--out", str(out)]) == 0
    assert f"written to {out}" in capsys.readouterr().out
    assert Calibration.load(out).sensor_name == "capacitive4x4"
