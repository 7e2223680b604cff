"""The public namespace of taxel.active is pinned: a change here is an API change."""

import taxel.active


def test_public_names():
    assert sorted(taxel.active.__all__) == [
        "Box",
        "CrossValidation",
        "DEFAULT_BAND_EDGES",
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
    for name in taxel.active.__all__:
        assert name in taxel.active.__doc__
