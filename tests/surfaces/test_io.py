import numpy as np
import pytest

from roughcontact._validate import ParameterError
from roughcontact.surfaces.io import load_heights, save_heights


@pytest.fixture
def heights():
    rng = np.random.default_rng(0)
    return rng.standard_normal((5, 7)) * 1e-3 + np.pi


@pytest.mark.parametrize("name", ["h.npy", "h.txt", "h.csv", "h.dat"])
def test_round_trip_exact(tmp_path, heights, name):
    p = save_heights(tmp_path / name, heights)
    assert p.exists()
    back = load_heights(p)
    assert back.dtype == np.float64 and back.shape == heights.shape
    np.testing.assert_array_equal(back, heights)


def test_round_trip_str_path(tmp_path, heights):
    save_heights(str(tmp_path / "h.npy"), heights)
    np.testing.assert_array_equal(load_heights(str(tmp_path / "h.npy")), heights)


def test_npy_suffix_not_doubled(tmp_path, heights):
    save_heights(tmp_path / "x.npy", heights)
    assert sorted(f.name for f in tmp_path.iterdir()) == ["x.npy"]


def test_load_comma_and_whitespace_text(tmp_path):
    (tmp_path / "a.txt").write_text("# comment\n1, 2, 3\n4,5,6\n")
    (tmp_path / "b.txt").write_text("1 2\t3\n4   5 6\n")
    expected = np.array([[1.0, 2.0, 3.0], [4.0, 5.0, 6.0]])
    np.testing.assert_array_equal(load_heights(tmp_path / "a.txt"), expected)
    np.testing.assert_array_equal(load_heights(tmp_path / "b.txt"), expected)


def test_missing_file(tmp_path):
    p = tmp_path / "nope.npy"
    with pytest.raises(ParameterError, match="nope.npy") as e:
        load_heights(p)
    assert "2D" in str(e.value)


def test_directory_is_not_a_file(tmp_path):
    with pytest.raises(ParameterError, match="is a directory, not a regular file"):
        load_heights(tmp_path)


@pytest.mark.parametrize("suffix", [".npy", ".txt"])
def test_1d_data_rejected(tmp_path, suffix):
    p = tmp_path / f"line{suffix}"
    if suffix == ".npy":
        np.save(p, np.arange(10.0))
    else:
        p.write_text("1 2 3 4\n")
    with pytest.raises(ParameterError, match="2D") as e:
        load_heights(p)
    assert f"line{suffix}" in str(e.value)


@pytest.mark.parametrize("suffix", [".npy", ".txt"])
def test_nan_rejected(tmp_path, suffix):
    data = np.ones((3, 3))
    data[1, 1] = np.nan
    p = tmp_path / f"bad{suffix}"
    if suffix == ".npy":
        np.save(p, data)
    else:
        np.savetxt(p, data)
    with pytest.raises(ParameterError, match="finite") as e:
        load_heights(p)
    assert f"bad{suffix}" in str(e.value)


def test_garbage_text_and_garbage_npy(tmp_path):
    (tmp_path / "g.txt").write_text("1 2 x\n3 4 5\n")
    with pytest.raises(ParameterError, match="g.txt"):
        load_heights(tmp_path / "g.txt")
    (tmp_path / "g.npy").write_bytes(b"not a numpy file")
    with pytest.raises(ParameterError, match="g.npy"):
        load_heights(tmp_path / "g.npy")
    (tmp_path / "ragged.txt").write_text("1 2 3\n4 5\n")
    with pytest.raises(ParameterError, match="ragged.txt"):
        load_heights(tmp_path / "ragged.txt")


def test_save_rejects_bad_heights(tmp_path):
    with pytest.raises(ParameterError, match="heights"):
        save_heights(tmp_path / "x.npy", np.ones(4))
    with pytest.raises(ParameterError, match="heights"):
        save_heights(tmp_path / "x.npy", np.full((3, 3), np.inf))
    assert not (tmp_path / "x.npy").exists()


def test_save_to_missing_directory(tmp_path):
    with pytest.raises(ParameterError, match="nodir"):
        save_heights(tmp_path / "nodir" / "x.txt", np.ones((2, 2)))


def test_plain_files_have_one_channel(tmp_path, heights):
    save_heights(tmp_path / "h.npy", heights)
    for channel in (None, 0, "heights"):
        np.testing.assert_array_equal(load_heights(tmp_path / "h.npy", channel=channel), heights)
    with pytest.raises(ParameterError, match="channel") as e:
        load_heights(tmp_path / "h.npy", channel="Height")
    assert "h.npy" in str(e.value) and "\n" not in str(e.value)


def test_text_with_a_header_is_not_plain_text(tmp_path):
    # a header makes it an instrument file; SurfaceTopography finds no units in this one,
    # and the one-line error gives numpy's reason too
    pytest.importorskip("SurfaceTopography")
    (tmp_path / "xy.txt").write_text("Scan Data\nLateral um,Raw nm\n0,1\n1,2\n")
    with pytest.raises(ParameterError, match="as plain text.*'Scan'") as e:
        load_heights(tmp_path / "xy.txt")
    assert "xy.txt" in str(e.value) and "\n" not in str(e.value)
