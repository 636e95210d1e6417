"""Fixes from a user review of the kinetology command: errors modulo 360°, one-line refusals
before any output, and the byte a truncated .kin file ends at."""

from __future__ import annotations

import numpy as np
import pytest

import kinetology
from kinetology import Motion
from kinetology.cli import main

from test_kinetology_readers import SMALL_BVH


def _crossing(frames: int = 240) -> Motion:
    """A hip turning around ±180° (the file's angle jumps from +179 to -179) and a root
    translation: the decoder returns the angle unwrapped."""
    t = np.arange(frames) / 120
    turn = (180 + 15 * np.sin(2 * np.pi * t) + 180) % 360 - 180
    return Motion(np.column_stack([10 * t, turn]), ("root.tx", "hip.rz"), 120.0,
                  source="crossing.bvh")


def _write_bvh(path, frames: int = 240):
    t = np.arange(frames) / 120
    rows = "\n".join(f"0 0 0 0 0 0 {30 * np.sin(2 * np.pi * x):.4f} 0 {20 * np.cos(3 * x):.4f}"
                     for x in t)
    head = SMALL_BVH[: SMALL_BVH.index("Frames:")]
    path.write_text(f"{head}Frames: {frames}\nFrame Time: 0.0083333\n{rows}\n")
    return path


# -- 1. errors modulo 360° ------------------------------------------------------------------

def test_codec_point_compares_rotations_modulo_360_as_compress_reports():
    from kinetology.evaluation import codec_point

    motion = _crossing()
    point = codec_point(motion, original_size=10_000)
    data = kinetology.compress(motion)
    assert point["mae_angles"] == pytest.approx(data.mean_error)
    assert point["mae"] == pytest.approx(data.mean_error_all)
    assert point["max_error"] < 5  # not the 360° between +179 and the decoded -181


def test_absolute_errors_wrap_rotations_but_not_translations():
    from kinetology.codec import absolute_errors

    a = Motion(np.array([[-179.0, 1.0]]), ("neck.rz", "root.tx"), 120)
    b = Motion(np.array([[181.5, 361.0]]), ("neck.rz", "root.tx"), 120)
    np.testing.assert_allclose(absolute_errors(a, b), [[0.5, 360.0]])


def test_reconstruction_plot_title_and_curve_are_modulo_360():
    pytest.importorskip("matplotlib")
    from kinetology.plotting import plot_reconstruction

    motion = _crossing()
    decoded = kinetology.decompress(kinetology.compress(motion))
    fig = plot_reconstruction(motion, decoded, "hip.rz")
    error = float(fig.axes[0].get_title().split("mean |error| ")[1].split()[0])
    assert error == pytest.approx(kinetology.codec.mean_errors(motion, decoded)[0], abs=1e-3)
    original, shown = (line.get_ydata() for line in fig.axes[0].get_lines())
    assert np.abs(original - shown).max() < 5  # drawn on the original's turn
    import matplotlib.pyplot as plt
    plt.close(fig)


# -- 2. a picture format matplotlib does not write ------------------------------------------

@pytest.mark.parametrize("kind", ["states", "reconstruction", "view"])
@pytest.mark.parametrize("name", ["p.txt", "p.xyz", "p"])
def test_plot_refuses_an_unknown_suffix_in_one_line_before_reading(tmp_path, capsys, kind,
                                                                   name):
    pytest.importorskip("matplotlib")
    # the input does not exist: the output's suffix is refused before any work
    argv = ["plot", str(tmp_path / "missing.bvh"), "--channel", "lknee", "--kind", kind,
            "-o", str(tmp_path / name)]
    assert main(argv) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "Traceback" not in err
    assert str(tmp_path / name) in err and ".png, .svg, .pdf" in err
    assert not (tmp_path / name).exists()


# -- 8. a truncated .kin file ---------------------------------------------------------------

def test_a_truncated_kin_file_names_the_byte_it_ends_at(tmp_path):
    from kinetology import MotionFormatError

    data = bytes(kinetology.compress(kinetology.synthetic_motion(3, seed=0)))
    for cut in (len(data) // 2, len(data) - 1):
        with pytest.raises(MotionFormatError, match=rf"at byte {cut} of the file"):
            kinetology.decompress(data[:cut], source="cut.kin")
