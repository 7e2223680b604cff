"""Active touch: sensing that moves the sensor over the object (Ellis seed, section 2.2).

Robot side: scene, probe interface, simulated finger
----------------------------------------------------
SceneObject, ProfileObject, Box, make_ball, Probe, ProbeReading, SimulatedFinger,
ProcedureStep, step_from_reading

Texture from sliding (spatial-frequency signature)
--------------------------------------------------
texture_signature, TextureSignature, spatial_power_spectrum, band_power, texture_features,
DEFAULT_BAND_EDGES

Texture classification (k nearest neighbours, JSON models)
---------------------------------------------------------
fit_texture_classifier, TextureClassifier, cross_validate_texture, CrossValidation
"""

from taxel.active._finger import SimulatedFinger
from taxel.active._probe import Probe, ProbeReading
from taxel.active._procedure import ProcedureStep, step_from_reading
from taxel.active._scene import Box, ProfileObject, SceneObject, make_ball
from taxel.active._spatial_spectrum import band_power, spatial_power_spectrum
from taxel.active._texture_classifier import (
    CrossValidation,
    TextureClassifier,
    cross_validate_texture,
    fit_texture_classifier,
)
from taxel.active._texture_signature import (
    DEFAULT_BAND_EDGES,
    TextureSignature,
    texture_features,
    texture_signature,
)

__all__ = [
    "DEFAULT_BAND_EDGES",
    "Box",
    "CrossValidation",
    "Probe",
    "ProbeReading",
    "ProcedureStep",
    "ProfileObject",
    "SceneObject",
    "SimulatedFinger",
    "TextureClassifier",
    "TextureSignature",
    "band_power",
    "cross_validate_texture",
    "fit_texture_classifier",
    "make_ball",
    "spatial_power_spectrum",
    "step_from_reading",
    "texture_features",
    "texture_signature",
]
