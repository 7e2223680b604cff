"""A tactile array sensor: cover mechanics -> transducer -> readout, frame by frame."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from functools import cached_property
from typing import Any, cast

import numpy as np

from taxel._validation import as_finite_array, as_rng, check_instance, check_positive
from taxel.mechanics import (
    ContactResult,
    ElasticMaterial,
    Indenter,
    inplane_stress_difference,
    solve_contact,
)
from taxel.sensor._cover import Cover
from taxel.sensor._fields import TaxelFields, taxel_fields
from taxel.sensor._geometry import ArrayGeometry, LoadGrid
from taxel.sensor._limits import load_limit
from taxel.sensor._readout import Readout, ReadoutChain
from taxel.sensor._response_direction import flat_plate_gain, reaches_turn, reading_turns_at
from taxel.transducers import (
    FtirTransducer,
    PhotoelasticTransducer,
    Transducer,
    add_drift,
    creep,
    play_hysteresis,
)

__all__ = ["SensorFrame", "TactileSensor"]

# what the sensing element feels, for each quantity a transducer may sense
_FIELD_OF_QUANTITY = {
    "pressure": "stress",  # a cell under the cover is pressed by -sigma_z at its depth
    "stress": "stress",
    "strain": "strain",
    "displacement": "displacement",
    "stress_difference": "pressure",  # computed from the surface pressure, see below
}
_DYNAMIC_QUANTITIES = ("stress",)
_HYSTERESIS_OPERATORS = 8  # piezoelectric: only changes are seen


@dataclass(frozen=True)
class SensorFrame:
    """One frame of a sensor, with what produced it.

    A simulated frame carries everything below; a frame read from a real sensor (by a
    robot driver, see ``docs/robot-driver.md``) carries only `raw`, which is all the
    features and the active procedures read.

    Attributes
    ----------
    raw : numpy.ndarray
        What the sensor outputs: ADC codes, camera levels, or volts when there is no ADC.
    signal : numpy.ndarray or None
        The transducer's ideal signal, before the readout electronics (None if measured).
    quantity : numpy.ndarray or None
        The transducer's input at each taxel (its `quantity`, in its `quantity_unit`; None
        if measured).
    fields : TaxelFields or None
        The mechanical fields at each taxel (None if measured): the surface pressure and
        the field the transducer senses; the others are NaN, not computed (for all four:
        ``taxel_fields(frame.contact.pressure, sensor.load_grid, sensor.cover)``).
    contact : ContactResult or None
        The solved contact, when the frame came from pressing an indenter.

    Examples
    --------
    >>> frame = SensorFrame(np.zeros((16, 16), np.uint16))  # a measured frame
    >>> frame.raw.shape, frame.fields is None
    ((16, 16), True)
    """

    raw: np.ndarray = field(repr=False)
    signal: np.ndarray | None = field(default=None, repr=False)
    quantity: np.ndarray | None = field(default=None, repr=False)
    fields: TaxelFields | None = field(default=None, repr=False)
    contact: ContactResult | None = field(default=None, repr=False)


@dataclass(frozen=True, eq=False)
class TactileSensor:
    """A tactile array sensor model (Ellis seed section 1; chapter sections 25.2-25.3).

    Parameters
    ----------
    name : str
        A short name (presets use their preset name).
    geometry : ArrayGeometry
        Where the taxels are.
    cover : Cover
        The compliant pad and the depth of the sensing elements.
    transducer : Transducer
        The transduction technology (see `taxel.transducers`).
    readout : Readout, optional
        The electronics: non-idealities and ADC.
    frame_rate : float, default 100.0
        Frames per second [Hz].
    full_scale : float, default 200e3
        Working range: the largest pressure the sensor is specified for [Pa].
    oversampling : int, default 1
        Surface cells per taxel along a side, on which contacts are solved.
    cell_modulus : float, optional
        For transducers that sense strain (capacitive): the constrained modulus of the
        sensing cell's dielectric [Pa], whose strain is sigma_z / cell_modulus. None uses the
        cover's own strain eps_z at the sensing depth (the chapter's model).
    calibration_levels : int, default 21
        Flat-plate pressures `calibrate` uses by default, >= 4: more where the output's
        steps are coarse (an 8-bit camera), so that the plates straddle each step.
    description : str
        One line for reports.
    """

    name: str
    geometry: ArrayGeometry
    cover: Cover
    transducer: Transducer
    readout: Readout = field(default_factory=Readout)
    frame_rate: float = 100.0
    full_scale: float = 200e3
    oversampling: int = 1
    cell_modulus: float | None = None
    calibration_levels: int = 21
    description: str = ""

    def __post_init__(self) -> None:
        if not isinstance(self.transducer, Transducer):
            raise TypeError(
                f"`transducer` must follow the Transducer protocol, got {self.transducer!r}"
            )
        if self.transducer.quantity not in _FIELD_OF_QUANTITY:
            raise ValueError(f"unsupported transducer quantity {self.transducer.quantity!r}")
        check_positive("frame_rate", self.frame_rate)
        check_positive("full_scale", self.full_scale)
        if self.cell_modulus is not None:
            check_positive("cell_modulus", self.cell_modulus)
        levels = self.calibration_levels
        if isinstance(levels, bool) or not isinstance(levels, int) or levels < 4:
            raise ValueError(f"`calibration_levels` must be an integer >= 4, got {levels!r}")
        self.geometry.load_grid(self.oversampling)  # validates the oversampling

    # ----------------------------------------------------------------- geometry and units
    @property
    def shape(self) -> tuple[int, int]:
        """(rows, cols) of taxels."""
        return self.geometry.shape

    @property
    def taxel_pitch(self) -> tuple[float, float]:
        """(row pitch, column pitch) [m]."""
        return self.geometry.taxel_pitch

    @cached_property
    def load_grid(self) -> LoadGrid:
        """The surface cells on which contacts are solved."""
        return self.geometry.load_grid(self.oversampling)

    @property
    def quantity(self) -> str:
        """The physical quantity the transducer senses."""
        return self.transducer.quantity

    @property
    def is_dynamic(self) -> bool:
        """True when the sensor sees only changes of load (piezoelectric)."""
        return self.transducer.quantity in _DYNAMIC_QUANTITIES

    # ------------------------------------------------------------------------- mechanics
    def press(
        self,
        indenter: Indenter,
        *,
        normal_force: float | None = None,
        indentation: float | None = None,
        position: tuple[float, float] = (0.0, 0.0),
        angle: float = 0.0,
        indenter_material: ElasticMaterial | None = None,
        initial: ContactResult | None = None,
        rng: Any = None,
        progress: Callable[[int, int], None] | None = None,
    ) -> SensorFrame:
        """Press an indenter on the sensor and read one frame.

        Parameters
        ----------
        indenter : Indenter
            What presses (see `taxel.mechanics.make_indenter`).
        normal_force, indentation : float
            Force [N] or approach [m], >= 0: give one. Zero reads the sensor at rest (no
            contact; with `rng`, its noise and fixed pattern alone).
        position, angle
            Placement of the indenter in the sensor frame [m], [rad].
        indenter_material : ElasticMaterial, optional
            An elastic indenter; None for rigid.
        initial : ContactResult, optional
            The previous frame's contact, to warm-start the solver.
        rng : numpy.random.Generator or int, optional
            Switches the noise on (reproducibly); None gives the noise-free frame.
        progress : callable, optional
            ``progress(done, total)``, called by the contact solve after each iteration (see
            `taxel.mechanics.solve_contact`); a fine load grid makes it slow.

        Returns
        -------
        SensorFrame

        Raises
        ------
        ValueError
            Also when the press would take the transducer past its physical end (close a
            reflective sensor's gap, squeeze a capacitive dielectric flat); the message
            says so and names `normal_force` (or `indentation`) and its value.
        """
        check_instance("indenter", indenter, Indenter)
        as_rng("rng", rng)  # before the solve, not after it
        x, y = self.load_grid.coordinates()
        heights = indenter.heights(x, y, position=position, angle=angle)
        contact = solve_contact(
            heights,
            self.load_grid.spacing,
            self.cover.material,
            normal_force=normal_force,
            indentation=indentation,
            indenter_material=indenter_material,
            thickness=self.cover.thickness,
            initial=initial,
            progress=progress,
        )
        try:
            return self.frame_from_pressure(
                contact.pressure, displacement=contact.displacement, rng=rng, contact=contact
            )
        except ValueError:  # past the transducer's end? say so of the load, not its input
            fields = self.fields(contact.pressure, displacement=contact.displacement)
            quantity = self.sensed_quantity(contact.pressure, fields)
            if normal_force is not None:
                load = ("normal_force", f"{normal_force:g} N")
            else:
                load = ("indentation", f"an indentation of {float(indentation or 0) * 1e3:g} mm")
            message = load_limit(self, quantity, *load)
            if message is None:
                raise
            raise ValueError(message) from None

    def fields(self, pressure: Any, *, displacement: np.ndarray | None = None) -> TaxelFields:
        """Mechanical fields at each taxel for a surface pressure on the load grid [Pa].

        Only the surface pressure and the field the transducer senses are computed (one
        convolution each); the others are NaN (`taxel_fields` computes all four).
        """
        pressure = as_finite_array("pressure", pressure, ndim=2)
        need = (_FIELD_OF_QUANTITY[self.quantity], "pressure")
        if self.quantity == "strain" and self.cell_modulus is not None:
            need = ("stress", "pressure")  # the cell's strain follows the stress at its depth
        return taxel_fields(
            pressure, self.load_grid, self.cover, displacement=displacement, need=need
        )

    def sensed_quantity(self, pressure: np.ndarray, fields: TaxelFields) -> np.ndarray:
        """The transducer's input at each taxel, from the fields (and the surface pressure)."""
        quantity = self.quantity
        if quantity == "pressure":
            return np.clip(-fields.stress, 0.0, None)  # a cell cannot be pulled
        if quantity == "stress":
            return fields.stress
        if quantity == "displacement":
            return fields.displacement
        if quantity == "strain":
            if self.cell_modulus is None:
                return fields.strain
            return fields.stress / self.cell_modulus
        # stress_difference: through the photoelastic layer under the cover (half-space model)
        thickness = cast(PhotoelasticTransducer, self.transducer).layer_thickness
        nodes, weights = np.polynomial.legendre.leggauss(3)
        total = np.zeros(self.load_grid.shape)
        for node, weight in zip(nodes, weights, strict=True):
            depth = self.cover.depth + (node + 1) / 2 * thickness
            total += (
                weight
                / 2
                * inplane_stress_difference(
                    pressure, self.load_grid.spacing, depth, self.cover.material
                )
            )
        return self.load_grid._means(total)

    # ---------------------------------------------------------------- transducer, readout
    def respond(self, quantity: Any, *, rng: Any = None) -> np.ndarray:
        """Ideal transducer signal for one frame of the sensed quantity.

        A dynamic (piezoelectric) sensor responds to the step from rest to `quantity`, read
        one frame period later.
        """
        return self._respond(self._taxel_frames("quantity", quantity), rng)

    def _respond(self, quantity: np.ndarray, rng: Any = None) -> np.ndarray:
        """`respond` on frames already checked."""
        if self.is_dynamic:
            series = np.stack([np.zeros_like(quantity), quantity], axis=-1)
            return self.transducer.respond(series, time_step=1.0 / self.frame_rate)[..., -1]
        if self.transducer.signal_unit == "DN":  # a camera: its own noise when rng is given
            return self.transducer.respond(quantity, rng=rng)
        return self.transducer.respond(quantity)

    @cached_property
    def readout_chain(self) -> ReadoutChain:
        """The electronics of this unit, bound to its signal range and fixed pattern.

        The ADC range covers this unit's taxels from rest to a full-scale flat plate after
        their gain, offset and crosstalk, so that no working taxel clips below full scale.
        """
        low, high = self.signal_range
        rest = self._ideal_signal(np.zeros(self.load_grid.shape))
        loaded = self._ideal_signal(np.full(self.load_grid.shape, self.full_scale))
        chain = ReadoutChain(self.readout, low, high, np.shape(rest))
        if self.readout.is_identity or self.is_dynamic:
            return chain
        return chain.covering(np.stack([rest, loaded]))

    @cached_property
    def quantity_span(self) -> float:
        """Span of the sensed quantity over the working range, unloaded to a full-scale plate.

        The unit is the transducer's `quantity_unit`; hysteresis loops are fractions of it.
        """
        grid = self.load_grid.shape
        values = []
        for pressure in (np.zeros(grid), np.full(grid, self.full_scale)):
            fields = self.fields(pressure)
            values.append(float(np.mean(self.sensed_quantity(pressure, fields))))
        return abs(values[1] - values[0]) or 1.0

    @cached_property
    def signal_range(self) -> tuple[float, float]:
        """(low, high) of the transducer's signal over the working range, with 5 % margin.

        Found by reading the unloaded sensor and a flat plate pressing the whole array at
        `full_scale`, the same loads a calibration uses.
        """
        rest = self._ideal_signal(np.zeros(self.load_grid.shape))
        loaded = self._ideal_signal(np.full(self.load_grid.shape, self.full_scale))
        values = np.concatenate([np.ravel(rest), np.ravel(loaded)])
        if self.quantity == "stress_difference":  # a flat plate makes no fringes
            photoelastic = cast(PhotoelasticTransducer, self.transducer)
            values = np.append(values, photoelastic.source_intensity)
        if self.is_dynamic:  # a step can swing either way before it fades
            values = np.append(values, -values)
        low, high = float(values.min()), float(values.max())
        margin = 0.05 * (high - low) if high > low else 1.0
        return low - margin, high + margin

    @cached_property
    def flat_plate_gain(self) -> float:
        """Mean change of the raw reading per pascal near rest (`response_direction`)."""
        return flat_plate_gain(self)

    @property
    def reading_falls_with_pressure(self) -> bool:
        """Whether the raw reading falls as the pressure rises (a PVDF array's does)."""
        return self.flat_plate_gain < 0

    @cached_property
    def reading_turns_at(self) -> float | None:
        """The mean raw reading past which the reading turns back (`response_direction`)."""
        return reading_turns_at(self)

    def reaches_turn(self, raw: Any) -> bool:
        """Whether a raw frame reaches `reading_turns_at` (`response_direction`)."""
        return reaches_turn(self, self._taxel_frames("raw", raw))

    def _ideal_signal(self, pressure: np.ndarray) -> np.ndarray:
        fields = self.fields(pressure)
        return np.asarray(self._respond(self.sensed_quantity(pressure, fields)), dtype=float)

    def frame_from_pressure(
        self,
        pressure: Any,
        *,
        displacement: np.ndarray | None = None,
        rng: Any = None,
        contact: ContactResult | None = None,
        temperature: float | None = None,
    ) -> SensorFrame:
        """Read one frame for a surface pressure on the load grid [Pa].

        `rng` switches on the noise (reproducibly); `temperature` [K] applies the readout's
        temperature coefficient.
        """
        pressure = as_finite_array("pressure", pressure, ndim=2)
        fields = self.fields(pressure, displacement=displacement)
        quantity = self.sensed_quantity(pressure, fields)
        signal, raw = self._read(quantity, rng, temperature)
        return SensorFrame(raw, signal, quantity, fields, contact)

    def _taxel_frames(self, name: str, values: Any, ndim: int = 2) -> np.ndarray:
        """`values` as float frames of the taxels, shape (..., rows, cols), at least `ndim`-D."""
        array = np.asarray(values, dtype=float)
        if array.ndim < ndim or array.shape[-2:] != self.shape:
            batch = "(frames, " if ndim == 3 else "(..., "
            raise ValueError(
                f"`{name}` must have shape {batch}{self.shape[0]}, {self.shape[1]}) for this "
                f"sensor's taxels, got {array.shape}"
            )
        return array

    def _read(
        self, quantity: np.ndarray, rng: Any, temperature: float | None
    ) -> tuple[np.ndarray, np.ndarray]:
        generator = as_rng("rng", rng)
        signal = self._respond(quantity, generator)
        raw = self.readout_chain.apply(signal, rng=generator, temperature=temperature)
        return np.asarray(signal, dtype=float), np.asarray(raw)

    def read(self, quantity: Any, *, rng: Any = None, temperature: float | None = None) -> Any:
        """Raw frame for a frame of the sensed quantity (transducer, then readout).

        The mechanics are left out, so repeated frames of one load (a calibration's
        repeats) cost only the electronics. `rng` switches the noise on.
        """
        quantity = self._taxel_frames("quantity", as_finite_array("quantity", quantity))
        return self._read(quantity, rng, temperature)[1]

    def mean_reading(self, quantity: Any) -> np.ndarray:
        """The expected raw frame for a frame of the sensed quantity, without quantisation.

        What the mean of many noisy frames tends to when the noise spans a few ADC steps:
        the analog signal at the ADC input in code units (minus half a step, the mean
        offset of a flooring converter), or the camera's mean level [DN] before rounding.
        Used to measure responses finer than one step (sensitivity, monotonicity).
        """
        quantity = self._taxel_frames("quantity", as_finite_array("quantity", quantity))
        transducer = self.transducer
        if isinstance(transducer, FtirTransducer):  # the camera quantises; undo its rounding
            fraction = transducer.light_fraction(quantity)
            if transducer.scratch_count:
                fraction = fraction + transducer.scratches(quantity.shape[-2:])
            span = transducer.bright_level - transducer.dark_level
            signal = transducer.dark_level + span * fraction
        else:
            signal = np.asarray(self._respond(quantity), dtype=float)
        chain = self.readout_chain
        if self.readout.is_identity:
            return signal
        analog = chain.analog(signal)
        lsb = chain.lsb
        if lsb is None:
            return analog
        return (analog - chain.rails[0]) / lsb - 0.5

    def read_sequence(self, quantities: Any, *, rng: Any = None) -> np.ndarray:
        """Raw frames for a time series of the sensed quantity, shape (frames, ...).

        Applies what acts along time: creep and hysteresis of the cover on the quantity,
        the transducer's own dynamics (piezoelectric), and baseline drift, then the static
        readout chain frame by frame.
        """
        series = self._taxel_frames("quantities", as_finite_array("quantities", quantities), 3)
        if series.shape[0] == 0:
            raise ValueError("`quantities` must hold at least one frame, got 0")
        step = 1.0 / self.frame_rate
        readout = self.readout
        moved = np.moveaxis(series, 0, -1)  # time along the last axis, as the dynamics expect
        if readout.creep:
            moved = creep(
                moved, step, creep_fraction=readout.creep, time_constant=readout.creep_time
            )
        if readout.hysteresis:
            # the loop is a fraction of the working range, as `Readout` documents it; a sum of
            # plays (Prandtl-Ishlinskii) rounds the loop's corners, where a single play would
            # freeze the reading for any change smaller than the whole loop
            moved = play_hysteresis(
                moved,
                loop_width=readout.hysteresis * self.quantity_span,
                n_operators=_HYSTERESIS_OPERATORS,
            )
        if self.is_dynamic:
            signal = self.transducer.respond(moved, time_step=step)
        else:
            signal = np.moveaxis(
                np.asarray([self._respond(frame) for frame in np.moveaxis(moved, -1, 0)]), 0, -1
            )
        generator = as_rng("rng", rng)
        if readout.drift_rate:
            signal = add_drift(
                signal, step, rate=readout.drift_rate * self.readout_chain.span, rng=generator
            )
        frames = np.moveaxis(signal, -1, 0)
        return np.asarray([self.readout_chain.apply(frame, rng=generator) for frame in frames])

    # ----------------------------------------------------------------- reporting helpers
    @property
    def density_class(self) -> str:
        """LDTA, MDTA, HDTA or VHDTA (Ellis seed, section 1)."""
        return self.geometry.density_class
