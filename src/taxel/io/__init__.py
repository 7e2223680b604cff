"""Readers and writers of tactile frames, sequences and recordings.

Every reader validates the file: a missing file raises `FileNotFoundError` naming it; an
empty, truncated, ragged, corrupt or non-numeric one raises `ValueError` naming the file and,
for text, the line.

Frames and sequences (npy, npz, png, tif, csv)
----------------------------------------------
read_frame, read_sequence, TactileSequence; read_array (any .npy as stored, its header
checked against the file before anything is allocated); read_archive (every array of an
.npz, each checked so)

Writing (never over an existing file unless asked; never over an input)
-------------------------------------------------------------------------
write_frame, write_text, write_files (several files, all or none), check_new_file

FabricSlide recordings (capacitive finger sliding over fabrics)
---------------------------------------------------------------
read_fabricslide, FabricSlideRecording, parse_fabricslide_name, list_fabricslide_files,
CPM_FINGER, cpm_finger_sensor (the CPM-Finger as a sensor model), CPM_FINGER_ASSUMED
"""

from taxel.io._arrays import read_archive, read_array
from taxel.io._cpm_finger import CPM_FINGER_ASSUMED, cpm_finger_sensor
from taxel.io._fabricslide import (
    CPM_FINGER,
    FabricSlideRecording,
    list_fabricslide_files,
    parse_fabricslide_name,
    read_fabricslide,
)
from taxel.io._frames import TactileSequence, read_frame, read_sequence
from taxel.io._writers import check_new_file, write_files, write_frame, write_text

__all__ = [
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
