"""Passive tactile features of one tactile image (Ellis seed, section 2.1).

Works on any tactile image: raw 8- or 16-bit frames, calibrated readings or pressure maps
[Pa], of any array geometry (give the taxel pitch [m]). Given a sensor description instead
(a `taxel.sensor.TactileSensor`), the features also use its cover: they remove sensor
defects narrower than the cover's blur (scratches on an FTIR sensor's glass) and allow for
the blur when they judge sizes. Positions are in the sensor frame ``S`` of `taxel.frames`
(x along columns, y along rows, z out of the sensor), and in the robot's base frame given
the sensor's pose ``T_BS``.

Everything at once
------------------
extract, TactileFeatures, ContactPose

One feature each
----------------
find_contact (Contact, ContactRegion), detect_edges (Edges),
classify_contact (ContactShape, CONTACT_TYPES), detect_holes (HoleReport, Hole),
detect_slots (SlotReport, Slot), contact_plane (ContactPlane),
texture_measures (Texture), fit_line (LineFit), fit_circle (CircleFit). Those that take
an image also take the keywords of `prepare` (`Preparation`: calibrated, smoothing,
baseline, defects, noise, reference) and give what `extract` gives with them.

Helpers
-------
prepare (Prepared): validation, smoothing, noise, baseline and contact mask shared by all;
contact_regions: `find_contact` on an image already prepared;
sensor_coordinates: taxel indices to sensor-frame metres; pitch_pair;
sensor_noise: the noise of a sensor's raw frames (``noise="sensor"``).

Examples
--------
>>> import numpy as np
>>> from taxel.features import extract
>>> y, x = np.mgrid[:32, :32]
>>> pen = np.exp(-((x - 20) ** 2 + (y - 10) ** 2) / 4.0)  # a pen tip at row 10, col 20
>>> features = extract(pen, 0.5e-3)  # a blob 1.7 mm wide at half its peak
>>> features.contact_type, [round(v, 2) for v in features.contact.centroid_index]
('point', [10.0, 20.0])
"""

from taxel.features._contact import Contact, ContactRegion, contact_regions, find_contact
from taxel.features._edges import Edges, detect_edges
from taxel.features._extract import ContactPose, TactileFeatures, extract
from taxel.features._fitting import CircleFit, LineFit, fit_circle, fit_line
from taxel.features._gaps import Hole, HoleReport, Slot, SlotReport
from taxel.features._holes import detect_holes, detect_slots
from taxel.features._image import Preparation, Prepared, prepare
from taxel.features._sensor import pitch_pair, sensor_coordinates, sensor_noise
from taxel.features._shape import CONTACT_TYPES, ContactShape, classify_contact
from taxel.features._surface import ContactPlane, contact_plane
from taxel.features._texture import Texture, texture_measures

__all__ = [
    "CONTACT_TYPES",
    "CircleFit",
    "Contact",
    "ContactPlane",
    "ContactPose",
    "ContactRegion",
    "ContactShape",
    "Edges",
    "Hole",
    "HoleReport",
    "LineFit",
    "Preparation",
    "Prepared",
    "Slot",
    "SlotReport",
    "TactileFeatures",
    "Texture",
    "classify_contact",
    "contact_plane",
    "contact_regions",
    "detect_edges",
    "detect_holes",
    "detect_slots",
    "extract",
    "find_contact",
    "fit_circle",
    "fit_line",
    "pitch_pair",
    "prepare",
    "sensor_coordinates",
    "sensor_noise",
    "texture_measures",
]
