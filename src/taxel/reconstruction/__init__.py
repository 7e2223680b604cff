"""Reconstruction: recover pressure (and indenter shape) from taxel readings."""

from taxel.reconstruction._operator import SensorOperator, forward_operator
from taxel.reconstruction._spec import (
    FORWARD_MODEL_PRESETS,
    ForwardModelSpec,
    as_forward_model_spec,
    forward_model_preset,
)

__all__ = [
    "FORWARD_MODEL_PRESETS",
    "ForwardModelSpec",
    "SensorOperator",
    "as_forward_model_spec",
    "forward_model_preset",
    "forward_operator",
]
