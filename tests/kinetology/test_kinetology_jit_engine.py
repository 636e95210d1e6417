"""The compiled engine (numba) gives the numpy engine's answers exactly, and the choice validates.

numba is in the ``test`` extra, so these tests run (a missing numba fails the import below
rather than skipping). The numpy engine is the reference: it is itself checked against plain
per-frame loops in ``test_kinetology_fast_segmentation.py``.
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import numba  # noqa: F401  (the test extra installs it: no silent skip)
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from kinetology import Motion, _kinetemes_jit
from kinetology._engines import select
from psgs._foundation.engines import ENGINES
from kinetology.performances import segment_performances
from kinetology.segmentation import segment, segments, states
# every dead band and smoothing the numpy engine is checked with against plain loops (at 120
# fps: 0.05 s is 18 frames each side, 0.01 s is 4)
from test_kinetology_fast_segmentation import deadbands

REPO = Path(__file__).resolve().parents[2]


def assert_same(a, b):
    """Two Segmentations hold the same channels and the same arrays, bit for bit."""
    assert a.channels == b.channels and a.still == b.still and a.frames == b.frames
    for left, right in ((a.borders, b.borders), (a.codes, b.codes),
                        (a.displacements, b.displacements)):
        assert len(left) == len(right)
        for x, y in zip(left, right):
            assert x.dtype == y.dtype and x.shape == y.shape
            assert x.tobytes() == y.tobytes()


@st.composite
def motions(draw, max_frames=400):
    frames = draw(st.one_of(st.integers(1, 3), st.integers(4, max_frames)))  # 1-3: no derivative
    count = draw(st.integers(1, 5))
    rate = draw(st.sampled_from([10.0, 30.0, 60.0, 120.0]))
    rng = np.random.default_rng(draw(st.integers(0, 2 ** 16)))
    columns = []
    for _ in range(count):
        kind = draw(st.sampled_from(["walk", "wrap", "constant", "sine", "steps", "spiky"]))
        if kind == "walk":
            column = np.cumsum(rng.normal(scale=draw(st.sampled_from([0.01, 2.0, 30.0])),
                                          size=frames))
        elif kind == "wrap":  # an angle turning through +-180 deg, as a file stores it
            column = (np.cumsum(rng.normal(8.0, 3.0, size=frames)) + 180) % 360 - 180
        elif kind == "constant":
            column = np.full(frames, draw(st.sampled_from([0.0, -179.5, 42.0])))
        elif kind == "sine":
            column = 40 * np.sin(np.arange(frames) / rate * 2 * np.pi * rng.uniform(0.2, 3))
        elif kind == "steps":  # exact zeros in the derivatives, ties in the percentiles
            column = np.round(np.cumsum(rng.integers(-1, 2, size=frames)) * 3.0)
        else:  # mostly still with a few jumps: runs that stay in the dead band
            column = np.where(rng.random(frames) < 0.05, rng.normal(0, 50, frames), 0.0)
        columns.append(column)
    axes = draw(st.lists(st.sampled_from(["rx", "ry", "rz", "tx"]), min_size=count,
                         max_size=count))
    return Motion(np.column_stack(columns), tuple(f"j{i}.{a}" for i, a in enumerate(axes)), rate)


@settings(max_examples=150)
@given(motions(), deadbands)
def test_the_engines_segment_alike(motion, params):
    assert_same(segments(motion, engine="numba", **params),
                segments(motion, engine="numpy", **params))


@settings(max_examples=40)
@given(motions(max_frames=120), deadbands)
def test_the_engines_give_the_same_actiongram_and_states(motion, params):
    fast, plain = segment(motion, engine="numba", **params), segment(motion, engine="numpy",
                                                                     **params)
    assert fast == plain and fast.to_text() == plain.to_text()
    assert fast.to_json() == plain.to_json()
    keys = ("smoothing", "velocity_deadband", "acceleration_deadband", "relative_deadband",
            "unwrap")
    kept = {k: params[k] for k in keys}
    assert np.array_equal(states(motion.values, motion.frame_rate, engine="numba", **kept),
                          states(motion.values, motion.frame_rate, engine="numpy", **kept))


@settings(max_examples=30)
@given(motions(max_frames=300), deadbands, st.lists(st.integers(1, 200), min_size=1, max_size=3))
def test_segment_performances_alike(motion, params, lengths):
    cuts = np.cumsum([0] + lengths)
    takes = [Motion(motion.values[a:b], motion.channels, motion.frame_rate)
             for a, b in zip(cuts[:-1], cuts[1:]) if a < motion.frames]
    fast = segment_performances(takes, engine="numba", **params)
    plain = segment_performances(takes, engine="numpy", **params)
    assert [a.to_text() for a in fast] == [a.to_text() for a in plain]


@pytest.mark.parametrize("frames, channels, rate", [
    (20_011, 31, 120.0),   # threaded: odd groups of channels
    (30_000, 40, 30.0),    # threaded, the direct sum (5 frames each side)
    (9_000, 7, 120.0),     # one thread; several percentile steps (every 1st frame: 9,000 > 8,192)
])
def test_long_takes_alike(frames, channels, rate):
    rng = np.random.default_rng(frames)
    values = np.cumsum(rng.normal(size=(frames, channels)), axis=0)
    values[:, 1] = (values[:, 1] * 30 + 180) % 360 - 180  # wraps
    values[:, 2] = 7.0                                     # still
    motion = Motion(values, tuple(f"j{i}.rx" for i in range(channels)), rate)
    assert_same(segments(motion, engine="numba"), segments(motion, engine="numpy"))


@pytest.mark.parametrize("rate", [120.0, 30.0])
def test_threads_do_not_change_the_result(monkeypatch, rate):
    """1-4 threads (groups of 9 channels split 9, 4+5, 3+3+3, 2+2+2+3): the same bits."""
    rng = np.random.default_rng(3)
    values = np.cumsum(rng.normal(size=(5_000, 9)), axis=0)
    values[:, 4] = (values[:, 4] * 40 + 180) % 360 - 180  # wraps: largest_step splits frames
    motion = Motion(values, tuple(f"j{i}.ry" for i in range(9)), rate)
    monkeypatch.setattr(_kinetemes_jit, "thread_count", lambda c, f: 1)
    alone = segments(motion, engine="numba")
    for threads in (2, 3, 4):
        monkeypatch.setattr(_kinetemes_jit, "thread_count", lambda c, f, k=threads: k)
        assert_same(segments(motion, engine="numba"), alone)
    assert_same(alone, segments(motion, engine="numpy"))


@settings(max_examples=150)
@given(st.lists(st.one_of(st.floats(0, 1e6), st.sampled_from([0.0, 1.0, 2.5]),
                          st.just(np.inf)), min_size=1, max_size=60),
       st.integers(0, 3))
def test_the_percentile_is_numpys_bit_for_bit(values, repeat):
    sample = np.array(values * (1 + 50 * repeat))  # ties; samples of up to 9,060 values
    lower, gamma = _kinetemes_jit._percentile_plan(sample.size)
    got = _kinetemes_jit._percentile(sample, lower, gamma, np.empty(sample.size - lower),
                                     np.empty(sample.size))
    with np.errstate(invalid="ignore"):  # inf - inf in numpy's interpolation, as in ours
        expected = np.percentile(sample, 95)
    assert np.array_equal(np.float64(got), expected, equal_nan=True)
    assert np.float64(got).tobytes() == np.float64(expected).tobytes() or np.isnan(expected)


@pytest.mark.parametrize("layout", ["probes hold the largest", "probes hold the smallest",
                                    "sorted", "reversed", "all equal"])
def test_the_percentile_is_numpys_whichever_values_the_probes_see(layout):
    """Every 16th value sets the threshold of the search: the answer must not depend on it
    (too high a threshold falls back to searching every value)."""
    rng = np.random.default_rng(7)
    for m in (160, 161, 1000, 8192, 9001):
        sample = rng.random(m)
        if layout == "probes hold the largest":
            sample[::16] += 10.0
        elif layout == "probes hold the smallest":
            sample[::16] -= 10.0
        elif layout == "sorted":
            sample.sort()
        elif layout == "reversed":
            sample = np.sort(sample)[::-1].copy()
        else:
            sample[:] = 0.25
        lower, gamma = _kinetemes_jit._percentile_plan(m)
        got = _kinetemes_jit._percentile(sample.copy(), lower, gamma,
                                         np.empty(m - lower), np.empty(m))
        assert np.float64(got).tobytes() == np.percentile(sample, 95).tobytes(), (layout, m)


def test_the_engine_choice_validates():
    motion = Motion(np.zeros((10, 1)), ("a.rx",), 30.0)
    assert ENGINES == ("auto", "numpy", "numba")
    assert select("numba").name == "numba" and select("auto").name == "numba"
    assert select("numpy").name == "numpy"
    for bad in ("fortran", "NUMBA", "", None, 3):
        with pytest.raises(ValueError, match="engine must be one of 'auto', 'numpy', 'numba'"):
            segments(motion, engine=bad)
    with pytest.raises(ValueError, match="engine must be one of"):
        segment_performances([motion], engine="c")
    with pytest.raises(ValueError, match="engine must be one of"):
        states(np.zeros(5), 30.0, engine="c")
    with pytest.raises(TypeError, match="unknown segmentation parameter"):
        segments(motion, engin="numba")  # a misspelt keyword is still caught


def test_without_numba_auto_is_numpy_and_numba_is_a_clear_error():
    script = ("import sys; sys.modules['numba'] = None\n"
              "import numpy as np, kinetology\n"
              "from kinetology.segmentation import segments\n"
              "m = kinetology.Motion(np.cumsum(np.ones((50, 2)), 0), ('a.rx', 'b.rx'), 30.0)\n"
              "print(segments(m).borders[0].tolist() == segments(m, engine='numpy')"
              ".borders[0].tolist())\n"
              "try:\n"
              "    segments(m, engine='numba')\n"
              "except ImportError as error:\n"
              "    print(error)\n")
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                          cwd=REPO, timeout=60, env={"PYTHONPATH": str(REPO), "PATH": ""})
    lines = done.stdout.splitlines()
    assert done.returncode == 0, done.stderr[-2000:]
    assert lines[0] == "True"
    assert "engine='numba' needs numba" in lines[1] and "pip install 'psgs[fast]'" in lines[1]


def _other_cpus() -> dict[str, dict[str, str]]:
    """Child environments that compute as another x86-64 would: numba compiling for a generic
    x86-64 (SSE2, no AVX or FMA: the code a CI machine's CPU or an AVX-512 one would not
    share with this one), numpy's SIMD loops held to its baseline, OpenBLAS's kernels to an
    old core. Environment variables, so each needs a fresh process."""
    import numpy._core._multiarray_umath as umath
    dispatched = [f for f in umath.__cpu_dispatch__ if umath.__cpu_features__.get(f)]
    return {
        "numba generic": {"NUMBA_CPU_NAME": "generic", "NUMBA_CPU_FEATURES": ""},
        "numpy baseline": {"NPY_DISABLE_CPU_FEATURES": " ".join(dispatched),
                           "OPENBLAS_CORETYPE": "Prescott"},
    }


@pytest.fixture(scope="module")
def host_digest():
    """The probe's digest here, with the numpy engine; the numba engine must give it too."""
    from numerics_probe import fingerprint
    host = fingerprint("numpy")
    assert fingerprint("numba") == host
    return host


@pytest.mark.skipif(__import__("platform").machine() not in ("x86_64", "AMD64"),
                    reason="the generic target and the feature names are x86-64's")
@pytest.mark.parametrize("cpu", ["numba generic", "numpy baseline"])
def test_another_cpu_computes_the_same_floats(cpu, host_digest):
    """The promise: every output (smoothed values, borders, codes, displacements, the codec's
    bytes) is the same to the bit on every CPU, with either engine. Each sum runs in one
    fixed order of IEEE operations (no BLAS, no libm in the numbers, no ``fastmath``), so a
    child process compiling for another CPU gives the host's digest (numba's generic build
    is compiled on the first run, 5-8 s, then cached beside the module)."""
    import os

    host = host_digest
    engine = "numba" if cpu.startswith("numba") else "numpy"
    env = {**os.environ, **_other_cpus()[cpu], "PYTHONPATH": str(REPO)}
    done = subprocess.run([sys.executable, str(Path(__file__).with_name("numerics_probe.py")),
                           engine], env=env, capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr[-2000:]
    assert done.stdout.strip() == host
