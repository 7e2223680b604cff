"""Reconstruction: pressure (and indenter shape) from taxel readings (chapter seed, 25.2).

Taxels at depth d read zeta = T F (eq. 25.5): the inverse problem is ill-posed and needs
regularization. Everything here is built once per sensor and reused frame after frame.

Forward model of a sensor
    ForwardModelSpec, forward_model_preset, FORWARD_MODEL_PRESETS, as_forward_model_spec,
    spec_from_sensor, forward_operator, SensorOperator,
    calibrated_readings (raw frames through a calibration, in the forward model's quantity)
Solvers (class: setup once, then solve frame after frame; function: one call)
    TikhonovSolver (Tikhonov of order 0, 1, 2 and truncated SVD),
    ADMMSolver (non-negative Tikhonov, non-negative total variation),
    SupportSolver (non-negative least squares on the support of a Tikhonov estimate:
    force and centroid of a contact), nonneg_quadratic,
    reconstruct, naive_inverse, solver_for, METHODS
Parameter choice
    RULES ("gcv", "lcurve", "discrepancy"; the default is "discrepancy" with the noise
    estimated from the frame), LARGEST_REGULARIZATION (the largest lambda given),
    estimate_noise_level, ParameterCurve, lcurve_curvature,
    estimate_noise (Wahba's GCV-based estimator, kept for comparison)
Results
    ReconstructionResult, ShapeResult
Shape recovery (displacement-sensing sensors)
    recover_shape

Glossary (additions to docs/nomenclature.md): ``regularization`` lambda [-] (relative: the
penalty is lambda^2 |A|^2/|L|^2 |L x|^2) or, for total variation, mu [Pa];
``residual_norm`` |A x - b| [reading units]; ``solution_norm`` |L x|; ``noise_level`` sigma
[reading units]; ``oversampling`` k [-] (load cells per taxel along each axis);
``taxel_pitch`` [m]; ``load_pitch`` = taxel_pitch / k [m].
"""

from taxel.reconstruction._admm import ADMMSolver
from taxel.reconstruction._beyond import extend_readings
from taxel.reconstruction._calibrated import calibrated_readings
from taxel.reconstruction._choice import RULES, ParameterCurve, lcurve_curvature
from taxel.reconstruction._frames import LARGEST_REGULARIZATION
from taxel.reconstruction._operator import SensorOperator, forward_operator
from taxel.reconstruction._reconstruct import (
    METHODS,
    estimate_noise_level,
    naive_inverse,
    reconstruct,
    solver_for,
)
from taxel.reconstruction._restricted import nonneg_quadratic
from taxel.reconstruction._result import ReconstructionResult
from taxel.reconstruction._shape import ShapeResult, recover_shape
from taxel.reconstruction._spec import (
    FORWARD_MODEL_PRESETS,
    ForwardModelSpec,
    as_forward_model_spec,
    forward_model_preset,
    spec_from_sensor,
)
from taxel.reconstruction._support import SupportSolver
from taxel.reconstruction._tikhonov import TikhonovSolver, estimate_noise

__all__ = [
    "FORWARD_MODEL_PRESETS",
    "LARGEST_REGULARIZATION",
    "METHODS",
    "RULES",
    "ADMMSolver",
    "ForwardModelSpec",
    "ParameterCurve",
    "ReconstructionResult",
    "SensorOperator",
    "ShapeResult",
    "SupportSolver",
    "TikhonovSolver",
    "as_forward_model_spec",
    "calibrated_readings",
    "estimate_noise",
    "estimate_noise_level",
    "extend_readings",
    "forward_model_preset",
    "forward_operator",
    "lcurve_curvature",
    "naive_inverse",
    "nonneg_quadratic",
    "reconstruct",
    "recover_shape",
    "solver_for",
    "spec_from_sensor",
]
