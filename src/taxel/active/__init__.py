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

Edge radius from a light and a firm press (empirical table, JSON)
-----------------------------------------------------------------
EdgeRadius, EdgeRadiusResult, measure_edge_radius, make_edge, edge_cross_section,
EdgeCrossSection, SECTION_DESCRIPTORS, EdgeRadiusTable, fit_edge_radius_table,
build_edge_radius_table, DEFAULT_EDGE_RADII

Deformation and stiffness (touch, light and firm press)
-------------------------------------------------------
Deformation, DeformationResult, measure_deformation, make_deformation_object,
DEFORMATION_OBJECTS, make_block, PadCalibration, calibrate_pad, core_area

Recognition against a library of object models (up to three touches)
--------------------------------------------------------------------
Recognition, RecognitionResult, recognize_object, ModelLibrary, build_model_library,
make_model, MODEL_NAMES, describe_models, TOUCH_FEATURES
"""

from taxel.active._deformable_objects import (
    DEFORMATION_OBJECTS,
    make_block,
    make_deformation_object,
)
from taxel.active._deformation import Deformation, DeformationResult, measure_deformation
from taxel.active._edge_radius import (
    DEFAULT_EDGE_RADII,
    EdgeRadius,
    EdgeRadiusResult,
    build_edge_radius_table,
    make_edge,
    measure_edge_radius,
)
from taxel.active._edge_section import SECTION_DESCRIPTORS, EdgeCrossSection, edge_cross_section
from taxel.active._edge_table import EdgeRadiusTable, fit_edge_radius_table
from taxel.active._finger import SimulatedFinger
from taxel.active._model_library import ModelLibrary
from taxel.active._object_library import MODEL_NAMES, describe_models, make_model
from taxel.active._pad_calibration import PadCalibration, calibrate_pad, core_area
from taxel.active._probe import Probe, ProbeReading
from taxel.active._procedure import ProcedureStep, step_from_reading
from taxel.active._recognition import Recognition, RecognitionResult
from taxel.active._recognize import build_model_library, recognize_object
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
from taxel.active._touch_features import TOUCH_FEATURES

__all__ = [
    "DEFAULT_BAND_EDGES",
    "DEFAULT_EDGE_RADII",
    "DEFORMATION_OBJECTS",
    "MODEL_NAMES",
    "SECTION_DESCRIPTORS",
    "TOUCH_FEATURES",
    "Box",
    "CrossValidation",
    "Deformation",
    "DeformationResult",
    "EdgeCrossSection",
    "EdgeRadius",
    "EdgeRadiusResult",
    "EdgeRadiusTable",
    "ModelLibrary",
    "PadCalibration",
    "Probe",
    "ProbeReading",
    "ProcedureStep",
    "ProfileObject",
    "Recognition",
    "RecognitionResult",
    "SceneObject",
    "SimulatedFinger",
    "TextureClassifier",
    "TextureSignature",
    "band_power",
    "build_edge_radius_table",
    "build_model_library",
    "calibrate_pad",
    "core_area",
    "cross_validate_texture",
    "describe_models",
    "edge_cross_section",
    "fit_edge_radius_table",
    "fit_texture_classifier",
    "make_ball",
    "make_block",
    "make_deformation_object",
    "make_edge",
    "make_model",
    "measure_deformation",
    "measure_edge_radius",
    "recognize_object",
    "spatial_power_spectrum",
    "step_from_reading",
    "texture_features",
    "texture_signature",
]
