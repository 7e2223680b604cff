"""FabricSlide reader: names, units and columns, bad files, and three real recordings."""

from pathlib import Path

import numpy as np
import pytest

from taxel.io import (
    CPM_FINGER,
    list_fabricslide_files,
    parse_fabricslide_name,
    read_fabricslide,
)

HEADER = "timestamp, proximity1, proximity2, " + ", ".join(f"channel{i}" for i in range(1, 17))
DATA = Path(__file__).resolve().parents[2].parent / "shared" / "data" / "fabricslide" / "fabric"


def _write(path, rows, header=HEADER, newline=True):
    text = "\n".join([header, *rows]) + ("\n" if newline else "")
    path.write_text(text)
    return path


def _row(stamp, first=100):
    return f"{stamp}, 3, 65535, " + ", ".join(str(first + i) for i in range(16))


def test_name_fields():
    assert parse_fabricslide_name("WovenFabric_F250_V120mmps_2.csv") == {
        "fabric": "WovenFabric",
        "force_setting": 250,
        "sliding_velocity": pytest.approx(0.12),
        "repetition": 2,
    }
    assert parse_fabricslide_name("x/Canvas_F120_V-150mmps_0.csv")["sliding_velocity"] == -0.15


@pytest.mark.parametrize(
    "name", ["Canvas_F120_V10_0.csv", "Canvas_120_V10mmps_0.csv", "Canvas_F120_V10mmps.csv"]
)
def test_bad_names(name):
    with pytest.raises(ValueError, match="is not a FabricSlide file name"):
        parse_fabricslide_name(name)
    with pytest.raises(ValueError, match="must not be zero"):
        parse_fabricslide_name("Canvas_F120_V0mmps_0.csv")


def test_columns_units_and_order(tmp_path):
    # columns are matched by name: put channel16 first to prove it
    names = HEADER.split(", ")
    order = [names[-1], *names[:-1]]
    rows = []
    for k in range(4):
        values = dict(zip(names, _row(5000 + 28 * k, first=10 * k).split(", "), strict=True))
        rows.append(", ".join(values[name] for name in order))
    path = _write(tmp_path / "Linen_F180_V-50mmps_1.csv", rows, header=", ".join(order))
    recording = read_fabricslide(path)
    assert recording.fabric == "Linen"
    assert recording.force_setting == 180
    assert recording.sliding_velocity == pytest.approx(-0.05)
    assert recording.repetition == 1
    np.testing.assert_allclose(recording.time, [0.0, 0.028, 0.056, 0.084])
    assert recording.start_time == pytest.approx(5.0)
    assert recording.readings.shape == (4, 16)
    np.testing.assert_array_equal(recording.readings[2], 20 + np.arange(16))
    np.testing.assert_array_equal(recording.proximity, [[3, 65535]] * 4)
    assert recording.sampling_rate == pytest.approx(1 / 0.028)
    assert recording.sensor_description is CPM_FINGER
    assert CPM_FINGER["n_taxels"] == 16
    assert CPM_FINGER["taxel_positions"] is None


@pytest.mark.parametrize(
    ("rows", "header", "newline", "message"),
    [
        ([], HEADER, True, r"line 1: a header but no data rows"),
        ([_row(0)], HEADER, True, r"needs at least two rows, got 1"),
        (
            [_row(0), _row(28)[:-9]],
            HEADER,
            False,
            r"line 3: truncated row: 18 fields, expected 19",
        ),
        ([_row(0), _row(28) + ", 7", _row(56)], HEADER, True, r"line 3: ragged row: 20 fields"),
        ([_row(0), _row(28).replace("105", "1o5")], HEADER, True, r"line 3: not a number"),
        ([_row(28), _row(0)], HEADER, True, r"line 3: timestamp goes backwards"),
        ([_row(0), _row(0)], HEADER, True, r"the timestamps do not advance"),
        ([_row(0)[:-5], _row(28)[:-5]], HEADER[:-11], True, r"missing column\(s\) channel16"),
    ],
)
def test_bad_files_name_file_and_line(tmp_path, rows, header, newline, message):
    path = _write(tmp_path / "Denim_F120_V-10mmps_0.csv", rows, header, newline)
    with pytest.raises(ValueError, match=r"Denim_F120_V-10mmps_0\.csv.*" + message):
        read_fabricslide(path)


def test_empty_and_missing_files(tmp_path):
    path = tmp_path / "Denim_F120_V-10mmps_0.csv"
    path.write_text("")
    with pytest.raises(ValueError, match=r"Denim_F120_V-10mmps_0\.csv: the file is empty"):
        read_fabricslide(path)
    with pytest.raises(FileNotFoundError, match=r"no such file: .*Canvas_F120_V10mmps_0\.csv"):
        read_fabricslide(tmp_path / "Canvas_F120_V10mmps_0.csv")


def test_listing(tmp_path):
    _write(tmp_path / "Denim_F120_V-10mmps_0.csv", [_row(0), _row(28)])
    _write(tmp_path / "Canvas_F120_V10mmps_0.csv", [_row(0), _row(28)])
    (tmp_path / "notes.csv").write_text("x")
    assert [p.name for p in list_fabricslide_files(tmp_path)] == [
        "Canvas_F120_V10mmps_0.csv",
        "Denim_F120_V-10mmps_0.csv",
    ]
    with pytest.raises(FileNotFoundError, match="no such directory"):
        list_fabricslide_files(tmp_path / "absent")
    (tmp_path / "empty").mkdir()
    with pytest.raises(ValueError, match="holds no FabricSlide recording"):
        list_fabricslide_files(tmp_path / "empty")


@pytest.mark.skipif(not DATA.is_dir(), reason=f"FabricSlide data not found at {DATA}")
@pytest.mark.parametrize(
    "name",
    ["Denim_F150_V-10mmps_0.csv", "Linen_F210_V50mmps_0.csv", "Canvas_F250_V-150mmps_0.csv"],
)
def test_real_recordings(name):
    recording = read_fabricslide(DATA / name)
    assert recording.readings.shape == (recording.n_steps, 16)
    # the timestamp unit: 35 Hz sampling, and duration x speed equals the commanded
    # travel timing (0.5 + 0.03 pi) m of the authors' velocity profile, at any speed
    assert recording.sampling_rate == pytest.approx(35.3, abs=0.5)
    duration = recording.time[-1] - recording.time[0]
    assert duration * abs(recording.sliding_velocity) == pytest.approx(0.5 + 0.03 * np.pi, 0.01)
    # the force setting is a target for the mean reading, not newtons
    assert recording.readings.mean() == pytest.approx(recording.force_setting, rel=0.15)
    assert np.all(recording.readings >= 0)
    assert np.all(recording.readings == np.round(recording.readings))


def test_a_missing_recording_is_missing_whatever_its_name(tmp_path):
    with pytest.raises(FileNotFoundError, match=r"^no such file: .*missing\.csv$"):
        read_fabricslide(tmp_path / "missing.csv")
