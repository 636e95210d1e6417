"""Engine choice: small inputs stay on numpy under "auto"; numba's compilation is announced once."""

from __future__ import annotations

import io
import subprocess
import sys

import numpy as np
import pytest

from psgs._foundation import engines
from psgs.errors import ValidationError


def test_small_inputs_stay_on_numpy_until_the_compiled_loops_run():
    assert engines.for_input("auto", 10, 100, "no.such.module") == "numpy"
    assert engines.for_input("auto", 100, 100, "no.such.module") == "auto"
    assert engines.for_input("numba", 10, 100, "no.such.module") == "numba"
    assert engines.for_input("numpy", 10**9, 100, "no.such.module") == "numpy"
    # a module whose loops have run (a value with signatures) makes the compiled engine free
    module = type(sys)("psgs_test_loaded")
    module.loop = type("Dispatcher", (), {"signatures": [("int64",)]})()
    sys.modules[module.__name__] = module
    try:
        assert engines.for_input("auto", 10, 100, module.__name__) == "auto"
    finally:
        del sys.modules[module.__name__]
    with pytest.raises(ValidationError, match="engine must be one of"):
        engines.for_input("fortran", 10, 100, "no.such.module")


def test_a_small_segmentation_and_induction_never_load_the_compiled_modules():
    pytest.importorskip("numba")
    code = ("import sys, numpy as np\n"
            "from kinetology.segmentation import states\n"
            "from psgs.induce import PAL\n"
            "from psgs.induce.synthetic import generate\n"
            "states(np.cumsum(np.ones((200, 3)), axis=0), 120.0)\n"
            "PAL().induce(generate(seed=1).actiongram)\n"
            "print(sorted(m for m in sys.modules if m.endswith('_jit')))\n")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          timeout=60, check=True)
    assert done.stdout.strip() == "[]"
    assert "compiling" not in done.stderr


def test_numba_compilation_is_announced_once():
    event = pytest.importorskip("numba.core.event")
    stream = io.StringIO()
    with event.install_listener("numba:compile", engines._announcer(stream)):
        for _ in range(3):
            with event.trigger_event("numba:compile", data={}):
                pass
    lines = stream.getvalue().splitlines()
    assert len(lines) == 1 and "numba is compiling" in lines[0]


def test_a_cached_call_fires_no_compile_event():
    numba = pytest.importorskip("numba")
    event = pytest.importorskip("numba.core.event")
    stream = io.StringIO()
    twice = numba.njit(lambda x: x * 2)  # no cache: its first call compiles
    listener = engines._announcer(stream)
    with event.install_listener("numba:compile", listener):
        assert twice(np.int64(2)) == 4
    assert stream.getvalue().count("\n") == 1
    quiet = io.StringIO()
    with event.install_listener("numba:compile", engines._announcer(quiet)):
        assert twice(np.int64(3)) == 6  # compiled already: nothing to say
    assert quiet.getvalue() == ""
