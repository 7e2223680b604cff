"""Active touch: sensing that moves the sensor over the object (Ellis seed, section 2.2).

Robot side: scene, probe interface, simulated finger
----------------------------------------------------
SceneObject, ProfileObject, Box, make_ball, Probe, ProbeReading, SimulatedFinger,
ProcedureStep, step_from_reading

Surface normal, planarity, edges and corners by probing
-------------------------------------------------------
calibrate_pad, PadCalibration, estimate_contact_point, ContactPoint, fit_plane,
PlaneProbing, probe_plane, PlaneEstimate, CornerProbing, locate_corner, CornerEstimate,
box_corner_frame; simulated trials with known answers: plane_probing_trial, PlaneTrial,
corner_probing_trial, CornerTrial

Slip: incipient and gross, from pattern displacement and a PVDF array
--------------------------------------------------------------------
SlipDetector, detect_slip, SlipDetection, SlipEvent; hold-then-slip simulation:
SlipScenario, random_slip_scenario, simulate_slip, SlipSequence, slip_sensors,
SLIP_DISPLACEMENT, ANNULUS_GROWTH; scoring: slip_trials, score_slip_detection,
evaluate_slip_detection, SlipEvaluation; thresholds for a false-alarm budget:
calibrate_slip_detector, SlipCalibration

Texture from sliding (spatial-frequency signature)
--------------------------------------------------
TextureSliding, slide_texture, TextureSlide, SLIDING_BAND_EDGES, Grating, SampledProfile;
texture_speed_study, TextureSpeedStudy, texture_surface (speed invariance, classification);
texture_signature, TextureSignature, spatial_power_spectrum, band_power, texture_features,
DEFAULT_BAND_EDGES

Texture classification (k nearest neighbours, JSON models)
---------------------------------------------------------
fit_texture_classifier, TextureClassifier, cross_validate_texture, CrossValidation
"""

from taxel.active._contact_point import (
    ContactPoint,
    PadCalibration,
    calibrate_pad,
    estimate_contact_point,
)
from taxel.active._finger import SimulatedFinger
from taxel.active._probe import Probe, ProbeReading
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
from taxel.active._scene import Box, ProfileObject, SceneObject, make_ball
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
from taxel.active._texture_study import (
    TextureSpeedStudy,
    texture_speed_study,
    texture_surface,
)

__all__ = [
    "ANNULUS_GROWTH",
    "DEFAULT_BAND_EDGES",
    "SLIDING_BAND_EDGES",
    "SLIP_DISPLACEMENT",
    "Box",
    "ContactPoint",
    "CornerEstimate",
    "CornerProbing",
    "CornerTrial",
    "CrossValidation",
    "Grating",
    "PadCalibration",
    "PlaneEstimate",
    "PlaneProbing",
    "PlaneTrial",
    "Probe",
    "ProbeReading",
    "ProcedureStep",
    "ProfileObject",
    "SampledProfile",
    "SceneObject",
    "SimulatedFinger",
    "SlipCalibration",
    "SlipDetection",
    "SlipDetector",
    "SlipEvaluation",
    "SlipEvent",
    "SlipScenario",
    "SlipSequence",
    "TextureClassifier",
    "TextureSignature",
    "TextureSlide",
    "TextureSliding",
    "TextureSpeedStudy",
    "band_power",
    "box_corner_frame",
    "calibrate_pad",
    "calibrate_slip_detector",
    "corner_probing_trial",
    "cross_validate_texture",
    "detect_slip",
    "estimate_contact_point",
    "evaluate_slip_detection",
    "fit_plane",
    "fit_texture_classifier",
    "locate_corner",
    "make_ball",
    "plane_probing_trial",
    "probe_plane",
    "random_slip_scenario",
    "score_slip_detection",
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
