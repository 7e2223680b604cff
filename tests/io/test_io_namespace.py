"""The public namespace of taxel.io is pinned: a change here is an API change."""

import taxel.io


def test_public_names():
    assert sorted(taxel.io.__all__) == [
        "CPM_FINGER",
        "CPM_FINGER_ASSUMED",
        "FabricSlideRecording",
        "TactileSequence",
        "check_new_file",
        "cpm_finger_sensor",
        "list_fabricslide_files",
        "parse_fabricslide_name",
        "read_archive",
        "read_array",
        "read_fabricslide",
        "read_frame",
        "read_sequence",
        "write_files",
        "write_frame",
        "write_text",
    ]
    for name in taxel.io.__all__:
        assert name in taxel.io.__doc__
