r"""Reader of the FabricSlide recordings (a capacitive finger sliding over fabrics).

FabricSlide (Wang et al. 2022, doi:10.3389/fnbot.2022.808222, MIT licence) holds csv
files named ``<Fabric>_F<setting>_V<velocity>mmps_<repetition>.csv`` with the columns
``timestamp, proximity1, proximity2, channel1, ..., channel16`` of the CPM-Finger, a
finger-shaped capacitive sensor with 16 taxels and two proximity channels. This module maps
them onto `taxel` names and SI units.
"""

from __future__ import annotations

import os
import re
from dataclasses import dataclass, field
from pathlib import Path
from types import MappingProxyType
from typing import Any

import numpy as np

from taxel.io._table import check_file, read_numeric_table

__all__ = [
    "CPM_FINGER",
    "FabricSlideRecording",
    "list_fabricslide_files",
    "parse_fabricslide_name",
    "read_fabricslide",
]

#: What the FabricSlide README and the paper's abstract say about the sensor; the sensor
#: layer will turn it into a sensor object. Facts not published there (taxel positions,
#: pitch, cover) are None rather than guessed.
CPM_FINGER: MappingProxyType[str, Any] = MappingProxyType(
    {
        "name": "CPM-Finger",
        "transduction": "capacitive",
        "form": "finger-shaped",
        "n_taxels": 16,
        "n_proximity_channels": 2,
        "reading_unit": "raw integer counts",
        "taxel_positions": None,
        "source": "FabricSlide README; Wang et al., Front. Neurorobot. 16:808222 (2022)",
    }
)

_NAME = re.compile(
    r"^(?P<fabric>[A-Za-z][A-Za-z0-9]*)_F(?P<setting>\d+)"
    r"_V(?P<velocity>[-+]?\d+(?:\.\d+)?)mmps_(?P<repetition>\d+)\.csv$"
)
_TIME_COLUMN = "timestamp"
_PROXIMITY_COLUMNS = ("proximity1", "proximity2")
_TAXEL_COLUMNS = tuple(f"channel{index}" for index in range(1, 17))
_SECONDS_PER_TIMESTAMP = 1e-3


def parse_fabricslide_name(name: str | os.PathLike[str]) -> dict[str, Any]:
    """Split a FabricSlide file name into its fields.

    Parameters
    ----------
    name : str or path-like
        ``<Fabric>_F<setting>_V<velocity>mmps_<repetition>.csv``; a leading folder is ignored.

    Returns
    -------
    dict
        ``fabric`` (str), ``force_setting`` (int, the controller's setting, see
        `FabricSlideRecording`), ``sliding_velocity`` (float [m/s], sign = direction) and
        ``repetition`` (int).

    Raises
    ------
    ValueError
        When the name does not follow the pattern, or the velocity is zero.

    Examples
    --------
    >>> parse_fabricslide_name("data/Linen_F150_V-20mmps_0.csv")
    {'fabric': 'Linen', 'force_setting': 150, 'sliding_velocity': -0.02, 'repetition': 0}
    """
    base = Path(name).name
    match = _NAME.match(base)
    if match is None:
        raise ValueError(
            f"{base!r} is not a FabricSlide file name "
            "(expected <Fabric>_F<setting>_V<velocity>mmps_<repetition>.csv)"
        )
    velocity = float(match["velocity"]) * 1e-3
    if velocity == 0:
        raise ValueError(f"{base!r}: the sliding velocity must not be zero")
    return {
        "fabric": match["fabric"],
        "force_setting": int(match["setting"]),
        "sliding_velocity": velocity,
        "repetition": int(match["repetition"]),
    }


@dataclass(frozen=True)
class FabricSlideRecording:
    """One FabricSlide recording in `taxel` names and units.

    Attributes
    ----------
    path : str
        The file it was read from.
    fabric : str
        The fabric class, from the file name (e.g. ``'Denim'``).
    force_setting : int
        The normal-force setting ``F<setting>`` of the file name, as the authors' controller
        received it. It is not in newtons: in every file of repetition 0 the mean of the 16
        readings lies within -8 % to +14 % of the setting, so it behaves as a target for
        the mean reading [counts].
    sliding_velocity : float
        Commanded sliding velocity [m/s]; the sign is the direction of sliding.
    repetition : int
        Repetition index ``_<n>`` of the condition.
    time : numpy.ndarray
        (n_steps,) time since the first row [s].
    readings : numpy.ndarray
        (n_steps, 16) raw counts of ``channel1..channel16``.
    proximity : numpy.ndarray
        (n_steps, 2) raw counts of ``proximity1, proximity2``.
    start_time : float
        Timestamp of the first row [s] on the logger's clock.
    sensor_description : mapping
        What is known of the sensor, `CPM_FINGER`; a place for the sensor layer.
    """

    path: str
    fabric: str
    force_setting: int
    sliding_velocity: float
    repetition: int
    time: np.ndarray
    readings: np.ndarray
    proximity: np.ndarray
    start_time: float
    sensor_description: MappingProxyType[str, Any] = field(
        default_factory=lambda: CPM_FINGER, repr=False
    )

    @property
    def n_steps(self) -> int:
        """Number of rows (time steps)."""
        return int(self.time.shape[0])

    @property
    def sampling_rate(self) -> float:
        """Mean sampling rate [Hz]: steps per second over the whole recording."""
        return float((self.n_steps - 1) / (self.time[-1] - self.time[0]))


def read_fabricslide(path: str | os.PathLike[str]) -> FabricSlideRecording:
    r"""Read one FabricSlide csv file.

    Parameters
    ----------
    path : str or path-like
        ``<Fabric>_F<setting>_V<velocity>mmps_<repetition>.csv``.

    Returns
    -------
    FabricSlideRecording

    Raises
    ------
    FileNotFoundError
        When `path` does not exist.
    ValueError
        Naming the file (and line) when the name does not follow the pattern, a column is
        missing, the file is empty, truncated, ragged or non-numeric, it has fewer than two
        rows, or time goes backwards or does not advance.

    Notes
    -----
    Columns are found by their header names, not their order. Timestamps are integer
    milliseconds, ``time = (timestamp - timestamp[0]) * 1e-3`` [s]. The unit was checked on
    the data, not taken on trust: over all 322 files of repetition 0, at 10 to 150 mm/s,
    the duration times the commanded speed is 0.590 to 0.602 m (0.593 m on average): the
    duration is inversely proportional to the speed, as a fixed travel requires. Read as
    milliseconds, it
    equals the timing of the velocity profile in the authors' published acquisition code
    (0.5 / |v| s at constant speed plus two sinusoidal ramps of 0.015 pi / |v| s each:
    (0.5 + 0.03 pi) m / |v| = 0.594 m / |v|). Rows are about 28 ms apart (35 Hz); a few
    consecutive rows share a timestamp (the clock is truncated to whole milliseconds),
    so time is required to be non-decreasing, not increasing.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> folder = pathlib.Path(tempfile.mkdtemp())
    >>> header = "timestamp, proximity1, proximity2, " + ", ".join(
    ...     f"channel{i}" for i in range(1, 17))
    >>> rows = [f"{1000 + 28 * k}, 0, 65535, " + ", ".join(["100"] * 16) for k in range(3)]
    >>> path = folder / "Denim_F150_V-20mmps_0.csv"
    >>> _ = path.write_text("\n".join([header, *rows]) + "\n")
    >>> recording = read_fabricslide(path)
    >>> recording.fabric, recording.force_setting, recording.sliding_velocity
    ('Denim', 150, -0.02)
    >>> recording.time, recording.readings.shape
    (array([0.   , 0.028, 0.056]), (3, 16))
    """
    check_file(path)  # a missing file is missing, whatever its name
    fields = parse_fabricslide_name(path)
    table = read_numeric_table(path, header=True)
    header = [name.lower() for name in table.header or ()]
    wanted = (_TIME_COLUMN, *_PROXIMITY_COLUMNS, *_TAXEL_COLUMNS)
    missing = [name for name in wanted if name not in header]
    if missing:
        raise ValueError(f"{path}, line 1: missing column(s) {', '.join(missing)}")
    if table.values.shape[0] < 2:
        raise ValueError(f"{path}: needs at least two rows, got {table.values.shape[0]}")

    def columns(names: tuple[str, ...]) -> np.ndarray:
        return table.values[:, [header.index(name) for name in names]]

    stamps = table.values[:, header.index(_TIME_COLUMN)]
    steps = np.diff(stamps)
    if np.any(steps < 0):
        index = int(np.argmax(steps < 0)) + 1
        raise ValueError(f"{path}, line {table.line_numbers[index]}: timestamp goes backwards")
    if stamps[-1] == stamps[0]:
        raise ValueError(f"{path}: the timestamps do not advance")
    return FabricSlideRecording(
        path=str(path),
        fabric=fields["fabric"],
        force_setting=fields["force_setting"],
        sliding_velocity=fields["sliding_velocity"],
        repetition=fields["repetition"],
        time=(stamps - stamps[0]) * _SECONDS_PER_TIMESTAMP,
        readings=columns(_TAXEL_COLUMNS),
        proximity=columns(_PROXIMITY_COLUMNS),
        start_time=float(stamps[0] * _SECONDS_PER_TIMESTAMP),
    )


def list_fabricslide_files(directory: str | os.PathLike[str]) -> list[Path]:
    """The FabricSlide csv files directly in `directory`, sorted by name.

    Parameters
    ----------
    directory : str or path-like
        A folder such as ``fabricslide/fabric``.

    Returns
    -------
    list of pathlib.Path

    Raises
    ------
    FileNotFoundError
        When `directory` does not exist.
    ValueError
        When it is not a folder or holds no file named like a FabricSlide recording.
    """
    directory = Path(directory)
    if not directory.exists():
        raise FileNotFoundError(f"no such directory: {directory}")
    if not directory.is_dir():
        raise ValueError(f"{directory}: not a directory")
    found = sorted(path for path in directory.glob("*.csv") if _NAME.match(path.name))
    if not found:
        raise ValueError(f"{directory}: holds no FabricSlide recording (<Fabric>_F*_V*mmps_*.csv)")
    return found
