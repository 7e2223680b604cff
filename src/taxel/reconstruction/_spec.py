"""What the inverse problem needs to know about a sensor: the forward-model specification.

The sensor layer (`taxel.sensor`) describes a whole device; reconstruction needs only the
linear map from surface pressure to calibrated readings. `ForwardModelSpec` holds exactly
that, and any object with a ``forward_model_spec()`` method (a `TactileSensor`) can stand in
for it. Until the sensor presets exist, `forward_model_preset` builds the two configurations
used by the reconstruction benchmark from one table.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from taxel._validation import check_choice, check_count, check_grid_shape, check_positive
from taxel.mechanics import ElasticMaterial
from taxel.sensor import TactileSensor, make_sensor

__all__ = [
    "FORWARD_MODEL_PRESETS",
    "QUANTITIES",
    "ForwardModelSpec",
    "as_forward_model_spec",
    "forward_model_preset",
    "plate_reading",
    "reading_quantity",
    "spec_from_sensor",
    "with_dead_taxels",
]

QUANTITIES: tuple[str, ...] = ("stress", "strain", "displacement")


@dataclass(frozen=True)
class ForwardModelSpec:
    """The linear forward model of a tactile array: pressure on a load grid -> readings.

    Parameters
    ----------
    shape : tuple of int
        (rows, cols) of the taxel array.
    taxel_pitch : float
        Centre-to-centre distance of the taxels [m] (square cells).
    material : ElasticMaterial
        The cover.
    depth : float
        Depth d of the sensing elements below the cover surface [m]; ignored (may be 0)
        for ``quantity="displacement"``.
    thickness : float, optional
        Cover thickness over a rigid backing [m]; None for a half-space.
    quantity : {"stress", "strain", "displacement"}, default "stress"
        What a calibrated reading is. "stress": the pressure felt at depth, -sigma_z(d) [Pa],
        so a uniform pressure p reads p; "strain": eps_z(d) [-] (negative under load);
        "displacement": the normal surface displacement u_z [m] (optical sensors).
    oversampling : int, default 1
        Load cells per taxel along each axis: the pressure is sought on a grid of pitch
        ``taxel_pitch / oversampling`` (super-resolution for values > 1).
    dead_taxels : array_like of bool or sequence of (row, col), optional
        Taxels the calibration marked dead; they are left out of every fit.
    full_scale : float, optional
        Full-scale reading, in reading units (used to state noise as a fraction of it).
    noise_level : float, optional
        Standard deviation of the reading noise, in reading units, if known; below
        `full_scale`.

    Notes
    -----
    A calibrated reading is the quantity at depth averaged over the taxel's cell. With
    oversampling k the forward operator is the exact cell-integrated operator on the fine
    load grid followed by k x k block averaging; with k = 1 it is the cell-integrated kernel
    sampled at the taxel centre (`taxel.mechanics.depth_stress_operator`).

    Examples
    --------
    >>> from taxel.mechanics import ElasticMaterial
    >>> spec = ForwardModelSpec((16, 16), 2e-3, ElasticMaterial(1e6, 0.49), 1.5e-3,
    ...                         thickness=1.5e-3, oversampling=2, dead_taxels=[(3, 4)])
    >>> spec.load_shape, spec.load_pitch, int(spec.live_taxels.sum())
    ((32, 32), 0.001, 255)
    """

    shape: tuple[int, int]
    taxel_pitch: float
    material: ElasticMaterial
    depth: float
    thickness: float | None = None
    quantity: str = "stress"
    oversampling: int = 1
    dead_taxels: tuple[tuple[int, int], ...] = field(default=(), repr=False)
    full_scale: float | None = None
    noise_level: float | None = None

    def __post_init__(self) -> None:
        rows, cols = check_grid_shape("shape", self.shape)
        if rows < 2 or cols < 2:
            raise ValueError(f"`shape` must be at least (2, 2), got {self.shape!r}")
        object.__setattr__(self, "shape", (rows, cols))
        object.__setattr__(self, "taxel_pitch", check_positive("taxel_pitch", self.taxel_pitch))
        if not isinstance(self.material, ElasticMaterial):
            raise TypeError(f"`material` must be an ElasticMaterial, got {self.material!r}")
        check_choice("quantity", self.quantity, QUANTITIES)
        depth = check_positive("depth", self.depth, allow_zero=self.quantity == "displacement")
        object.__setattr__(self, "depth", depth)
        if self.thickness is not None:
            thickness = check_positive("thickness", self.thickness)
            if depth > thickness:
                raise ValueError(
                    f"`depth` must be <= `thickness` ({thickness:g} m), got {depth:g}"
                )
            object.__setattr__(self, "thickness", thickness)
        try:
            oversampling = check_count("oversampling", self.oversampling)
        except (TypeError, ValueError):
            oversampling = 0  # not a whole number: refused below
        if not 1 <= oversampling <= 8:
            raise ValueError(
                f"`oversampling` must be an integer in 1..8, got {self.oversampling!r}"
            )
        object.__setattr__(self, "oversampling", oversampling)
        object.__setattr__(self, "dead_taxels", _as_taxel_list(self.dead_taxels, (rows, cols)))
        for name in ("full_scale", "noise_level"):
            value = getattr(self, name)
            if value is not None:
                object.__setattr__(self, name, check_positive(name, value))
        if self.noise_level is not None:
            self.check_noise_level(self.noise_level)

    @property
    def reading_unit(self) -> str:
        """The unit of a reading: "Pa", "m", or "" for a strain."""
        return {"stress": "Pa", "displacement": "m"}.get(self.quantity, "")

    def check_noise_level(self, noise_level: Any, name: str = "noise_level") -> float:
        """`noise_level` as a float; raise unless it is > 0 and below the full-scale reading.

        Noise as large as the full-scale reading leaves nothing to reconstruct: the
        discrepancy principle would smooth any contact away (2 N read 0.02 N at 1e300 Pa).
        """
        value = check_positive(name, noise_level)
        if self.full_scale is not None and value >= self.full_scale:
            unit = f" {self.reading_unit}".rstrip()
            raise ValueError(
                f"`{name}` must be below the full-scale reading ({self.full_scale:.4g}{unit}), "
                f"got {value:g}"
            )
        return value

    @property
    def load_shape(self) -> tuple[int, int]:
        """(rows, cols) of the load grid on which pressure is sought."""
        k = self.oversampling
        return self.shape[0] * k, self.shape[1] * k

    @property
    def load_pitch(self) -> float:
        """Cell size of the load grid [m]."""
        return self.taxel_pitch / self.oversampling

    @property
    def live_taxels(self) -> np.ndarray:
        """Boolean (rows, cols) mask, False at dead taxels."""
        mask = np.ones(self.shape, dtype=bool)
        for row, col in self.dead_taxels:
            mask[row, col] = False
        return mask

    def with_changes(self, **changes: Any) -> ForwardModelSpec:
        """A copy with some fields replaced (e.g. ``oversampling=2``)."""
        return replace(self, **changes)


def with_dead_taxels(spec: ForwardModelSpec, dead_taxels: Any) -> ForwardModelSpec:
    """`spec` with `dead_taxels` (a boolean mask or (row, col) pairs) also left out.

    `spec` itself when there are none to add (a solver cached for it is then reused).

    Examples
    --------
    >>> spec = forward_model_preset("resistive16", dead_taxels=[(0, 0)])
    >>> mask = np.zeros((16, 16), dtype=bool); mask[2, 5] = True
    >>> with_dead_taxels(spec, mask).dead_taxels
    ((0, 0), (2, 5))
    """
    if dead_taxels is None:
        return spec
    added = _as_taxel_list(dead_taxels, spec.shape)
    if set(added) <= set(spec.dead_taxels):
        return spec
    return spec.with_changes(dead_taxels=tuple(sorted(set(spec.dead_taxels) | set(added))))


def _as_taxel_list(dead: Any, shape: tuple[int, int]) -> tuple[tuple[int, int], ...]:
    """Dead taxels as a sorted tuple of (row, col), from a boolean mask or a list of pairs."""
    if dead is None:
        return ()
    try:
        array = np.asarray(dead)
    except ValueError:  # ragged: pairs and triples mixed
        raise ValueError(
            f"`dead_taxels` must be a boolean mask or (row, col) pairs, got {dead!r}"
        ) from None
    if array.dtype == bool:
        if array.shape != shape:
            raise ValueError(f"`dead_taxels` mask must have shape {shape}, got {array.shape}")
        pairs = np.argwhere(array)
    else:
        if array.size == 0:
            return ()
        if array.ndim != 2 or array.shape[1] != 2:
            raise ValueError(
                f"`dead_taxels` must be a boolean mask or (row, col) pairs, got {dead!r}"
            )
        if array.dtype.kind not in "iuf" or not np.all(np.isfinite(array) & (array % 1 == 0)):
            raise ValueError(
                f"`dead_taxels` must hold whole-number (row, col) indices, got {dead!r}"
            )
        pairs = array.astype(int)
        if np.any(pairs < 0) or np.any(pairs[:, 0] >= shape[0]) or np.any(pairs[:, 1] >= shape[1]):
            raise ValueError(f"`dead_taxels` must lie inside the {shape} array, got {dead!r}")
    result = tuple(sorted({(int(r), int(c)) for r, c in pairs}))
    if len(result) >= shape[0] * shape[1]:
        raise ValueError("`dead_taxels` must leave at least one live taxel")
    return result


# quantity the transducer senses -> what a calibrated reading is, for the inverse problem
_READING = {
    "pressure": "stress",
    "stress": "stress",
    "strain": "strain",
    "displacement": "displacement",
}


def reading_quantity(sensor: TactileSensor) -> str:
    """What a calibrated reading of `sensor` is for the inverse problem: a `QUANTITIES` entry."""
    reading = _READING.get(sensor.quantity, sensor.quantity)
    if sensor.quantity == "strain" and sensor.cell_modulus is not None:
        reading = "stress"  # the cell's strain follows the stress at its depth
    return reading


def plate_reading(sensor: TactileSensor) -> np.ndarray:
    """Each taxel's reading per pascal of a flat plate over the whole array [reading unit / Pa].

    The reading is `reading_quantity`: the stress felt at depth (-sigma_z, [Pa / Pa]), the
    strain eps_z [1 / Pa] or the surface displacement u_z [m / Pa], from the sensor's own
    cover model. A calibration maps raw codes to the plate pressure that gives them; times
    this, to what the forward model predicts.
    """
    quantity = reading_quantity(sensor)
    plate = np.ones(sensor.load_grid.shape)
    value = sensor.fields(plate).get(quantity)
    return np.clip(-value, 0.0, None) if quantity == "stress" else value


def spec_from_sensor(sensor: TactileSensor, **changes: Any) -> ForwardModelSpec:
    """The forward model of a `taxel.sensor.TactileSensor`, with optional changes.

    A calibrated reading of a pressure- or stress-sensing taxel is the pressure felt at its
    depth, -sigma_z(d) [Pa]; of a strain-sensing one, eps_z(d) (or, when its cell has its
    own modulus, again the stress at depth); of a displacement-sensing one, u_z [m].

    Raises
    ------
    ValueError
        For sensors whose readings are not one value per taxel of a square array
        (microbend fibres, photoelastic fringes, rectangular or hexagonal layouts).

    Examples
    --------
    >>> from taxel.sensor import make_sensor
    >>> spec = spec_from_sensor(make_sensor("vhdta128"))
    >>> spec.shape, round(spec.depth / spec.taxel_pitch, 2), spec.quantity
    ((128, 128), 3.88, 'stress')
    """
    quantity = sensor.quantity
    geometry = sensor.geometry
    if quantity not in _READING or sensor.name == "microbend16":
        raise ValueError(
            f"`sensor` {sensor.name!r} does not give one reading per taxel of its "
            f"{quantity!r}; the pressure cannot be reconstructed from it this way"
        )
    row_pitch, col_pitch = geometry.taxel_pitch
    if geometry.layout == "hexagonal" or not np.isclose(row_pitch, col_pitch):
        raise ValueError(f"`sensor` {sensor.name!r} must be a square array, got {geometry.layout}")
    reading = reading_quantity(sensor)
    full_scale = sensor.full_scale
    if reading != "stress":  # in the reading's own unit: the largest reading of a full plate
        full_scale *= float(np.abs(plate_reading(sensor)).max())
    fields: dict[str, Any] = {
        "shape": geometry.shape,
        "taxel_pitch": col_pitch,
        "material": sensor.cover.material,
        "depth": sensor.cover.depth,
        "thickness": sensor.cover.thickness,
        "quantity": reading,
        "full_scale": full_scale,
    }
    return ForwardModelSpec(**(fields | changes))


# the sensor presets whose readings can be inverted for a pressure map
FORWARD_MODEL_PRESETS: tuple[str, ...] = (
    "vhdta128",
    "harmon10x20",
    "resistive16",
    "capacitive4x4",
    "piezo8x8",
    "reflective8x8",
)


def forward_model_preset(name: str, **changes: Any) -> ForwardModelSpec:
    """The forward model of a preset sensor of `taxel.sensor`, with optional changes.

    Parameters
    ----------
    name : str
        One of `FORWARD_MODEL_PRESETS`, e.g. "vhdta128" (128 x 128 taxels at 33/128 mm
        under a 1 mm cover, E = 0.5 MPa, nu = 0.49, bonded to glass, stress sensed at the
        interface, full scale 413.7 kPa) or "resistive16" (16 x 16 taxels at 2 mm under a
        1.5 mm cover, E = 1 MPa, nu = 0.49, stress sensed at the base, full scale 200 kPa).
    **changes
        Fields of `ForwardModelSpec` to override (``oversampling``, ``dead_taxels``, ...).

    Returns
    -------
    ForwardModelSpec

    Examples
    --------
    >>> spec = forward_model_preset("vhdta128")
    >>> spec.shape, round(spec.depth / spec.taxel_pitch, 2)
    ((128, 128), 3.88)
    """
    check_choice("sensor", name, FORWARD_MODEL_PRESETS)
    return spec_from_sensor(make_sensor(name), **changes)


def as_forward_model_spec(sensor: Any) -> ForwardModelSpec:
    """The forward-model spec of `sensor`: a spec, a preset name, or a sensor object.

    A sensor object is a `taxel.sensor.TactileSensor` (see `spec_from_sensor`), or anything
    with a ``forward_model_spec()`` method returning a spec.

    Examples
    --------
    >>> as_forward_model_spec(forward_model_preset("resistive16")).shape
    (16, 16)
    """
    if isinstance(sensor, ForwardModelSpec):
        return sensor
    if isinstance(sensor, str):
        return forward_model_preset(sensor)
    if isinstance(sensor, TactileSensor):
        return spec_from_sensor(sensor)
    method = getattr(sensor, "forward_model_spec", None)
    if callable(method):
        spec = method()
        if isinstance(spec, ForwardModelSpec):
            return spec
    raise TypeError(
        "`sensor` must be a ForwardModelSpec, a TactileSensor, a preset name or have a "
        f"forward_model_spec() method, got {type(sensor).__name__}"
    )
