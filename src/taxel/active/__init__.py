"""Active touch: sensing that moves the sensor over the object (Ellis seed, section 2.2).

Robot side: scene, probe interface, simulated finger
----------------------------------------------------
SceneObject, ProfileObject, Box, make_ball, make_hollow_ball, Probe, ProbeReading, NoContactError,
SimulatedFinger, finger_force_limit, ProcedureStep, step_from_reading

Surface normal, planarity, edges and corners by probing
-------------------------------------------------------
calibrate_contact_points, ContactPointCalibration, estimate_contact_point, ContactPoint, fit_plane,
PlaneProbing, probe_plane, PlaneEstimate, CornerProbing, locate_corner, CornerEstimate,
box_corner_frame; simulated trials with known answers: plane_probing_trial, PlaneTrial,
corner_probing_trial, CornerTrial

Slip: incipient and gross, from pattern displacement and a PVDF array
--------------------------------------------------------------------
SlipDetector, detect_slip, SlipDetection, SlipEvent; online, one frame at a time in a
sensor loop: SlipMonitor; hold-then-slip simulation:
SlipScenario, random_slip_scenario, simulate_slip, SlipSequence, slip_sensors,
SLIP_DISPLACEMENT, ANNULUS_GROWTH; scoring: slip_trials, score_slip_detection,
evaluate_slip_detection, SlipEvaluation; thresholds for a false-alarm budget:
calibrate_slip_detector, SlipCalibration

Texture from sliding (spatial-frequency signature)
--------------------------------------------------
TextureSliding, slide_texture, TextureSlide, SLIDING_BAND_EDGES, Grating, SampledProfile;
texture_speed_study, TextureSpeedStudy, texture_surface (speed invariance, classification);
texture_signature, TextureSignature, spatial_power_spectrum, band_power, texture_features,
DEFAULT_BAND_EDGES, NORMALIZATIONS; independence of the load: load_shares,
remove_load_coherent

Texture classification (k nearest neighbours, JSON models)
---------------------------------------------------------
fit_texture_classifier, TextureClassifier, cross_validate_texture, CrossValidation;
settings chosen by cross-validation on training groups only: choose_texture_model,
TextureModelChoice, nested_cross_validate_texture

Edge radius from a light and a firm press (empirical table, JSON)
-----------------------------------------------------------------
EdgeRadius, EdgeRadiusResult, measure_edge_radius, make_edge, edge_cross_section,
EdgeCrossSection, SECTION_DESCRIPTORS, EdgeRadiusTable, fit_edge_radius_table,
build_edge_radius_table, DEFAULT_EDGE_RADII, sharpest_edge_radius, largest_edge_offset

Deformation and stiffness (touch, light and firm press)
-------------------------------------------------------
Deformation, DeformationResult, measure_deformation, deflection_exponent,
make_deformation_object, DEFORMATION_OBJECTS, WALL_THICKNESS, make_block, PadCalibration,
calibrate_pad, core_area

Recognition against a library of object models (up to three touches)
--------------------------------------------------------------------
Recognition, RecognitionResult, recognize_object, ModelLibrary, build_model_library,
make_model, MODEL_NAMES, describe_models, TOUCH_FEATURES, DESCRIPTOR_NAMES (the features a
library's templates hold: the first touch's and the least and most of the other two)
"""

from taxel.active._contact_point import (
    ContactPoint,
    ContactPointCalibration,
    calibrate_contact_points,
    estimate_contact_point,
)
from taxel.active._deformable_objects import (
    DEFORMATION_OBJECTS,
    make_block,
    make_deformation_object,
)
from taxel.active._deformation import (
    Deformation,
    DeformationResult,
    deflection_exponent,
    measure_deformation,
)
from taxel.active._edge_radius import (
    DEFAULT_EDGE_RADII,
    EdgeRadius,
    EdgeRadiusResult,
    build_edge_radius_table,
    largest_edge_offset,
    make_edge,
    measure_edge_radius,
    sharpest_edge_radius,
)
from taxel.active._edge_section import SECTION_DESCRIPTORS, EdgeCrossSection, edge_cross_section
from taxel.active._edge_table import EdgeRadiusTable, fit_edge_radius_table
from taxel.active._finger import SimulatedFinger, finger_force_limit
from taxel.active._load_normalization import load_shares, remove_load_coherent
from taxel.active._model_library import ModelLibrary
from taxel.active._object_library import MODEL_NAMES, describe_models, make_model
from taxel.active._pad_calibration import PadCalibration, calibrate_pad, core_area
from taxel.active._probe import NoContactError, Probe, ProbeReading
from taxel.active._probe_corner import (
    CornerEstimate,
    CornerProbing,
    box_corner_frame,
    locate_corner,
)
from taxel.active._probe_plane import PlaneEstimate, PlaneProbing, fit_plane, probe_plane
from taxel.active._probing_trials import (
    CornerTrial,
    PlaneTrial,
    corner_probing_trial,
    plane_probing_trial,
)
from taxel.active._procedure import ProcedureStep, step_from_reading
from taxel.active._recognition import Recognition, RecognitionResult
from taxel.active._recognize import DESCRIPTOR_NAMES, build_model_library, recognize_object
from taxel.active._scene import Box, ProfileObject, SceneObject, make_ball, make_hollow_ball
from taxel.active._sliding_texture import (
    SLIDING_BAND_EDGES,
    Grating,
    SampledProfile,
    TextureSlide,
    TextureSliding,
    slide_texture,
)
from taxel.active._slip import SlipDetection, SlipDetector, SlipEvent, detect_slip
from taxel.active._slip_evaluation import (
    SlipCalibration,
    SlipEvaluation,
    calibrate_slip_detector,
    evaluate_slip_detection,
    score_slip_detection,
    slip_trials,
)
from taxel.active._slip_monitor import SlipMonitor
from taxel.active._slip_simulation import (
    ANNULUS_GROWTH,
    SLIP_DISPLACEMENT,
    SlipScenario,
    SlipSequence,
    random_slip_scenario,
    simulate_slip,
    slip_sensors,
)
from taxel.active._spatial_spectrum import band_power, spatial_power_spectrum
from taxel.active._texture_classifier import TextureClassifier, fit_texture_classifier
from taxel.active._texture_signature import (
    DEFAULT_BAND_EDGES,
    NORMALIZATIONS,
    TextureSignature,
    texture_features,
    texture_signature,
)
from taxel.active._texture_study import (
    TextureSpeedStudy,
    texture_speed_study,
    texture_surface,
)
from taxel.active._texture_validation import (
    CrossValidation,
    TextureModelChoice,
    choose_texture_model,
    cross_validate_texture,
    nested_cross_validate_texture,
)
from taxel.active._touch_features import TOUCH_FEATURES

__all__ = [
    "ANNULUS_GROWTH",
    "DEFAULT_BAND_EDGES",
    "DEFAULT_EDGE_RADII",
    "DEFORMATION_OBJECTS",
    "DESCRIPTOR_NAMES",
    "MODEL_NAMES",
    "NORMALIZATIONS",
    "SECTION_DESCRIPTORS",
    "SLIDING_BAND_EDGES",
    "SLIP_DISPLACEMENT",
    "TOUCH_FEATURES",
    "WALL_THICKNESS",
    "Box",
    "ContactPoint",
    "ContactPointCalibration",
    "CornerEstimate",
    "CornerProbing",
    "CornerTrial",
    "CrossValidation",
    "Deformation",
    "DeformationResult",
    "EdgeCrossSection",
    "EdgeRadius",
    "EdgeRadiusResult",
    "EdgeRadiusTable",
    "Grating",
    "ModelLibrary",
    "NoContactError",
    "PadCalibration",
    "PlaneEstimate",
    "PlaneProbing",
    "PlaneTrial",
    "Probe",
    "ProbeReading",
    "ProcedureStep",
    "ProfileObject",
    "Recognition",
    "RecognitionResult",
    "SampledProfile",
    "SceneObject",
    "SimulatedFinger",
    "SlipCalibration",
    "SlipDetection",
    "SlipDetector",
    "SlipEvaluation",
    "SlipEvent",
    "SlipMonitor",
    "SlipScenario",
    "SlipSequence",
    "TextureClassifier",
    "TextureModelChoice",
    "TextureSignature",
    "TextureSlide",
    "TextureSliding",
    "TextureSpeedStudy",
    "band_power",
    "box_corner_frame",
    "build_edge_radius_table",
    "build_model_library",
    "calibrate_contact_points",
    "calibrate_pad",
    "calibrate_slip_detector",
    "choose_texture_model",
    "core_area",
    "corner_probing_trial",
    "cross_validate_texture",
    "deflection_exponent",
    "describe_models",
    "detect_slip",
    "edge_cross_section",
    "estimate_contact_point",
    "evaluate_slip_detection",
    "finger_force_limit",
    "fit_edge_radius_table",
    "fit_plane",
    "fit_texture_classifier",
    "largest_edge_offset",
    "load_shares",
    "locate_corner",
    "make_ball",
    "make_block",
    "make_deformation_object",
    "make_edge",
    "make_hollow_ball",
    "make_model",
    "measure_deformation",
    "measure_edge_radius",
    "nested_cross_validate_texture",
    "plane_probing_trial",
    "probe_plane",
    "random_slip_scenario",
    "recognize_object",
    "remove_load_coherent",
    "score_slip_detection",
    "sharpest_edge_radius",
    "simulate_slip",
    "slide_texture",
    "slip_sensors",
    "slip_trials",
    "spatial_power_spectrum",
    "step_from_reading",
    "texture_features",
    "texture_signature",
    "texture_speed_study",
    "texture_surface",
]
