"""Frame and sequence readers: round trips for every format, and every kind of bad file."""

import re

import cv2
import numpy as np
import pytest

from taxel.io import TactileSequence, read_array, read_frame, read_sequence

GRID = np.arange(12, dtype=np.float64).reshape(3, 4) * 7.0


def test_npy_round_trip(tmp_path):
    np.save(tmp_path / "frame.npy", GRID.astype(np.int16))
    frame = read_frame(tmp_path / "frame.npy")
    assert frame.dtype == np.float64
    np.testing.assert_array_equal(frame, GRID)


def test_npz_single_array_and_key(tmp_path):
    np.savez(tmp_path / "one.npz", pressure=GRID)
    np.testing.assert_array_equal(read_frame(tmp_path / "one.npz"), GRID)
    np.savez(tmp_path / "two.npz", first=GRID, second=GRID + 1)
    np.testing.assert_array_equal(read_frame(tmp_path / "two.npz", key="second"), GRID + 1)


def test_npz_with_metadata_beside_its_array(tmp_path):
    import zipfile

    np.savez(tmp_path / "noted.npz", frame=GRID)
    with zipfile.ZipFile(tmp_path / "noted.npz", "a") as archive:
        archive.writestr("meta.json", '{"sensor": "resistive16"}')
    np.testing.assert_array_equal(read_frame(tmp_path / "noted.npz"), GRID)
    np.testing.assert_array_equal(read_frame(tmp_path / "noted.npz", key="frame"), GRID)


def test_npz_ambiguous_or_missing_key(tmp_path):
    np.savez(tmp_path / "two.npz", first=GRID, second=GRID + 1)
    with pytest.raises(ValueError, match=r"two\.npz: holds 2 arrays \(first, second\)"):
        read_frame(tmp_path / "two.npz")
    with pytest.raises(ValueError, match="no array named 'third'; the file holds: first, second"):
        read_frame(tmp_path / "two.npz", key="third")


@pytest.mark.parametrize("suffix", [".png", ".tif"])
@pytest.mark.parametrize("dtype", [np.uint8, np.uint16])
def test_image_round_trip_keeps_bit_depth(tmp_path, suffix, dtype):
    top = np.iinfo(dtype).max
    image = np.array([[0, 1, 2], [top - 2, top - 1, top]], dtype=dtype)
    path = tmp_path / f"frame{suffix}"
    assert cv2.imwrite(str(path), image)
    frame = read_frame(path)
    np.testing.assert_array_equal(frame, image.astype(np.float64))
    assert frame.max() == top


def test_colour_image_is_refused(tmp_path):
    path = tmp_path / "colour.png"
    cv2.imwrite(str(path), np.zeros((4, 5, 3), np.uint8))
    with pytest.raises(ValueError, match="must be a grayscale image, got 3 channels"):
        read_frame(path)


def test_multipage_tif_is_refused(tmp_path):
    path = tmp_path / "pages.tif"
    cv2.imwritemulti(str(path), [np.zeros((2, 2), np.uint8)] * 2)
    with pytest.raises(ValueError, match="holds 2 pages"):
        read_frame(path)


@pytest.mark.parametrize("suffix", [".png", ".tif", ".npy", ".npz"])
def test_truncated_binary_files(tmp_path, suffix):
    full = tmp_path / f"full{suffix}"
    if suffix in (".png", ".tif"):
        cv2.imwrite(str(full), np.full((20, 20), 9, np.uint8))
    elif suffix == ".npy":
        np.save(full, GRID)
    else:
        np.savez(full, frame=GRID)
    cut = tmp_path / f"cut{suffix}"
    cut.write_bytes(full.read_bytes()[: len(full.read_bytes()) // 3])
    with pytest.raises(ValueError, match=rf"cut\{suffix}"):
        read_frame(cut)


def test_csv_grid_round_trip(tmp_path):
    path = tmp_path / "grid.csv"
    np.savetxt(path, GRID, delimiter=",")
    np.testing.assert_array_equal(read_frame(path), GRID)


def test_missing_file_is_named(tmp_path):
    with pytest.raises(FileNotFoundError, match=r"no such file: .*absent\.npy"):
        read_frame(tmp_path / "absent.npy")


def test_unknown_suffix(tmp_path):
    (tmp_path / "frame.bmpx").write_bytes(b"12")
    with pytest.raises(ValueError, match="unknown frame format '.bmpx'"):
        read_frame(tmp_path / "frame.bmpx")


@pytest.mark.parametrize(
    ("content", "message"),
    [
        ("", r"empty\.csv: the file is empty"),
        ("\n  \n", r"empty\.csv: the file is empty"),
        ("1, 2, 3\n4, 5, 6\n7, 8", r"empty\.csv, line 3: truncated row: 2 fields, expected 3"),
        ("1, 2, 3\n4, 5\n7, 8, 9\n", r"empty\.csv, line 2: ragged row: 2 fields, expected 3"),
        ("1, 2, 3\n4, x, 6\n", r"empty\.csv, line 2: not a number: 'x'"),
        ("1, 2, 3\n4, , 6\n", r"empty\.csv, line 2: empty field"),
        ("1, 2, 3\n4, nan, 6\n", r"empty\.csv, line 2: NaN or infinite value"),
        ("a, b, c\n1, 2, 3\n", r"empty\.csv, line 1: a frame csv has no header"),
        ("timestamp, b\n1, 2\n", r"has a time column; read it with `read_sequence`"),
        # a spreadsheet's export with another separator: the message says which
        ("0;1;2\n3;4;5\n", r"line 1: one field, '0;1;2' \(fields must be separated by ','"),
        ("0;1;2\n", r"line 1: one field, '0;1;2' \(.*this line has semicolons\)"),
        ("0\t1\t2\n3\t4\t5\n", r"line 1: one field, .*this line has tabs\)"),
        ("0,5;1,5\n", r"line 1: not a number: '5;1' \(.*with '\.' for decimals; this line has"),
        ("1, 2\n3;4, 5\n", r"line 2: not a number: '3;4' \(.*this line has semicolons\)"),
    ],
)
def test_bad_csv_frames_name_file_and_line(tmp_path, content, message):
    path = tmp_path / "empty.csv"
    path.write_text(content)
    with pytest.raises(ValueError, match=message):
        read_frame(path)


def test_binary_garbage_csv(tmp_path):
    path = tmp_path / "garbage.csv"
    path.write_bytes(b"\xff\xfe\x00\x81")
    with pytest.raises(ValueError, match="not a text file"):
        read_frame(path)


def test_npy_that_is_not_2d_or_numeric(tmp_path):
    np.save(tmp_path / "cube.npy", np.zeros((2, 2, 2)))
    with pytest.raises(ValueError, match=r"must be 2-D, got shape \(2, 2, 2\)"):
        read_frame(tmp_path / "cube.npy")
    np.save(tmp_path / "text.npy", np.array([["a", "b"]]))
    with pytest.raises(ValueError, match="holds <U1 data, not real numbers"):
        read_frame(tmp_path / "text.npy")
    np.save(tmp_path / "complex.npy", np.ones((2, 2), complex))
    with pytest.raises(ValueError, match="holds complex128 data, not real numbers"):
        read_frame(tmp_path / "complex.npy")
    np.save(tmp_path / "hole.npy", np.array([[1.0, np.inf]]))
    with pytest.raises(ValueError, match="1 NaN or infinite value"):
        read_frame(tmp_path / "hole.npy")


def test_csv_sequence_with_timestamp(tmp_path):
    path = tmp_path / "log.csv"
    path.write_text("timestamp, left, right\n100, 1, 2\n128, 3, 4\n156, 5, 6\n")
    sequence = read_sequence(path, time_scale=1e-3)
    assert isinstance(sequence, TactileSequence)
    np.testing.assert_allclose(sequence.time, [0.1, 0.128, 0.156])
    np.testing.assert_array_equal(sequence.readings, [[1, 2], [3, 4], [5, 6]])
    assert sequence.channel_names == ("left", "right")
    assert sequence.n_steps == 3


def test_npz_sequence_round_trip(tmp_path):
    frames = np.arange(24.0).reshape(2, 3, 4)
    np.savez(tmp_path / "movie.npz", time=[0.0, 0.01], readings=frames)
    sequence = read_sequence(tmp_path / "movie.npz")
    np.testing.assert_array_equal(sequence.readings, frames)
    np.testing.assert_array_equal(sequence.time, [0.0, 0.01])


@pytest.mark.parametrize(
    ("content", "message"),
    [
        ("a, b\n1, 2\n", r"line 1: no 'timestamp' column"),
        ("timestamp\n1\n", r"line 1: no reading column beside the time column"),
        ("timestamp, a\n", r"line 1: a header but no data rows"),
        ("timestamp, a\n5, 1\n4, 2\n", r"line 3: time goes backwards \(5 -> 4\)"),
        ("timestamp, a\n5, 1\n6, 2, 3\n", r"line 3: ragged row: 3 fields, expected 2"),
        ("timestamp, a\n5, 1\n6, 2\n7,", r"line 4: truncated row: empty field"),
    ],
)
def test_bad_csv_sequences(tmp_path, content, message):
    path = tmp_path / "log.csv"
    path.write_text(content)
    with pytest.raises(ValueError, match=message):
        read_sequence(path)


def test_bad_npz_sequences(tmp_path):
    np.savez(tmp_path / "notime.npz", readings=np.zeros((2, 3)))
    with pytest.raises(ValueError, match="no array named 'time'"):
        read_sequence(tmp_path / "notime.npz")
    np.savez(tmp_path / "short.npz", time=[0.0], readings=np.zeros((2, 3)))
    with pytest.raises(ValueError, match=r"'time' \(1,\) and 'readings' \(2, 3\)"):
        read_sequence(tmp_path / "short.npz")
    with pytest.raises(ValueError, match="`time_scale` must be > 0"):
        read_sequence(tmp_path / "short.npz", time_scale=0)
    with pytest.raises(FileNotFoundError, match="absent.csv"):
        read_sequence(tmp_path / "absent.csv")


def _claiming(path, shape):
    """A .npy file whose header claims `shape` of float64, followed by 64 bytes."""
    header = {"descr": "<f8", "fortran_order": False, "shape": shape}
    with open(path, "wb") as stream:
        np.lib.format.write_array_header_1_0(stream, header)
        stream.write(bytes(64))
    return path


@pytest.mark.parametrize("shape", [(10**7, 10**7), (10**6, 1000, 16, 16), (3, 3)])
def test_a_header_claiming_more_than_the_file_holds_is_refused(tmp_path, shape):
    # read naively, the first two would allocate terabytes before finding the data missing
    path = _claiming(tmp_path / "claims.npy", shape)
    expected = r"claims\.npy: not a readable \.npy file \(truncated or corrupt: its header "
    expected += rf"claims shape \({shape[0]}, .* \(\d+ bytes\), but 64 bytes follow\)"
    with pytest.raises(ValueError, match=expected):
        read_frame(path)
    with pytest.raises(ValueError, match=expected):
        read_array(path)


def test_a_version_3_header_is_checked_as_well(tmp_path):
    # np.save writes version 3.0 (UTF-8) headers for non-Latin-1 field names; numpy has no
    # public reader of them, and one claiming 75 GB went to np.load unchecked
    header = "{'descr': '<f8', 'fortran_order': False, 'shape': (100000, 100000), }"
    header += " " * (-(len(header) + 13) % 64) + "\n"
    path = tmp_path / "three.npy"
    path.write_bytes(b"\x93NUMPY\x03\x00" + len(header).to_bytes(4, "little") + header.encode())
    with pytest.raises(ValueError, match=r"three\.npy: .*claims shape \(100000, 100000\)"):
        read_frame(path)
    garbled = tmp_path / "garbled.npy"
    garbled.write_bytes(b"\x93NUMPY\x03\x00" + (8).to_bytes(4, "little") + b"{'shape'")
    with pytest.raises(ValueError, match=r"garbled\.npy: .*version 3\.0 header cannot be read"):
        read_frame(garbled)


def _png_header(path, width, height):
    """A PNG of an 8-bit grey image: its header and its first row alone."""
    import struct
    import zlib

    def chunk(kind, data):
        crc = zlib.crc32(kind + data) & 0xFFFFFFFF
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", crc)

    body = struct.pack(">IIBBBBB", width, height, 8, 0, 0, 0, 0)
    data = chunk(b"IDAT", zlib.compress(bytes(width + 1)))  # its first row
    path.write_bytes(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", body) + data + chunk(b"IEND", b""))
    return path


def test_an_image_larger_than_opencv_reads_is_a_value_error(tmp_path):
    # 10^10 pixels, over OpenCV's 2^30: it raised cv2.error (a traceback on the command line)
    path = _png_header(tmp_path / "huge.png", 100_000, 100_000)
    with pytest.raises(ValueError, match=r"huge\.png: OpenCV cannot read the image: its header"):
        read_frame(path)


@pytest.mark.parametrize("suffix", [".png", ".tif"])
def test_an_image_of_fewer_than_8_bits_is_refused_not_scaled(tmp_path, suffix):
    # OpenCV reads a 1-bit image's 0/1 as 0/255 (a 4-bit one's 13 as 221): not as stored
    image = pytest.importorskip("PIL.Image")
    path = tmp_path / f"bilevel{suffix}"
    image.fromarray(np.eye(6, dtype=bool)).save(path)
    with pytest.raises(ValueError, match=r"bilevel\.\w+: stores 1-bit samples, which OpenCV"):
        read_frame(path)


def test_an_image_whose_name_is_not_utf8_is_refused_not_a_crash(tmp_path):
    # OpenCV's imread crashed the process (a segmentation fault) on such a name
    import os

    name = os.fsdecode(os.fsencode(str(tmp_path)) + b"/bad\xff.png")
    cv2.imwrite(str(tmp_path / "good.png"), np.zeros((4, 4), np.uint8))
    os.rename(tmp_path / "good.png", os.fsencode(name))
    with pytest.raises(ValueError, match=r"bad.*\.png'?: the file's name is not valid UTF-8"):
        read_frame(name)


def test_an_archive_member_claiming_more_than_it_holds_is_refused(tmp_path):
    import zipfile

    member = _claiming(tmp_path / "frame.npy", (10**7, 10**7))
    path = tmp_path / "claims.npz"
    with zipfile.ZipFile(path, "w") as archive:
        archive.write(member, "frame.npy")
    with pytest.raises(ValueError, match=r"claims\.npz: not a readable \.npz file \(truncated"):
        read_frame(path)


@pytest.mark.parametrize(
    ("content", "problem"),
    [
        (b"", "the file is empty"),
        (b"1, 2\n3, 4\n", "no NumPy header: a text or image file?"),
        (b"PK\x03\x04 garbage", "it is an .npz archive; save one array with np.save"),
    ],
)
def test_files_that_are_no_npy_say_what_they_are(tmp_path, content, problem):
    # not numpy's hint to load a pickle unsafely
    path = tmp_path / "frame.npy"
    path.write_bytes(content)
    with pytest.raises(ValueError, match=re.escape(f"not a readable .npy file ({problem})")):
        read_array(path)


def test_an_npz_that_is_no_zip_is_a_value_error(tmp_path):
    path = tmp_path / "frame.npz"
    path.write_bytes(b"PK\x03\x04 garbage")
    with pytest.raises(ValueError, match=r"frame\.npz: not a readable \.npz file"):
        read_frame(path)


def test_an_npz_with_a_corrupt_compressed_array_is_a_value_error(tmp_path, spoil_deflate):
    path = tmp_path / "packed.npz"
    np.savez_compressed(path, frame=GRID)
    spoil_deflate(path, "frame.npy")
    # zlib's own error escaped before
    with pytest.raises(
        ValueError,
        match=r"packed\.npz: not a readable \.npz file \(Error -3 while decompressing data",
    ):
        read_frame(path)


def test_read_array_keeps_the_stored_type_and_shape(tmp_path):
    stored = np.arange(24, dtype=np.int16).reshape(2, 3, 4)
    np.save(tmp_path / "batch.npy", stored)
    array = read_array(tmp_path / "batch.npy")
    assert array.dtype == np.int16 and np.array_equal(array, stored)


def test_a_boolean_frame_is_no_readings(tmp_path):
    np.save(tmp_path / "mask.npy", GRID > 20)
    expected = r"mask\.npy: the frame holds bool data, not real numbers"
    with pytest.raises(ValueError, match=expected):
        read_frame(tmp_path / "mask.npy")


def test_a_key_is_only_for_an_archive(tmp_path):
    np.save(tmp_path / "frame.npy", GRID)
    expected = r"frame\.npy: `key` names an array of an \.npz archive, not of a \.npy file"
    with pytest.raises(ValueError, match=expected):
        read_frame(tmp_path / "frame.npy", key="pressure")


def test_a_corrupt_image_is_one_error_without_opencv_s_log(tmp_path, capfd):
    path = tmp_path / "corrupt.png"
    path.write_bytes(b"\x89PNG\r\n\x1a\n" + b"x" * 50)  # a chunk claiming gigabytes
    with pytest.raises(ValueError, match=r"corrupt\.png: cannot decode the image"):
        read_frame(path)
    assert capfd.readouterr().err == ""  # OpenCV wrote "read_chunk ... too large" here
    from cv2.utils import logging as cv_logging

    assert cv_logging.getLogLevel() != cv_logging.LOG_LEVEL_SILENT  # restored


def test_read_frame_as_stored(tmp_path):
    frame = np.arange(12, dtype=np.uint16).reshape(3, 4) * 1000
    np.save(tmp_path / "raw.npy", frame)
    np.savez(tmp_path / "raw.npz", frame=frame, other=frame.astype(np.float32))
    stored = read_frame(tmp_path / "raw.npy", as_stored=True)
    assert stored.dtype == np.uint16 and stored[2, 3] == 11000
    assert read_frame(tmp_path / "raw.npy").dtype == np.float64
    assert read_frame(tmp_path / "raw.npz", key="other", as_stored=True).dtype == np.float32
    with pytest.raises(TypeError, match="`as_stored` must be True or False, got 'yes'"):
        read_frame(tmp_path / "raw.npy", as_stored="yes")
