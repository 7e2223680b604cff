"""The guides in docs/ run as written."""

import re
from pathlib import Path

import pytest

from taxel.active import NoContactError
from taxel.frames import make_pose

DOCS = Path(__file__).resolve().parents[1] / "docs"


def test_the_robot_driver_guide_runs_and_its_driver_fits_a_plane(capsys):
    guide = DOCS / "robot-driver.md"
    blocks = re.findall(r"```python\n(.*?)```", guide.read_text(), flags=re.S)
    assert len(blocks) == 3
    namespace: dict = {}
    for block in blocks[:2]:
        exec(compile(block, str(guide), "exec"), namespace)
    assert namespace["error"] < 0.1  # degrees, as the simulated finger gives
    assert capsys.readouterr().out.startswith("normal within 0.0")
    # a press where nothing lies within reach is the driver's NoContactError
    probe = namespace["probe"]
    probe.move_to(make_pose(namespace["down"], [1.0, 1.0, 0.08]))
    with pytest.raises(NoContactError, match="nothing within reach"):
        probe.press(normal_force=5.0)


def test_the_guide_s_slip_loop_stops_at_the_slip(capsys):
    guide = DOCS / "robot-driver.md"
    block = re.findall(r"```python\n(.*?)```", guide.read_text(), flags=re.S)[2]
    namespace: dict = {}
    exec(compile(block, str(guide), "exec"), namespace)
    stream, monitor = namespace["stream"], namespace["monitor"]
    found = re.search(r"gross slip at frame (\d+) \(", capsys.readouterr().out)
    assert found is not None and monitor.state == "gross"
    # the loop stopped at the frame that decided gross slip, within 3 frames of its start
    assert monitor.n_frames == int(found.group(1)) + 1
    assert 0 <= int(found.group(1)) - stream.gross_frame <= 3
    # the events it printed are the batch detector's on the whole recording
    batch = namespace["detector"].run(
        stream.static_frames, stream.piezo_frames, frame_rate=stream.frame_rate
    )
    assert monitor.events == batch.events
