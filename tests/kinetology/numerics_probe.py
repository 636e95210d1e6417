"""A fingerprint of kinetology's numbers, run in this process or in a child with another CPU.

``python tests/kinetology/numerics_probe.py ENGINE`` prints the sha256 of every output of a
few fixed takes (smoothed values, borders, codes, displacements, the actiongram's text and a
codec stream) segmented with ENGINE; ``test_kinetology_jit_engine.py`` runs it with numba's
target forced to a generic x86-64 (``NUMBA_CPU_NAME=generic``), with numpy's SIMD dispatch
and OpenBLAS's kernels held to an older CPU, and compares with the host's fingerprint: equal
digests are the promise that every machine computes the same floats.
"""

from __future__ import annotations

import hashlib
import sys

import numpy as np


def takes():
    """Fixed takes: long (threaded) and short, 120 fps (18-frame kernel) and 30 fps, one
    channel and many, wrapping angles and still ones."""
    from kinetology import Motion
    out = []
    for frames, channels, rate, seed in ((20_011, 31, 120.0, 1), (3_000, 7, 30.0, 2),
                                         (2_500, 1, 120.0, 3), (40, 5, 60.0, 4)):
        rng = np.random.default_rng(seed)
        values = np.cumsum(rng.normal(size=(frames, channels)), axis=0) * 3.0
        if channels > 2:
            values[:, 1] = (values[:, 1] * 10 + 180) % 360 - 180
            values[:, 2] = 7.0
        out.append(Motion(values, tuple(f"j{i}.r{'xyz'[i % 3]}" for i in range(channels)),
                          rate))
    return out


def fingerprint(engine: str) -> str:
    """sha256 over every number the takes give with ``engine``."""
    from kinetology.codec import compress
    from kinetology.segmentation import segment, segments, smooth
    digest = hashlib.sha256()
    for motion in takes():
        digest.update(np.ascontiguousarray(smooth(motion.values, motion.frame_rate, 0.05),
                                           dtype=float).tobytes())
        found = segments(motion, engine=engine)
        for arrays in (found.borders, found.codes, found.displacements):
            for array in arrays:
                digest.update(np.ascontiguousarray(array).tobytes())
        digest.update(segment(motion, engine=engine).to_text().encode())
        if motion.frames < 5_000:
            digest.update(compress(motion))
    return digest.hexdigest()


if __name__ == "__main__":
    print(fingerprint(sys.argv[1]))
