"""Per-taxel calibration from flat-plate presses, with dead and stuck taxels masked.

A calibration rig presses a flat plate on the whole array at a set of known pressures,
several times each, and records the raw frames. For every taxel the mean reading at each
pressure is made monotonic (isotonic regression: noise can make neighbouring means cross)
and a monotone cubic (PCHIP) through those points is the taxel's response; its inverse is
the calibration. A taxel whose reading hardly changes with load, or that reads a rail of
the ADC at every pressure, is excluded: its calibrated value is NaN and `valid` is False.
"""

from __future__ import annotations

import json
import math
import os
from dataclasses import dataclass, field
from functools import cached_property
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from taxel._npy import read_npz
from taxel._validation import as_finite_array, is_json_number
from taxel.sensor._monotone import invert_pchip
from taxel.sensor._sensor import TactileSensor

if TYPE_CHECKING:
    from scipy.interpolate import PchipInterpolator

__all__ = ["Calibration", "check_calibration"]

_FORMAT = "taxel.calibration/1"
# the arrays a calibration file holds
_ARRAYS = {"meta", "pressures", "readings", "unresponsive", "pinned", "noise", "felt_fraction"}


@dataclass(frozen=True, eq=False)
class Calibration:
    """A per-taxel map from raw reading to equivalent plate pressure [Pa].

    The calibrated value of a taxel (`apply`) is the pressure of a flat plate over the
    whole array that gives its reading: the pressure on the cover above it when the load
    is uniform, and for any load the sensed quantity expressed in that unit. `felt_pressure`
    turns it into the pressure the taxel feels, the normal stress at its depth, which a
    plate over the array delivers in full to inner taxels and only in part to the edge
    ones. Build it with `calibrate`.

    Attributes
    ----------
    sensor_name : str
        The sensor it belongs to.
    pressures : numpy.ndarray, shape (n_levels,)
        Plate pressures of the calibration, increasing, from 0 [Pa].
    readings : numpy.ndarray, shape (n_levels, *shape)
        Monotonic fit of the mean raw reading of every taxel at each pressure [raw unit].
    valid : numpy.ndarray of bool, shape `shape`
        Taxels that respond to load; the others are NaN in every calibrated frame.
    unresponsive : numpy.ndarray of bool
        Taxels whose reading changes by less than `min_response` of the median change
        from no load to full scale (dead, stuck, or wired the wrong way).
    pinned : numpy.ndarray of bool
        Taxels that read a rail of the ADC (bottom or top code) at every pressure.
    noise : numpy.ndarray
        Standard deviation of each taxel's reading over the repeats without load
        [raw unit]; 0 for a noise-free calibration.
    full_scale : float
        The sensor's working range [Pa].
    repeats : int
        Frames averaged per pressure.
    felt_fraction : numpy.ndarray, optional
        Per taxel, the compressive normal stress at the sensing depth per pascal of plate
        pressure [-], from the sensor's cover model; None when not known (ones are used).
    """

    sensor_name: str
    pressures: np.ndarray = field(repr=False)
    readings: np.ndarray = field(repr=False)
    valid: np.ndarray = field(repr=False)
    unresponsive: np.ndarray = field(repr=False)
    pinned: np.ndarray = field(repr=False)
    noise: np.ndarray = field(repr=False)
    full_scale: float
    repeats: int
    felt_fraction: np.ndarray | None = field(default=None, repr=False)

    @property
    def shape(self) -> tuple[int, ...]:
        """Shape of one raw frame."""
        return tuple(self.readings.shape[1:])

    @property
    def direction(self) -> int:
        """+1 when the reading grows with load, -1 when it falls (microbend fibres)."""
        change = np.median((self.readings[-1] - self.readings[0])[self.valid])
        return 1 if not change < 0 else -1

    @cached_property
    def _response(self) -> PchipInterpolator:
        # imported here: scipy.interpolate takes ~0.8 s to import (see taxel.cli)
        from scipy.interpolate import PchipInterpolator

        flat = self.direction * self.readings.reshape(len(self.pressures), -1)
        return PchipInterpolator(self.pressures, flat, axis=0)

    def apply(self, raw: Any, *, clip: bool = False) -> np.ndarray:
        """Calibrated frame: equivalent plate pressure of every taxel [Pa].

        Parameters
        ----------
        raw : array_like, shape (..., *shape)
            One or more raw frames of the sensor.
        clip : bool, default False
            Clip the result to [0, full_scale]. By default a reading on the far side of
            the no-load reading continues the response's slope there, so noise about no
            load stays zero-mean (clipping it at 0 would add a positive bias to every
            unloaded taxel, and to any total force).

        Returns
        -------
        numpy.ndarray, shape (..., *shape)
            Pressure [Pa]. A reading beyond the full-scale one returns full scale (the
            information is lost there); a reading that several pressures share (a flat part
            of the response) returns the middle of them. NaN where `valid` is False.
        """
        raw = self._frames(raw)
        shape = self.shape
        lead = raw.shape[: raw.ndim - len(shape)]
        taxels = int(np.prod(shape))
        knots = self.direction * self.readings.reshape(len(self.pressures), taxels)
        oriented = self.direction * raw.reshape(-1, taxels)
        x = np.clip(oriented, knots[0], knots[-1])
        pressure = invert_pchip(self._response, self.pressures, knots, x)
        if not clip:
            below = oriented < knots[0]
            pressure = np.where(below, (oriented - knots[0]) * self._rest_slope, pressure)
        pressure = np.where(self.valid.reshape(taxels), pressure, np.nan)
        return pressure.reshape(*lead, *shape)

    def beyond_full_scale(self, raw: Any) -> np.ndarray:
        """Which taxels read at or beyond their full-scale plate reading (saturated).

        `apply` returns full scale there: the load beyond it is lost, and a total force
        summed over such taxels is too small.

        Parameters
        ----------
        raw : array_like, shape (..., *shape)
            One or more raw frames of the sensor.

        Returns
        -------
        numpy.ndarray of bool, shape (..., *shape)
            False at the taxels `valid` excludes.

        Examples
        --------
        >>> from taxel.sensor import calibrate, make_sensor
        >>> sensor = make_sensor("resistive16")
        >>> calibration = calibrate(sensor)
        >>> plate = np.full(sensor.load_grid.shape, 2 * sensor.full_scale)
        >>> int(calibration.beyond_full_scale(sensor.frame_from_pressure(plate).raw).sum())
        256
        >>> int(calibration.beyond_full_scale(calibration.readings[0]).sum())  # no load
        0
        """
        raw = self._frames(raw)
        oriented = self.direction * raw
        full = self.direction * self.readings[-1]
        return (oriented >= full) & self.valid

    def below_rest(self, raw: Any) -> np.ndarray:
        """Which taxels read below their no-load reading by more than noise explains.

        No load on the cover reads lower than no load: such a reading is of another sensor,
        another unit, or no frame of raw codes at all, and `apply` turns it into a negative
        pressure (it continues the response's slope past no load). A taxel is flagged when
        its reading lies past its no-load one, on the side away from load, by more than
        five times its noise (at least the median taxel's: a few repeats of an 8-bit camera
        may all read one level) and more than 1 % of its span from no load to full scale.

        Parameters
        ----------
        raw : array_like, shape (..., *shape)
            One or more raw frames of the sensor.

        Returns
        -------
        numpy.ndarray of bool, shape (..., *shape)
            False at the taxels `valid` excludes.

        Examples
        --------
        >>> from taxel.sensor import calibrate, make_sensor
        >>> calibration = calibrate(make_sensor("resistive16"))
        >>> int(calibration.below_rest(np.full((16, 16), -50)).sum())
        256
        >>> int(calibration.below_rest(calibration.readings[0]).sum())  # no load
        0
        """
        raw = self._frames(raw)
        rest = self.direction * self.readings[0]
        span = self.direction * self.readings[-1] - rest
        typical = np.median(self.noise[self.valid]) if np.any(self.valid) else 0.0
        margin = np.maximum(5 * np.maximum(self.noise, typical), 0.01 * span)
        return (self.direction * raw < rest - margin) & self.valid

    def _frames(self, raw: Any) -> np.ndarray:
        """`raw` as finite frames whose shape ends in the calibrated one (else ValueError)."""
        raw = as_finite_array("raw", raw)
        shape = self.shape
        if raw.shape[raw.ndim - len(shape) :] != shape:
            raise ValueError(f"`raw` must end in the calibrated shape {shape}, got {raw.shape}")
        return raw

    @cached_property
    def _rest_slope(self) -> np.ndarray:
        """Pressure per unit reading at no load, per taxel [Pa per raw unit]; 0 if flat.

        The secant over the first 5 % of the range at least: the slope of one short
        segment between two noisy (or 8-bit) knots could be off many times over.
        """
        knots = self.direction * self.readings.reshape(len(self.pressures), -1)
        span = max(1, int(np.searchsorted(self.pressures, 0.05 * self.pressures[-1])))
        slope = (knots[span] - knots[0]) / (self.pressures[span] - self.pressures[0])
        return np.divide(1.0, slope, out=np.zeros_like(slope), where=slope > 0)

    def felt_pressure(self, raw: Any, *, clip: bool = False) -> np.ndarray:
        """Pressure each taxel feels: the normal stress at its depth [Pa], NaN if excluded.

        `apply` times `felt_fraction`. For cells that sense the stress at their depth
        (resistive, FTIR, microbend, capacitive cells with their own modulus) this is their
        input whatever the load: what a reconstruction's forward model predicts. For
        sensors of the cover's strain or surface displacement it holds for flat loads only.
        For microbend fibres it is the mean along each fibre.
        """
        fraction = 1.0 if self.felt_fraction is None else self.felt_fraction
        return self.apply(raw, clip=clip) * fraction

    # ----------------------------------------------------------------------- files
    def save(self, path: str | os.PathLike[str], *, overwrite: bool = False) -> Path:
        """Write the calibration to a ``.npz`` file; refuse to replace one unless told.

        Examples
        --------
        >>> import tempfile, pathlib
        >>> from taxel.sensor import calibrate, make_sensor
        >>> calibration = calibrate(make_sensor("capacitive4x4"), n_levels=6)
        >>> path = pathlib.Path(tempfile.mkdtemp()) / "cap.npz"
        >>> _ = calibration.save(path)
        >>> Calibration.load(path).sensor_name
        'capacitive4x4'
        >>> calibration.save(path)
        Traceback (most recent call last):
        ...
        FileExistsError: ... exists; pass overwrite=True to replace it
        """
        path = Path(path)
        if path.suffix != ".npz":
            raise ValueError(f"`path` must end in .npz, got {str(path)!r}")
        if path.exists() and not overwrite:
            raise FileExistsError(
                f"`path` {str(path)!r} exists; pass overwrite=True to replace it"
            )
        meta = {
            "format": _FORMAT,
            "sensor_name": self.sensor_name,
            "full_scale": self.full_scale,
            "repeats": self.repeats,
        }
        # written beside the target and renamed once complete: a failed write (a full
        # disk) leaves the old file as it was and no half-written one (taxel.io does the
        # same for the other layers; the sensor layer cannot import it)
        partial = path.with_name(f".{path.name}.partial")
        try:
            with open(partial, "wb") as stream:
                np.savez(
                    stream,
                    meta=np.array(json.dumps(meta)),
                    pressures=self.pressures,
                    readings=self.readings,
                    unresponsive=self.unresponsive,
                    pinned=self.pinned,
                    noise=self.noise,
                    felt_fraction=(
                        np.ones(self.shape) if self.felt_fraction is None else self.felt_fraction
                    ),
                )
            os.replace(partial, path)
        except OSError as error:  # named by the file asked for, not the temporary one
            raise OSError(error.errno, error.strerror, str(path)) from None
        finally:
            partial.unlink(missing_ok=True)
        return path

    @classmethod
    def load(cls, path: str | os.PathLike[str]) -> Calibration:
        """Read a calibration written by `save`; a wrong or damaged file raises ValueError.

        The error names the file. Each array's header is checked against the bytes the
        archive holds before the array is read, so that a corrupt one claiming a huge shape
        is refused rather than allocated (a MemoryError).
        """
        path = Path(path)
        if path.is_dir():
            raise ValueError(f"{path}: a folder, not a taxel calibration file")
        if not path.is_file():
            raise FileNotFoundError(f"no such file: {path}")
        try:
            with path.open("rb") as handle:  # (each header checked before numpy allocates)
                arrays = read_npz(handle)
        except (OSError, ValueError) as error:
            raise ValueError(f"{path}: not a taxel calibration file ({error})") from None
        missing = sorted(_ARRAYS - set(arrays))
        if missing:
            held = ", ".join(sorted(arrays)) or "no array"
            raise ValueError(
                f"{path}: not a taxel calibration file: it lacks the array(s) "
                f"{', '.join(missing)} that `taxel calibrate` writes (it holds {held})"
            )
        try:
            meta = json.loads(str(arrays.pop("meta")))
        except ValueError as error:
            raise ValueError(f"{path}: not a taxel calibration file ({error})") from None
        if not isinstance(meta, dict) or meta.get("format") != _FORMAT:
            format_tag = meta.get("format") if isinstance(meta, dict) else None
            raise ValueError(f"{path}: not a taxel calibration file (format {format_tag})")
        lacking = [key for key in ("sensor_name", "full_scale", "repeats") if key not in meta]
        if lacking:
            raise ValueError(
                f"{path}: not a taxel calibration file: its meta lacks {', '.join(lacking)}"
            )
        readings, pressures = arrays["readings"], arrays["pressures"]
        shape = readings.shape[1:]
        if readings.ndim < 2 or pressures.shape != readings.shape[:1]:
            raise ValueError(f"{path}: readings {readings.shape} do not match {pressures.shape}")
        for name in ("unresponsive", "pinned", "noise", "felt_fraction"):
            if arrays[name].shape != shape:
                raise ValueError(f"{path}: `{name}` has shape {arrays[name].shape}, not {shape}")
        for name in ("pressures", "readings", "noise", "felt_fraction"):
            if not np.issubdtype(arrays[name].dtype, np.number) or not np.all(
                np.isfinite(arrays[name])
            ):
                raise ValueError(f"{path}: `{name}` must hold finite numbers")
        if pressures.size < 2 or np.any(np.diff(pressures) <= 0):
            raise ValueError(f"{path}: `pressures` must rise strictly, got {pressures.tolist()}")
        unresponsive = arrays["unresponsive"].astype(bool)
        pinned = arrays["pinned"].astype(bool)
        full_scale, repeats = meta["full_scale"], meta["repeats"]
        if not is_json_number(full_scale) or not math.isfinite(full_scale) or full_scale <= 0:
            raise ValueError(
                f"{path}: its meta's full_scale must be a pressure > 0 [Pa], got {full_scale!r}"
            )
        if not isinstance(repeats, int) or isinstance(repeats, bool) or repeats < 1:
            raise ValueError(
                f"{path}: its meta's repeats must be a whole number >= 1, got {repeats!r}"
            )
        return cls(
            sensor_name=str(meta["sensor_name"]),
            pressures=pressures.astype(float),
            readings=readings.astype(float),
            valid=~(unresponsive | pinned),
            unresponsive=unresponsive,
            pinned=pinned,
            noise=arrays["noise"].astype(float),
            full_scale=float(full_scale),
            repeats=repeats,
            felt_fraction=arrays["felt_fraction"].astype(float),
        )


def check_calibration(calibration: Any, sensor: TactileSensor) -> Calibration:
    """Raise unless `calibration` is a Calibration whose frames have the sensor's shape."""
    if not isinstance(calibration, Calibration):
        raise TypeError(f"`calibration` must be a Calibration, got {calibration!r}")
    shape = np.shape(sensor.read(np.zeros(sensor.shape)))
    if calibration.shape != shape:
        raise ValueError(
            f"`calibration` of {calibration.sensor_name!r} reads frames of shape "
            f"{calibration.shape}, but {sensor.name!r} gives {shape}"
        )
    return calibration
