"""The public namespace of taxel.active is pinned: a change here is an API change."""

import taxel.active


def test_public_names():
    assert sorted(taxel.active.__all__) == [
        "Box",
        "ContactPoint",
        "CornerEstimate",
        "CornerProbing",
        "CornerTrial",
        "CrossValidation",
        "DEFAULT_BAND_EDGES",
        "PadCalibration",
        "PlaneEstimate",
        "PlaneProbing",
        "PlaneTrial",
        "Probe",
        "ProbeReading",
        "ProcedureStep",
        "ProfileObject",
        "SceneObject",
        "SimulatedFinger",
        "TextureClassifier",
        "TextureSignature",
        "band_power",
        "box_corner_frame",
        "calibrate_pad",
        "corner_probing_trial",
        "cross_validate_texture",
        "estimate_contact_point",
        "fit_plane",
        "fit_texture_classifier",
        "locate_corner",
        "make_ball",
        "plane_probing_trial",
        "probe_plane",
        "spatial_power_spectrum",
        "step_from_reading",
        "texture_features",
        "texture_signature",
    ]
    for name in taxel.active.__all__:
        assert name in taxel.active.__doc__
