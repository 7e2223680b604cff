"""A simulated robot finger carrying any sensor preset: the `Probe` of simulation."""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from dataclasses import replace
from typing import Any

import numpy as np

from taxel._validation import as_finite_array, as_rng, check_positive
from taxel.active._probe import NoContactError, ProbeReading
from taxel.active._scene import SceneObject
from taxel.frames import as_pose, transform_directions, transform_points
from taxel.mechanics import ContactResult, solve_contact
from taxel.sensor import TactileSensor, as_sensor

__all__ = ["SimulatedFinger", "finger_force_limit"]

# The contact and support models are linear elastic, for small strains: a press that would
# compress an object by more than half its height is refused, not extrapolated (the seed's
# racquet ball, the softest object it pressed, lost 18 % of its height at 39 N).
_LARGEST_COMPRESSION = 0.5
# A slide reads one frame per sensor frame period: a speed slip (mm/s given as m/s) would
# ask for millions of presses; more than this many frames is refused before moving.
_MOST_SLIDE_FRAMES = 100_000
_UNMOVED = ("; the finger did not move", "; the finger stays where it was")


def finger_force_limit(sensor: TactileSensor | str) -> float:
    """The largest force a simulated finger carrying `sensor` presses with, by default [N].

    The sensor's full-scale pressure over a quarter of its active area: a contact that
    covers a quarter of the array at full scale. Rounded to 12 significant digits, so that
    the limit reads as it is written (51.2 N for resistive16, not 51.199999999999996).

    Examples
    --------
    >>> finger_force_limit("resistive16")
    51.2
    """
    chosen = as_sensor(sensor)
    return float(f"{chosen.full_scale * chosen.geometry.active_area / 4:.12g}")


class SimulatedFinger:
    """A finger with a tactile sensor in a scene of objects (implements `Probe`).

    Parameters
    ----------
    sensor : TactileSensor or str
        The sensor on the fingertip, or a preset name (`taxel.sensor.PRESET_NAMES`).
    scene : sequence of SceneObject
        The objects within reach (at least one).
    pose : array_like, shape (4, 4)
        Initial approach pose T_BS of the sensor (not touching anything).
    max_force : float, optional
        The largest force the finger may press with [N]; default: `finger_force_limit`,
        the sensor's full-scale pressure over a quarter of its active area.
    reach : float, default 0.05
        How far along its normal the finger may travel looking for contact [m].
    rng : numpy.random.Generator or int, optional
        Noise of the sensor frames; None gives noise-free frames.

    Examples
    --------
    >>> from taxel.active import make_ball
    >>> from taxel.frames import make_pose
    >>> from taxel.sensor import make_sensor
    >>> ball = make_ball("ball", 6.25e-3)
    >>> down = make_pose(np.diag([1.0, -1.0, -1.0]), [0.0, 0.0, 0.02])
    >>> finger = SimulatedFinger(make_sensor("resistive16"), [ball], down)
    >>> reading = finger.press(normal_force=5.0)
    >>> round(reading.normal_force, 6)
    5.0
    >>> # 7.5 mm down to the ball's top, then a fraction of a mm into the 1.5 mm pad
    >>> 7.5 < reading.travel * 1e3 < 8.0
    True
    """

    def __init__(
        self,
        sensor: TactileSensor,
        scene: Sequence[SceneObject],
        pose: Any,
        *,
        max_force: float | None = None,
        reach: float = 0.05,
        rng: Any = None,
    ) -> None:
        self._sensor = sensor = as_sensor(sensor)
        if isinstance(scene, SceneObject | str) or not isinstance(scene, Iterable):
            raise TypeError(f"`scene` must be a sequence of SceneObject items, got {scene!r}")
        self._scene = tuple(scene)
        if not self._scene:
            raise ValueError("`scene` must hold at least one object, got an empty sequence")
        for item in self._scene:
            if not isinstance(item, SceneObject):
                raise TypeError(f"`scene` must hold SceneObject items, got {item!r}")
        if max_force is None:
            max_force = finger_force_limit(sensor)
        self.max_force = check_positive("max_force", max_force)
        self.reach = check_positive("reach", reach)
        self._rng = as_rng("rng", rng)
        self._pose = np.eye(4)
        self._last: ContactResult | None = None
        self._time = 0.0
        self.move_to(pose)

    # ------------------------------------------------------------------ the Probe API
    @property
    def sensor(self) -> TactileSensor:
        """The sensor on the fingertip."""
        return self._sensor

    @property
    def pose(self) -> np.ndarray:
        """The current approach pose T_BS."""
        return self._pose.copy()

    def move_to(self, pose: Any) -> None:
        """Move to an approach pose; a pose inside an object raises and leaves the finger."""
        pose = as_pose(pose, name="pose")
        distances = self._distances(pose)
        if np.isfinite(distances).any() and np.nanmin(distances) < 0:
            raise ValueError(
                f"`pose` puts the sensor {-np.nanmin(distances) * 1e3:.2f} mm inside an "
                "object; the finger stays where it was"
            )
        self._pose = pose
        self._last = None

    def press(
        self, *, normal_force: float | None = None, depth: float | None = None
    ) -> ProbeReading:
        """Press along the sensor normal (see `Probe.press`)."""
        if (normal_force is None) == (depth is None):
            raise ValueError("give exactly one of `normal_force` and `depth`")
        if normal_force is not None:
            normal_force = check_positive("normal_force", normal_force)
            if normal_force > self.max_force:
                raise ValueError(
                    f"`normal_force` must be <= the finger's limit {self.max_force:g} N, "
                    f"got {normal_force:g}; the finger did not move"
                )
        else:
            depth = check_positive("depth", depth)
        per_object = self._object_distances(self._pose)
        distances = np.min(per_object, axis=0)
        if not np.isfinite(distances).any() or np.nanmin(distances) > self.reach:
            spacing = max(self._sensor.load_grid.spacing)
            raise NoContactError(
                f"no object within the finger's reach ({self.reach * 1e3:g} mm) along the "
                f"sensor normal at any point of its load grid ({spacing * 1e3:.3g} mm apart; "
                "a thinner object can fall between them); the finger did not move"
            )
        first_touch = float(np.nanmin(distances))
        nearest = self._scene[int(np.argmin([np.min(each) for each in per_object]))]
        heights = np.where(np.isfinite(distances), distances - first_touch, np.inf)
        initial = self._last if self._last is not None and normal_force is not None else None
        if initial is not None and not np.isfinite(heights[initial.contact]).all():
            # the last frame pressed where there is now a hole: start from material only
            # (a warm start on an infinite height makes the solver's gap NaN)
            solid = np.isfinite(heights)
            initial = replace(
                initial,
                pressure=np.where(solid, initial.pressure, 0.0),
                contact=initial.contact & solid,
            )
        if depth is not None and nearest.gives_way:
            # the object also gives way by its force (a hollow ball's shell, an elastic
            # ball on the table): find the force whose press travels `depth` past the touch
            normal_force, depth = self._force_for_depth(heights, nearest, depth), None
        flat = 0.0 if normal_force is None else nearest.flattening(normal_force)
        contact = self._solve(heights, nearest, flat, normal_force, depth, initial)
        # a force-controlled press was checked above (its result may differ by rounding)
        if depth is not None and contact.normal_force > self.max_force:
            raise ValueError(
                f"`depth` {depth:g} m needs {contact.normal_force:.3g} N, beyond the finger's "
                f"limit {self.max_force:g} N; the finger did not move"
            )
        support = nearest.support_travel(contact.normal_force)
        share = self._object_share(nearest.contact_material)
        compression = support + flat + contact.indentation * share
        height = getattr(nearest, "top", None)
        if height is not None and compression > _LARGEST_COMPRESSION * height:
            raise ValueError(
                f"pressing {nearest.name!r} with {contact.normal_force:.3g} N would compress it "
                f"by {compression * 1e3:.3g} mm, more than half its height "
                f"({height * 1e3:.3g} mm), beyond what its elastic model describes; the "
                "finger did not move"
            )
        self._last = contact
        travel = first_touch + contact.indentation + flat + support
        return self._reading(contact, travel)

    def _solve(
        self,
        heights: np.ndarray,
        item: SceneObject,
        flat: float,
        normal_force: float | None,
        depth: float | None,
        initial: ContactResult | None,
    ) -> ContactResult:
        """The contact with `item`, its surface first flattened by `flat` [m] (a shell's)."""
        if flat > 0.0:  # the flattened disc, where the surface came within `flat` of it
            heights = np.maximum(heights - flat, 0.0)
        return solve_contact(
            heights,
            self._sensor.load_grid.spacing,
            self._sensor.cover.material,
            normal_force=normal_force,
            indentation=depth,
            indenter_material=item.contact_material,
            thickness=self._sensor.cover.thickness,
            initial=initial,
        )

    def _force_for_depth(self, heights: np.ndarray, item: SceneObject, depth: float) -> float:
        """The force [N] whose press travels `depth` [m] past the first touch.

        The travel is the contact's approach (the cover's and the object's surface), the
        object's own flattening (a shell's) and its give at the table; it grows with the
        force.
        """
        from scipy.optimize import brentq

        def excess(force: float) -> float:
            flat = item.flattening(force)
            contact = self._solve(heights, item, flat, force, None, None)
            return contact.indentation + flat + item.support_travel(force) - depth

        least = 1e-6 * self.max_force
        if excess(least) >= 0.0:
            raise ValueError(
                f"`depth` {depth:g} m is less than the travel of the lightest press the finger "
                f"makes ({least:g} N); the finger did not move"
            )
        # the most the finger gives, or the object's model describes (a hollow ball's)
        most = min(self.max_force, item.largest_force)
        if excess(most) < 0.0:
            if most < self.max_force:
                raise ValueError(
                    f"`depth` {depth:g} m flattens {item.name!r} past what its model describes "
                    f"(the most is {most:.3g} N, {excess(most) + depth:.3g} m of travel); the "
                    "finger did not move"
                )
            raise ValueError(
                f"`depth` {depth:g} m needs more than the finger's limit {self.max_force:g} N; "
                "the finger did not move"
            )
        return float(brentq(excess, least, most, rtol=1e-6))

    def _object_share(self, material: Any) -> float:
        """The object's share of the approach: its compliance over both bodies' (Hertz)."""
        if material is None:  # rigid
            return 0.0
        own = 1.0 / material.plane_strain_modulus
        return own / (own + 1.0 / self._sensor.cover.material.plane_strain_modulus)

    def slide(self, path: Any, *, speed: float, normal_force: float) -> list[ProbeReading]:
        """Slide pressed through base-frame points (see `Probe.slide`).

        A step refused on the way (the path leaves the object or runs into it) puts the
        finger back where, and as, the slide found it, and raises saying how far it got.
        """
        points = as_finite_array("path", path, ndim=2)
        if points.shape[1] != 3 or len(points) < 2:
            raise ValueError(f"`path` must be (K >= 2, 3) base-frame points, got {points.shape}")
        speed = check_positive("speed", speed)
        lengths = np.linalg.norm(np.diff(points, axis=0), axis=1)
        arc = np.concatenate([[0.0], np.cumsum(lengths)])
        step = speed / self._sensor.frame_rate
        n_frames = math.floor(arc[-1] / step + 1e-9) + 1
        if n_frames > _MOST_SLIDE_FRAMES:
            raise ValueError(
                f"`speed` {speed:g} m/s over the {arc[-1] * 1e3:.3g} mm `path` reads "
                f"{n_frames:.3g} frames at {self._sensor.frame_rate:g} Hz, more than "
                f"{_MOST_SLIDE_FRAMES}; the finger did not move"
            )
        samples = np.arange(0.0, arc[-1] + 1e-12, step)
        start_pose, start_last, start_time = self._pose.copy(), self._last, self._time
        readings = []
        for distance in samples:
            origin = np.array([np.interp(distance, arc, points[:, i]) for i in range(3)])
            pose = start_pose.copy()
            pose[:3, 3] = origin
            last = self._last
            try:
                self.move_to(pose)
                self._last = last  # keep warm-starting along the path
                readings.append(self.press(normal_force=normal_force))
            except ValueError as error:
                # a refused step leaves the finger where (and as) the slide found it
                self._pose, self._last, self._time = start_pose, start_last, start_time
                if not readings:  # refused at the start: it did not move at all
                    raise
                message = str(error)
                for unmoved in _UNMOVED:
                    message = message.removesuffix(unmoved)
                raise type(error)(
                    f"the slide was refused {distance * 1e3:.3g} mm along `path`: {message}; "
                    "the finger went back to where the slide started"
                ) from None
            self._time += 1.0 / self._sensor.frame_rate
        return readings

    def retract(self) -> None:
        """Lift back to the approach pose."""
        self._last = None

    # --------------------------------------------------------------------- internals
    def _cell_origins(self, pose: np.ndarray) -> np.ndarray:
        x, y = self._sensor.load_grid.coordinates()
        local = np.stack([x, y, np.zeros_like(x)], axis=-1)
        return transform_points(pose, local.reshape(-1, 3)).reshape(*x.shape, 3)

    def _object_distances(self, pose: np.ndarray) -> list[np.ndarray]:
        """Each object's distance along the sensor normal from every load-grid cell [m]."""
        origins = self._cell_origins(pose)
        normal = transform_directions(pose, [0.0, 0.0, 1.0])
        return [item.ray_distances(origins, normal) for item in self._scene]

    def _distances(self, pose: np.ndarray) -> np.ndarray:
        return np.min(self._object_distances(pose), axis=0)

    def _reading(self, contact: ContactResult, travel: float) -> ProbeReading:
        frame = self._sensor.frame_from_pressure(
            contact.pressure, displacement=contact.displacement, rng=self._rng, contact=contact
        )
        pressed = self._pose.copy()
        normal = transform_directions(self._pose, [0.0, 0.0, 1.0])
        pressed[:3, 3] += travel * normal
        # the object pushes the sensor back along -z_S; torque about the sensor origin
        x, y = self._sensor.load_grid.coordinates()
        cell = np.prod(self._sensor.load_grid.spacing)
        forces = contact.pressure * cell
        moment_x = float((y * forces).sum())
        moment_y = float(-(x * forces).sum())
        force_sensor = np.array([0.0, 0.0, -contact.normal_force])
        torque_sensor = -np.array([moment_x, moment_y, 0.0])
        wrench = np.concatenate(
            [
                transform_directions(pressed, force_sensor),
                transform_directions(pressed, torque_sensor),
            ]
        )
        return ProbeReading(frame, wrench, contact.normal_force, travel, pressed, self._time)
