"""Poses as 4x4 homogeneous transforms, and the robot's base -> flange -> sensor chain.

Frames (see ``docs/architecture.md``)
-------------------------------------
- Sensor frame ``S``: origin at the centre of the active area on the cover's outer surface;
  ``x`` along increasing image column, ``y`` along increasing image row, ``z`` the outward
  normal (from the sensor towards the object). Right-handed.
- Flange frame ``F``: the robot's tool mounting plate; base frame ``B``: the robot's base.
- A pose ``T_AB`` (4x4) maps points of frame ``B`` to frame ``A``:
  ``p_A = T_AB @ [p_B, 1]``; ``T_BS = T_BF @ T_FS``.

Functions
---------
make_pose, as_pose, invert_pose, compose_poses, sensor_pose, transform_points,
transform_directions

Examples
--------
>>> import numpy as np
>>> from taxel.frames import make_pose, transform_points
>>> T_BS = make_pose(np.diag([1.0, -1.0, -1.0]), [0.5, 0.0, 0.2])  # sensor facing down
>>> transform_points(T_BS, [0.0, 0.01, 0.0]).tolist()  # 1 cm along the sensor's y
[0.5, -0.01, 0.2]
"""

from taxel.frames._transforms import (
    as_pose,
    compose_poses,
    invert_pose,
    make_pose,
    sensor_pose,
    transform_directions,
    transform_points,
)

__all__ = [
    "as_pose",
    "compose_poses",
    "invert_pose",
    "make_pose",
    "sensor_pose",
    "transform_directions",
    "transform_points",
]
