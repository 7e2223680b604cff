"""The public namespace of taxel.sensor is pinned: a change here is an API change."""

import taxel.sensor


def test_public_names():
    assert sorted(taxel.sensor.__all__) == [
        "ArrayGeometry",
        "Calibration",
        "CalibrationError",
        "Cover",
        "DENSITY_CLASSES",
        "FIELD_NAMES",
        "HarmonRow",
        "HarmonTable",
        "LoadGrid",
        "PRESET_NAMES",
        "ReadingStep",
        "Readout",
        "ReadoutChain",
        "SensorFrame",
        "TactileSensor",
        "TaxelFields",
        "TwoPointResolution",
        "as_sensor",
        "calibrate",
        "calibration_error",
        "density_class",
        "harmon_table",
        "make_sensor",
        "reading_step",
        "taxel_fields",
        "two_point_resolution",
    ]
    for name in taxel.sensor.__all__:
        assert name in taxel.sensor.__doc__
