r"""Hold-then-slip sequences: a finger holds an object while the tangential load rises.

Physics (one trial, `SlipScenario`):

- The object touches the pad with a curved face (a sphere of radius R) under the normal
  force N. The normal contact is solved once (`solve_contact`, bonded-layer pad) on a fine
  grid; every frame re-samples that pressure field at the pattern's current offset.
- Tangential load T(t): held at T0, then ramped at a constant rate. Coulomb friction with
  static coefficient mu_s and kinetic mu_k < mu_s.
- Stick (T < mu_s N), Cattaneo-Mindlin: a central stick disc of radius
  c = a (1 - T / (mu_s N))^(1/3) and a slip annulus c < r < a. The traction on the pad is
  (Ciavarella-Jager superposition) q = mu_s [p_N - p_N'] with p_N' the pressure of the
  same contact at N' = N (1 - T / mu_s N), for a Hertz-like field the field shrunk by c/a
  in size and height. The object moves with the pad's surface by
  delta = K mu_s N [1 - (1 - T / mu_s N)^(2/3)], K = 3 (2 - nu) / (16 G a) (rigid object on
  the pad, half-space compliance; Johnson, Contact Mechanics, chapter 7).
- Gross slip once T reaches mu_s N: friction relaxes to mu_k with time constant tau and the
  object slides, v(t') = v_0 exp(-t' / tau) + v_s (1 - exp(-t' / tau)): its speed is
  continuous at the onset (the load exceeds the friction, so it cannot stop), starting from
  v_0, its mean speed over the last tau of the stick phase (the Cattaneo-Mindlin shift
  grows without bound in speed as c -> 0, a quasi-static divergence that the friction's own
  transition time smooths); the pattern translates by the sliding displacement s(t) plus
  the elastic shift K mu N.
- Micro-vibrations: stick-slip events of the sliding contact (Poisson, damped sinusoids of a
  few micrometres at 80-400 Hz, with the friction force fluctuating in step); smaller events
  while the slip annulus grows (their number proportional to the annulus' growth); a
  0.5 % jitter of the normal force (the arm's force control).
- Frames: the sensing elements feel sigma_z at their depth from the pressure (the sensor's
  own cover operator) and from the traction (Cerruti's point-force solution for a
  half-space, sigma_z = -3 Q x d^2 / (2 pi rho^5), integrated over each cell). A static
  array (resistive16 at 1 kHz) and a PVDF array (piezo8x8, whose charge amplifiers see only
  changes, eq. 25.17-25.18 of the chapter) read the same contact through
  `TactileSensor.read_sequence` (creep, hysteresis, piezo dynamics, readout noise).

Truth: gross slip starts at the first frame where the sliding displacement exceeds
`SLIP_DISPLACEMENT` (2 um); incipient slip at the first frame where the slip annulus has
grown by more than `ANNULUS_GROWTH` (1 %) of the contact radius since the sequence began.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from functools import lru_cache
from typing import Any

import numpy as np
from scipy import signal

from taxel._validation import (
    as_finite_array,
    as_rng,
    check_choice,
    check_finite,
    check_positive,
    check_range,
)
from taxel.active._slip_frames import sensed_stress
from taxel.mechanics import Sphere, effective_modulus, hertz_sphere, solve_contact
from taxel.sensor import TactileSensor, make_sensor

__all__ = [
    "ANNULUS_GROWTH",
    "SLIP_DISPLACEMENT",
    "SlipScenario",
    "SlipSequence",
    "random_slip_scenario",
    "simulate_slip",
    "slip_sensors",
]

SLIP_DISPLACEMENT = 2e-6  # [m] sliding that counts as gross slip
ANNULUS_GROWTH = 0.01  # fraction of the contact radius the annulus must grow by
SCENARIO_KINDS = ("slip", "hold", "steady")
_OVERSAMPLING = 4


@dataclass(frozen=True)
class SlipScenario:
    """The settings of one simulated trial (SI units; see the module notes).

    `kind` is 'slip' (hold, ramp past mu_s N, slide), 'hold' (the load stays below mu_s N:
    it ramps to `plateau` mu_s N and holds, or stays at T0 when `load_time` is 0) or
    'steady' (sliding at `sliding_speed` from the first frame: no onset).
    """

    kind: str = "slip"
    normal_force: float = 4.0
    radius: float = 0.02
    friction: float = 0.8
    kinetic_ratio: float = 0.85
    initial_load: float = 0.1
    hold_time: float = 0.1
    load_time: float = 0.15
    plateau: float = 0.8
    after_time: float = 0.1
    sliding_speed: float = 0.03
    relaxation_time: float = 4e-3
    direction: float = 0.0
    start: tuple[float, float] = (0.0, 0.0)
    vibration_rate: float = 200.0
    vibration_amplitude: float = 2e-6
    vibration_band: tuple[float, float] = (80.0, 400.0)
    friction_ripple: float = 0.03
    annulus_events: float = 10.0
    annulus_amplitude: float = 0.2
    force_jitter: float = 0.005
    seed: int = 0

    def __post_init__(self) -> None:
        check_choice("kind", self.kind, SCENARIO_KINDS)
        for name in (
            "normal_force",
            "radius",
            "friction",
            "hold_time",
            "after_time",
            "sliding_speed",
            "relaxation_time",
        ):
            check_positive(name, getattr(self, name))
        for name in (
            "load_time",
            "vibration_rate",
            "vibration_amplitude",
            "annulus_events",
            "force_jitter",
        ):
            check_positive(name, getattr(self, name), allow_zero=True)
        # fractions: mu_k <= mu_s, and the loads of a hold stay below mu_s N
        check_range("kinetic_ratio", self.kinetic_ratio, 0.0, 1.0, low_inclusive=False)
        check_range("initial_load", self.initial_load, 0.0, 1.0, high_inclusive=False)
        check_range("plateau", self.plateau, 0.0, 1.0, low_inclusive=False, high_inclusive=False)
        check_range("friction_ripple", self.friction_ripple, 0.0, 1.0, high_inclusive=False)
        check_range("annulus_amplitude", self.annulus_amplitude, 0.0, 1.0)
        check_finite("direction", self.direction)
        start = as_finite_array("start", self.start, ndim=1)
        if start.shape != (2,):
            raise ValueError(f"`start` must be an (x, y) pair [m], got {self.start!r}")
        band = as_finite_array("vibration_band", self.vibration_band, ndim=1)
        if band.shape != (2,) or not 0 < band[0] < band[1]:
            raise ValueError(
                f"`vibration_band` must be (low, high) with 0 < low < high [Hz], "
                f"got {self.vibration_band!r}"
            )
        if isinstance(self.seed, bool) or not isinstance(self.seed, int | np.integer):
            raise TypeError(f"`seed` must be an integer, got {self.seed!r}")
        if self.seed < 0:
            raise ValueError(f"`seed` must be >= 0, got {self.seed}")


def random_slip_scenario(kind: str, rng: Any) -> SlipScenario:
    """A scenario of `kind` with every physical setting drawn at random (see the notes).

    N in [1, 3] N, R in [30, 80] mm (the peak pressure stays within both arrays' range),
    mu_s in [0.4, 1.2], mu_k / mu_s in [0.7, 0.95], T0 in [0, 0.3] mu_s N, hold 60-150 ms,
    ramp to mu_s N in 50-300 ms, plateau of a hold in [0.5, 0.9] mu_s N (half of the holds
    keep T0 constant), v_s in [10, 50] mm/s, relaxation 2-8 ms, any direction; vibrations
    100-300 events/s of 1-4 um; 60 ms recorded after the onset, 200 ms of steady sliding.
    """
    check_choice("kind", kind, SCENARIO_KINDS)
    generator = as_rng("rng", rng)
    rng = generator if generator is not None else np.random.default_rng()
    steady = kind == "steady"
    return SlipScenario(
        kind=kind,
        normal_force=rng.uniform(1.0, 3.0),
        radius=rng.uniform(0.03, 0.08),
        friction=rng.uniform(0.4, 1.2),
        kinetic_ratio=rng.uniform(0.7, 0.95),
        initial_load=rng.uniform(0.0, 0.3),
        hold_time=rng.uniform(0.06, 0.15),
        load_time=0.0 if kind == "hold" and rng.random() < 0.5 else rng.uniform(0.05, 0.3),
        plateau=rng.uniform(0.5, 0.9),
        after_time=0.2 if steady else 0.06,
        sliding_speed=rng.uniform(0.01, 0.05),
        relaxation_time=rng.uniform(2e-3, 8e-3),
        direction=rng.uniform(0.0, 2 * np.pi),
        start=tuple(rng.uniform(-1e-3, 1e-3, 2)),
        vibration_rate=rng.uniform(100.0, 300.0),
        vibration_amplitude=rng.uniform(1e-6, 4e-6),
        friction_ripple=rng.uniform(0.02, 0.05),
        annulus_events=rng.uniform(5.0, 20.0),
        annulus_amplitude=rng.uniform(0.1, 0.3),
        seed=int(rng.integers(2**31)),
    )


@dataclass(frozen=True)
class SlipSequence:
    """A simulated sequence with its truth.

    Attributes
    ----------
    time : numpy.ndarray
        (n_frames,) [s].
    static_frames : numpy.ndarray
        (n_frames, rows, cols) raw frames of the static array.
    piezo_frames : numpy.ndarray
        (n_frames, rows, cols) raw frames of the PVDF array.
    frame_rate : float
        [Hz].
    tangential_load : numpy.ndarray
        (n_frames,) friction force on the pad [N].
    stick_ratio : numpy.ndarray
        (n_frames,) c / a (0 while sliding).
    sliding_displacement : numpy.ndarray
        (n_frames,) object travel over the pad [m].
    pattern_offset : numpy.ndarray
        (n_frames, 2) position of the contact pattern in the sensor frame [m].
    contact_radius : float
        a [m].
    incipient_frame, gross_frame : int or None
        Truth: the first frame of incipient and of gross slip (None: none happens).
    scenario : SlipScenario
    """

    time: np.ndarray = field(repr=False)
    static_frames: np.ndarray = field(repr=False)
    piezo_frames: np.ndarray = field(repr=False)
    frame_rate: float
    tangential_load: np.ndarray = field(repr=False)
    stick_ratio: np.ndarray = field(repr=False)
    sliding_displacement: np.ndarray = field(repr=False)
    pattern_offset: np.ndarray = field(repr=False)
    contact_radius: float
    incipient_frame: int | None
    gross_frame: int | None
    scenario: SlipScenario


@lru_cache(maxsize=1)
def slip_sensors() -> tuple[TactileSensor, TactileSensor]:
    """The static array (resistive16 at 1 kHz) and the PVDF array (piezo8x8) of the finger.

    Both are solved on load grids four times finer than their taxels, so that sub-taxel
    shifts of the pattern are seen.
    """
    static = replace(make_sensor("resistive16"), frame_rate=1000.0, oversampling=_OVERSAMPLING)
    piezo = replace(make_sensor("piezo8x8"), oversampling=_OVERSAMPLING)
    return static, piezo


@lru_cache(maxsize=64)
def _master_contact(
    sensor: TactileSensor, radius: float, normal_force: float
) -> tuple[np.ndarray, float, float]:
    """The pressure field of the sphere on the pad on a fine grid: (field, spacing, a)."""
    cover = sensor.cover
    hertz = hertz_sphere(normal_force, radius, effective_modulus(cover.material)).contact_radius
    spacing = hertz / 25
    n = 2 * int(np.ceil(1.6 * hertz / spacing)) + 1
    offsets = (np.arange(n) - n // 2) * spacing
    x, y = np.meshgrid(offsets, offsets)
    heights = Sphere(radius).local_heights(x, y)
    contact = solve_contact(
        heights,
        spacing,
        cover.material,
        normal_force=normal_force,
        thickness=cover.thickness,
        tolerance=1e-6,
    )
    return contact.pressure, spacing, float(np.sqrt(contact.contact_area / np.pi))


def _events(
    rng: np.random.Generator, rate: np.ndarray, time: np.ndarray, scenario: SlipScenario
) -> np.ndarray:
    """Sum of damped sinusoids started by a Poisson process of rate `rate(t)` [1/s]."""
    step = time[1] - time[0]
    counts = rng.poisson(np.clip(rate, 0.0, None) * step)
    total = np.zeros_like(time)
    low, high = scenario.vibration_band
    for index in np.nonzero(counts)[0]:
        for _ in range(counts[index]):
            start = time[index] - rng.uniform(0.0, step)
            decay = rng.uniform(2e-3, 6e-3)
            span = slice(index, min(index + int(6 * decay / step) + 1, time.size))
            age = time[span] - start
            frequency = rng.uniform(low, high)
            amplitude = rng.uniform(0.5, 1.0)
            total[span] += amplitude * np.exp(-age / decay) * np.sin(2 * np.pi * frequency * age)
    return total


def _kinematics(
    scenario: SlipScenario, time: np.ndarray, rng: np.random.Generator, compliance: float
) -> dict:
    """Load, stick ratio, friction, object position and sliding of every frame.

    The object's position (along the load, relative to the sensor's base) is the pad's
    shear delta while it sticks; once it slips it moves on from the last stuck position
    with a continuous speed (see the module notes), while the pad's shear relaxes with the
    friction force: the sliding displacement is the difference of the two. `compliance` is
    K [m/N].
    """
    s = scenario
    limit = s.friction * s.normal_force
    kinetic = s.kinetic_ratio * s.friction
    tau = s.relaxation_time
    if s.kind == "steady":
        t_slip = -np.inf
        stick = np.zeros(time.shape)
        friction = np.full(time.shape, kinetic)
        travel = s.sliding_speed * time
    else:
        initial = s.initial_load * limit
        target = limit if s.kind == "slip" else s.plateau * limit

        def load_at(t: np.ndarray) -> np.ndarray:
            rate = (limit - initial) / s.load_time if s.load_time > 0 else 0.0
            return np.minimum(initial + rate * np.clip(t - s.hold_time, 0.0, None), target)

        load = load_at(time)
        t_slip = s.hold_time + s.load_time if s.kind == "slip" else np.inf
        stick = np.where(time < t_slip, (1.0 - np.clip(load / limit, 0.0, 1.0)) ** (1 / 3), 0.0)
        after = np.clip(time - t_slip, 0.0, None) if np.isfinite(t_slip) else 0.0 * time
        relax = np.exp(-after / tau)
        friction = np.where(time < t_slip, s.friction, kinetic + (s.friction - kinetic) * relax)
        onset_speed = 0.0
        if np.isfinite(t_slip):  # the stick-phase shift over the last tau, K mu N (c/a)^2
            earlier = 1.0 - np.clip(load_at(np.array(t_slip - tau)) / limit, 0.0, 1.0)
            onset_speed = compliance * limit * float(earlier) ** (2 / 3) / tau
        travel = s.sliding_speed * (after - tau * (1.0 - relax)) + onset_speed * tau * (1 - relax)
    slipping = time >= t_slip
    vibration = s.vibration_amplitude * _events(
        rng, np.where(slipping, s.vibration_rate, 0.0), time, s
    )
    annulus_area = 1.0 - stick**2
    growth = np.clip(np.gradient(annulus_area, time), 0.0, None) * ~slipping
    vibration += (
        s.annulus_amplitude
        * s.vibration_amplitude
        * _events(rng, s.annulus_events * growth, time, s)
    )
    friction = friction * (1.0 + s.friction_ripple * vibration / s.vibration_amplitude * slipping)
    jitter = signal.lfilter(
        *signal.butter(2, 40.0 * (time[1] - time[0])), rng.standard_normal(time.size)
    )
    jitter *= s.force_jitter / max(float(jitter.std()), 1e-12)
    return {
        "stick": stick,
        "friction": friction,
        "slipping": slipping,
        "travel": travel,
        "vibration": vibration,
        "force_scale": 1.0 + jitter,
    }


def simulate_slip(
    scenario: SlipScenario, *, sensors: tuple[TactileSensor, TactileSensor] | None = None
) -> SlipSequence:
    """Simulate one hold-then-slip (or hold, or steady sliding) sequence.

    Parameters
    ----------
    scenario : SlipScenario
        The physical settings; `scenario.seed` seeds the vibrations and the sensor noise.
    sensors : (TactileSensor, TactileSensor), optional
        The static and the PVDF array at the same frame rate; default `slip_sensors()`.

    Returns
    -------
    SlipSequence

    Examples
    --------
    >>> sequence = simulate_slip(SlipScenario(kind="slip", hold_time=0.05, load_time=0.1))
    >>> sequence.static_frames.shape, sequence.piezo_frames.shape
    ((250, 16, 16), (250, 8, 8))
    >>> sequence.incipient_frame, sequence.gross_frame  # frames of the truth
    (54, 151)
    """
    if not isinstance(scenario, SlipScenario):
        raise TypeError(f"`scenario` must be a SlipScenario, got {scenario!r}")
    static, piezo = sensors or slip_sensors()
    if static.frame_rate != piezo.frame_rate:
        raise ValueError(
            f"`sensors` must share one frame rate, got {static.frame_rate:g} and "
            f"{piezo.frame_rate:g} Hz"
        )
    s = scenario
    rate = static.frame_rate
    steady = s.kind == "steady"
    duration = s.after_time if steady else s.hold_time + s.load_time + s.after_time
    time = np.arange(int(round(duration * rate))) / rate
    rng = np.random.default_rng(s.seed)
    master, spacing, contact_radius = _master_contact(static, s.radius, s.normal_force)
    material = static.cover.material
    modulus = material.youngs_modulus / (2 * (1 + material.poisson_ratio))
    compliance = 3 * (2 - material.poisson_ratio) / (16 * modulus * contact_radius)
    kinematics = _kinematics(s, time, rng, compliance)
    slipping = kinematics["slipping"]
    shear = np.where(
        slipping,
        compliance * kinematics["friction"] * s.normal_force,
        compliance * s.friction * s.normal_force * (1.0 - kinematics["stick"] ** 2),
    )
    released = s.kinetic_ratio * s.friction if s.kind == "steady" else s.friction
    position = np.where(
        slipping, compliance * released * s.normal_force + kinematics["travel"], shear
    )
    sliding = np.where(slipping, position - shear, 0.0)
    travel = position + kinematics["vibration"]
    direction = np.array([np.cos(s.direction), np.sin(s.direction)])
    path = float(travel.max() - travel.min())
    start = np.asarray(s.start) - direction * path / 2
    offsets = start + travel[:, None] * direction
    static_stress = sensed_stress(
        static, master, spacing, kinematics, offsets, s.normal_force, s.direction
    )
    piezo_stress = sensed_stress(
        piezo, master, spacing, kinematics, offsets, s.normal_force, s.direction
    )
    # the press happened long before: the charge amplifiers have forgotten it
    piezo_frames = piezo.read_sequence(piezo_stress - piezo_stress[0], rng=rng)
    static_frames = static.read_sequence(np.clip(-static_stress, 0.0, None), rng=rng)
    load = s.normal_force * kinematics["friction"] * (1.0 - kinematics["stick"] ** 3)
    width = 1.0 - kinematics["stick"]
    grown = np.nonzero((width - width[0] > ANNULUS_GROWTH) & ~kinematics["slipping"])[0]
    incipient = int(grown[0]) if grown.size and s.kind != "steady" else None
    slid = np.nonzero(sliding > SLIP_DISPLACEMENT)[0]
    gross = int(slid[0]) if slid.size and s.kind == "slip" else None
    return SlipSequence(
        time=time,
        static_frames=static_frames,
        piezo_frames=piezo_frames,
        frame_rate=rate,
        tangential_load=load,
        stick_ratio=kinematics["stick"],
        sliding_displacement=sliding,
        pattern_offset=offsets,
        contact_radius=contact_radius,
        incipient_frame=incipient,
        gross_frame=gross,
        scenario=s,
    )
