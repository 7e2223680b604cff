"""``taxel active slip``: slip in a recorded sequence from the command line."""

import json
import shutil

import numpy as np
import pytest

from taxel.active import detect_slip, random_slip_scenario, simulate_slip
from taxel.cli import main

RATE = "1000"


@pytest.fixture(scope="module")
def sequence(tmp_path_factory):
    """A simulated hold, load and slip, saved as an archive of static and PVDF frames."""
    simulated = simulate_slip(random_slip_scenario("slip", rng=4))
    path = tmp_path_factory.mktemp("slip") / "sequence.npz"
    np.savez(path, static=simulated.static_frames, piezo=simulated.piezo_frames)
    return path, simulated


def _strict_json(text):
    def refuse(token):
        raise ValueError(f"not strict JSON: {token}")

    return json.loads(text, parse_constant=refuse)


def test_the_table_lists_the_events_the_library_finds(sequence, capsys):
    path, simulated = sequence
    found = detect_slip(simulated.static_frames, simulated.piezo_frames, frame_rate=1000.0)
    assert [event.kind for event in found.events] == ["incipient", "gross"]
    assert main(["active", "slip", str(path), "--frame-rate", RATE, "--piezo-key", "piezo"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert "PVDF frames: 'piezo', 8 x 8" in lines[0]
    assert lines[1].startswith("initial state: holding")
    assert lines[2].split() == ["kind", "frame", "time", "[ms]", "channel"]
    rows = [line.split() for line in lines[3:]]
    expected = [
        [event.kind, str(event.frame), f"{event.time * 1e3:.1f}", event.channel]
        for event in found.events
    ]
    assert rows == expected


def test_json_is_strict_and_holds_the_librarys_events(sequence, capsys):
    path, simulated = sequence
    found = detect_slip(simulated.static_frames, frame_rate=1000.0)  # no --piezo-key
    assert main(["active", "slip", str(path), "--frame-rate", RATE, "--json"]) == 0
    result = _strict_json(capsys.readouterr().out)
    assert result["events"] == [event.to_dict() for event in found.events]
    assert result["initial_state"] == found.initial_state
    assert (result["static_key"], result["piezo_key"]) == ("static", None)
    assert result["position_noise_m"] == pytest.approx(found.position_noise)


def test_the_only_array_is_the_static_frames(tmp_path, sequence, capsys):
    _, simulated = sequence
    path = tmp_path / "only.npz"
    np.savez(path, frames=simulated.static_frames[:120])
    assert main(["active", "slip", str(path), "--frame-rate", RATE, "--json"]) == 0
    assert _strict_json(capsys.readouterr().out)["static_key"] == "frames"


def test_a_figure_is_drawn_and_not_replaced_unless_asked(tmp_path, sequence, capsys):
    path, _ = sequence
    figure = tmp_path / "slip.png"
    command = ["active", "slip", str(path), "--frame-rate", RATE, "--figure", str(figure)]
    assert main([*command, "--piezo-key", "piezo"]) == 0
    assert figure.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    capsys.readouterr()
    assert main(command) == 2
    error = capsys.readouterr().err
    assert error == (
        f"taxel active slip: error: --figure {str(figure)!r} exists; pass --overwrite to "
        "replace it\n"
    )
    assert main([*command, "--overwrite"]) == 0


def _refused(arguments, capsys):
    try:
        code = main(["active", "slip", *arguments])
    except SystemExit as stop:
        code = stop.code
    assert code == 2
    error = capsys.readouterr().err
    assert error.count("\n") == 1 and error.startswith("taxel active slip: error: ")
    return error


@pytest.mark.parametrize(
    ("arrays", "flags", "message"),
    [
        ({"static": (60, 6, 6)}, ["--static-key", "nope"], "--static-key 'nope': "),
        ({"static": (60, 6, 6)}, ["--piezo-key", "piezo"], "--piezo-key 'piezo': "),
        ({"a": (60, 6, 6), "b": (60, 6, 6)}, [], "holds a, b and none named 'static'"),
        ({"static": (60, 36)}, [], "--static-key 'static': "),
        ({"static": (60, 6, 6), "piezo": (59, 4, 4)}, ["--piezo-key", "piezo"], "59 PVDF"),
        ({"static": (60, 6, 6), "piezo": (60, 16)}, ["--piezo-key", "piezo"], "shape (60, 16)"),
        ({"static": (40, 6, 6)}, [], "holds 40 frames; slip detection needs more than its"),
        ({"static": (60, 6, 1)}, [], "frames are 6 x 1"),
        ({"static": (60, 6, 6)}, ["--piezo-key", "static"], "names the static frames too"),
        ({"static": (60, 6, 6)}, ["--piezo-time-constant", "0.1"], "give their frames with"),
    ],
)
def test_bad_archives_are_refused_in_one_line(tmp_path, capsys, arrays, flags, message):
    path = tmp_path / "bad.npz"
    rng = np.random.default_rng(0)
    np.savez(path, **{key: rng.normal(size=shape) for key, shape in arrays.items()})
    error = _refused([str(path), "--frame-rate", RATE, *flags], capsys)
    assert message in error


def test_nan_frames_are_refused(tmp_path, capsys):
    frames = np.ones((60, 6, 6))
    frames[3, 2, 2] = np.nan
    np.savez(tmp_path / "nan.npz", static=frames)
    error = _refused([str(tmp_path / "nan.npz"), "--frame-rate", RATE], capsys)
    assert "--static-key 'static': " in error and "holds 1 NaN or infinite value(s)" in error


def test_the_figure_is_never_the_input(tmp_path, sequence, capsys):
    source, _ = sequence
    disguised = tmp_path / "sequence.png"  # an archive under a figure's name
    shutil.copy(source, disguised)
    renamed = tmp_path / "renamed.npz"
    shutil.copy(source, renamed)
    error = _refused(
        [str(renamed), "--frame-rate", RATE, "--figure", str(renamed), "--overwrite"], capsys
    )
    assert "--figure must name a .png file" in error
    error = _refused([str(disguised), "--frame-rate", RATE, "--figure", str(disguised)], capsys)
    assert f"--figure {str(disguised)!r} is an input file; choose another" in error
    error = _refused([str(disguised), "--frame-rate", RATE], capsys)
    assert f"SEQUENCE {str(disguised)!r} must be an .npz archive of frames" in error


@pytest.mark.parametrize(
    ("arguments", "message"),
    [
        (["missing.npz", "--frame-rate", RATE], "SEQUENCE missing.npz: no such file"),
        (["x.npz"], "the following arguments are required: --frame-rate"),
        (["x.npz", "--frame-rate", "0"], "--frame-rate: must be > 0, got 0"),
        (["x.npz", "--frame-rate", RATE, "--pitch", "-1"], "--pitch: must be > 0, got -1"),
    ],
)
def test_bad_arguments_are_one_line(capsys, arguments, message):
    assert message in _refused(arguments, capsys)


def test_a_text_file_is_not_an_archive(tmp_path, capsys):
    path = tmp_path / "frames.npz"
    path.write_text("1, 2, 3\n")
    error = _refused([str(path), "--frame-rate", RATE], capsys)
    assert "not a readable .npz file" in error
