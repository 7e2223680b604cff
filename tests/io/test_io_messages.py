"""What the readers and writers say about files a spreadsheet or an image editor made."""

import cv2
import numpy as np
import pytest

from taxel.io import check_new_file, read_frame, read_sequence


def test_csv_with_a_byte_order_mark_reads_like_one_without(tmp_path):
    # a spreadsheet's "CSV UTF-8" starts with U+FEFF, which used to stick to the first field
    plain, marked = tmp_path / "plain.csv", tmp_path / "marked.csv"
    plain.write_text("24,1.5\n3,4\n", encoding="utf-8")
    marked.write_text("24,1.5\n3,4\n", encoding="utf-8-sig")
    assert marked.read_bytes()[:3] == b"\xef\xbb\xbf"
    assert np.array_equal(read_frame(marked), np.array([[24.0, 1.5], [3.0, 4.0]]))
    assert np.array_equal(read_frame(marked), read_frame(plain))


def test_csv_sequence_header_with_a_byte_order_mark(tmp_path):
    path = tmp_path / "slide.csv"
    path.write_text("time,a,b\n0.0,1,2\n0.1,3,4\n", encoding="utf-8-sig")
    sequence = read_sequence(path)
    assert sequence.channel_names == ("a", "b")
    assert np.array_equal(sequence.time, [0.0, 0.1])


def test_an_archive_without_arrays_says_so(tmp_path):
    path = tmp_path / "empty.npz"
    np.savez(path)
    with pytest.raises(ValueError, match=r"empty.npz: the archive holds no arrays$"):
        read_frame(path)


def test_an_image_with_alpha_says_what_it_holds(tmp_path):
    path = tmp_path / "grey_alpha.png"
    cv2.imwrite(str(path), np.zeros((4, 5, 4), np.uint8))
    with pytest.raises(ValueError, match=r"got 4 channels \(colour or grayscale, with alpha\)"):
        read_frame(path)


def test_an_output_beside_a_file_named_like_a_folder(tmp_path):
    parent = tmp_path / "notes"
    parent.write_text("a file, not a folder")
    with pytest.raises(ValueError, match=r"`path` is in a file, not a folder: '.*notes'"):
        check_new_file(parent / "frame.npy", suffix=".npy")
    with pytest.raises(ValueError, match=r"--out is in a folder that does not exist: '.*none'"):
        check_new_file(tmp_path / "none" / "frame.npy", suffix=".npy", name="--out")
    assert parent.read_text() == "a file, not a folder"


def test_an_existing_output_names_the_flag_that_named_it(tmp_path):
    truth = tmp_path / "truth.npy"
    np.save(truth, np.zeros((2, 2)))
    with pytest.raises(FileExistsError, match=r"^--truth '.*truth.npy' exists; pass --overwrite"):
        check_new_file(truth, suffix=".npy", name="--truth")
    assert np.array_equal(np.load(truth), np.zeros((2, 2)))
