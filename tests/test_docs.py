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
    assert len(blocks) == 2
    namespace: dict = {}
    for block in blocks:
        exec(compile(block, str(guide), "exec"), namespace)
    assert namespace["error"] < 0.1  # degrees, as the simulated finger gives
    assert capsys.readouterr().out.startswith("normal within 0.0")
    # a press where nothing lies within reach is the driver's NoContactError
    probe = namespace["probe"]
    probe.move_to(make_pose(namespace["down"], [1.0, 1.0, 0.08]))
    with pytest.raises(NoContactError, match="nothing within reach"):
        probe.press(normal_force=5.0)
