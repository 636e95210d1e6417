"""Inducers pickled before a parameter existed load with that parameter's default.

The bytes below are ``pickle.dumps((PAL(max_seconds=5, min_copies=4),
ContentPAL(engine="numpy"), MotionPAL(alpha=0.02)), protocol=4)`` made by psgs before
``max_bytes`` was a parameter: they hold no ``max_bytes``, and loaded they failed in
``get_params`` ("does not store its parameter 'max_bytes'").
"""

from __future__ import annotations

import base64
import pickle

from psgs.induce import PAL, ContentPAL, MotionPAL
from psgs.induce.synthetic import generate

OLD = base64.b64decode(
    "gASVxQMAAAAAAACMFXBzZ3MuaW5kdWNlLnBhbC5lbnRyeZSMA1BBTJSTlCmBlH2UKIwKbWluX2NvcGllc5RL"
    "BIwIY29uc2VydmWURz/jMzMzMzMzjAplZGdlX3NoYXJllEc/4AAAAAAAAIwMY29sdW1uX2FscGhhlEc/UGJN"
    "0vGp/IwObWF0Y2hfZnJhY3Rpb26URz/gAAAAAAAAjApzY2FuX2FscGhhlEc/qZmZmZmZmowFYWxwaGGURz+E"
    "euFHrhR7jA1zeW5jX2ZyYWN0aW9ulEc/4AAAAAAAAIwOd2luZG93X3N1cHBvcnSURz/Vwo9cKPXDjAttYXhf"
    "cGF0dGVybpRLQIwFc2VlZHOUSwOMBnJvdW5kc5RLAowMam9pbnNfY29waWVzlEsEjA5jb3B5X2FncmVlbWVu"
    "dJRHP+AAAAAAAACMEXNlY3Rpb25fZHVyYXRpb25zlIwDYW55lIwGdGltaW5nlIwEYXV0b5SMD3BlcmlvZF9x"
    "dWFudGlsZZRHP+zMzMzMzM2MEHBlcmlvZF9hZ3JlZW1lbnSURz/jMzMzMzMzjAttYXhfc2Vjb25kc5RLBYwI"
    "ZXZpZGVuY2WUjAlraW5ldGVtZXOUjAtqb2ludF9zaGFyZZRHP9AAAAAAAACMD25laWdoYm91cl9zaGFyZZRH"
    "P564UeuFHriMDWNoYW5uZWxfc2hhcmWURz/QAAAAAAAAjAltYXhfc2hpZnSURz+5mZmZmZmajAltaW5fY3lj"
    "bGWURz/QAAAAAAAAjA9taW5fY3ljbGVfc2NvcmWURz+pmZmZmZmajAZlbmdpbmWUaBZ1YowXcHNncy5pbmR1"
    "Y2UucGFsLmxlYXJuZXKUjApDb250ZW50UEFMlJOUKYGUfZQoaAVLA2gGRz/jMzMzMzMzaAdHP+AAAAAAAABo"
    "CEc/UGJN0vGp/GgJRz/gAAAAAAAAaApHP6mZmZmZmZpoC0c/hHrhR64Ue2gMRz/gAAAAAAAAaA1HP9XCj1wo"
    "9cNoDktAaA9LA2gQSwJoEUsEaBJHP+AAAAAAAABoE2gUaBVoFmgXRz/szMzMzMzNaBhHP+MzMzMzMzNoGU5o"
    "IowFbnVtcHmUdWKMHnBzZ3MuaW5kdWNlLnBhbC5tb3Rpb24ubGVhcm5lcpSMCU1vdGlvblBBTJSTlCmBlH2U"
    "KGgFSwNoC0c/lHrhR64Ue2gaaBtoHEc/0AAAAAAAAGgdRz+euFHrhR64aB5HP9AAAAAAAABoH0c/uZmZmZmZ"
    "mmggRz/QAAAAAAAAaCFHP6mZmZmZmZpoGU51YoeULg==")


def test_inducers_pickled_before_max_bytes_take_its_default():
    pal, content, motion = pickle.loads(OLD)
    assert pal.get_params() == PAL(max_seconds=5, min_copies=4).get_params()
    assert content.get_params() == ContentPAL(engine="numpy").get_params()
    assert motion.get_params() == MotionPAL(alpha=0.02).get_params()
    assert all(made.max_bytes is None for made in (pal, content, motion))
    actiongram = generate(seed=1).actiongram
    assert content.induce(actiongram) == ContentPAL(engine="numpy").induce(actiongram)
    assert pal.conf() == PAL(max_seconds=5, min_copies=4).conf()


def test_an_inducer_pickled_now_comes_back_as_it_was():
    made = ContentPAL(max_bytes=1e9, seeds=4)
    assert pickle.loads(pickle.dumps(made)).get_params() == made.get_params()
