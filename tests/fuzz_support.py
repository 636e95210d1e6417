"""Fuzzing the readers: mutate small real files, read them, allow only success or a documented error.

Shared by the fuzz tests (``tests/*/test_fuzz_*.py``, a few hundred hypothesis examples per
reader on every run) and by ``benchmarks/fuzz.py`` (10^4 inputs per reader, counts in
docs/testing.md). A *mutation* is a small edit of the file's bytes, the kind that real files
get from hand editing, truncation and bad exporters: delete a span, duplicate a span, put an
edge-case number (``nan``, ``1e-320``, ``1e308`` ..) in place of one of the file's numbers,
insert a token that readers treat specially (numbers at the edges of a float, braces, keywords,
byte-order marks, bytes that are not UTF-8, a lone surrogate), overwrite one byte, or, in a
JSON file, replace or drop one value (most byte edits of JSON stop at the parser; these reach
what reads the parsed value).

A reader passes on an input when, within :data:`TIME_LIMIT` seconds, it either returns a
value that survives its round-trip check, or raises one of its documented errors. Anything
else (another exception, a hang) is a finding.
"""

from __future__ import annotations

import json
import math
import random
import re
import signal
import tempfile
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path
from typing import Callable

SEEDS = Path(__file__).resolve().parent / "data" / "fuzz"

#: Seconds one input may take before it counts as a hang (generous: a loaded 2-core machine).
TIME_LIMIT = 5.0

# text that readers treat specially; inserted whole so that mutations reach deep code paths
TOKENS = (
    "0", "-1", "1e308", "-1e308", "1e-320", "nan", "inf", "-inf", "1e999", "9" * 5000, ".5",
    "0x1F", "1_0", "{", "}", "[", "]", "(", ")", "{" * 50, "[" * 2000, ":", "@", "#", "->",
    "|", ",", '"', "'", "\\", "\n", "\r\n", "\t", " ", "\n\n", "\ufeff", "\u00a0", "\ud800",
    "ε", "\\ud800", "\\u0000", "ROOT", "JOINT", "End Site", "OFFSET", "CHANNELS 3", "CHANNELS 0", "MOTION",
    "Frames: 0", "Frame Time: 0", "Xrotation", "Xposition", ":root", ":bonedata", "begin",
    "end", "axis", "dof rx", "name", ":RADIANS", ":hierarchy", "root", "psgs", "pcgs",
    "component", "start", "sync", "mode", "parallel", "single", "returning", "Q1", "S", "#",
    '"strings"', '"symbols"', '"durations"', '"start"', "null", "true", "[]", "{}",
)
# numbers at the edges of what a float (or a reader) takes, put in place of a number of the file
NUMBERS = ("0", "-0", "1", "-1", "0.5", "1e308", "-1e308", "1e-320", "5e-324", "1e15", "1e-9",
           "nan", "inf", "-inf", "1e999", "9" * 400, "12345678901234567890", "2.5e-7", "1e300")
_NUMBER = re.compile(rb"[-+]?\d+(?:\.\d*)?(?:[eE][-+]?\d+)?")
# bytes that are not UTF-8 text on their own
RAW_BYTES = (b"\xff", b"\xc3", b"\xed\xa0\x80", b"\x00", b"\xef\xbb\xbf")

# values put in place of one value of a JSON file ("json" edits; _DROP removes the member):
# byte edits of JSON mostly stop at the parser, these reach what reads the parsed value
_DROP = object()
JSON_VALUES = (_DROP, None, True, 0, -1, 2.5, 10 ** 400, 1e308, -1e308, "", "x", "a/b",
               "\u0000", [], {}, [1, 2], ["x"], {"x": 1}, [[[[[[[[[[[]]]]]]]]]]])

#: One mutation: (kind, position, length, argument); positions wrap around the data's length.
Mutation = tuple[str, int, int, int]
KINDS = ("delete", "duplicate", "insert", "raw", "byte", "number", "json")


def _json_edit(data: bytes, position: int, argument: int) -> bytes:
    """``data`` with its (position mod count)-th JSON value replaced (or dropped); data that
    is not JSON is left as it is."""
    try:
        root = [json.loads(data)]
    except (ValueError, RecursionError):
        return data
    slots = []  # (container, key) of every value but the root's own container
    stack = [(root, 0)]
    while stack:
        container, key = stack.pop()
        slots.append((container, key))
        value = container[key]
        if isinstance(value, dict):
            stack.extend((value, k) for k in value)
        elif isinstance(value, list):
            stack.extend((value, i) for i in range(len(value)))
    container, key = slots[position % len(slots)]
    new = JSON_VALUES[argument % len(JSON_VALUES)]
    if new is _DROP:
        if container is root:
            return data
        del container[key]
    else:
        container[key] = json.loads(json.dumps(new))  # a fresh copy
    return json.dumps(root[0], indent=2).encode()


def apply(data: bytes, mutations: list[Mutation]) -> bytes:
    """``data`` with each mutation applied in turn (positions taken modulo the current length)."""
    for kind, position, length, argument in mutations:
        at = position % (len(data) + 1)
        end = min(len(data), at + length)
        if kind == "delete":
            data = data[:at] + data[end:]
        elif kind == "duplicate":
            data = data[:end] + data[at:end] * (1 + argument % 3) + data[end:]
        elif kind == "insert":
            token = TOKENS[argument % len(TOKENS)].encode("utf-8", "surrogatepass")
            data = data[:at] + token + data[at:]
        elif kind == "raw":
            data = data[:at] + RAW_BYTES[argument % len(RAW_BYTES)] + data[at:]
        elif kind == "number":  # the file's (position mod count)-th number becomes an edge case
            found = list(_NUMBER.finditer(data))
            if found:
                match = found[position % len(found)]
                data = (data[:match.start()] + NUMBERS[argument % len(NUMBERS)].encode()
                        + data[match.end():])
        elif kind == "json":
            data = _json_edit(data, position, argument)
        elif data:  # "byte": overwrite one byte with a printable character
            at = min(at, len(data) - 1)
            data = data[:at] + bytes([32 + argument % 95]) + data[at + 1:]
    return data


def random_mutations(rng: random.Random) -> list[Mutation]:
    """One to four mutations drawn with ``rng`` (what the hypothesis strategy draws, for the
    long benchmark run where hypothesis' bookkeeping per example would dominate)."""
    return [(rng.choice(KINDS), rng.randrange(1 << 16), rng.choice((1, 1, 2, 5, 20, 200)),
             rng.randrange(1 << 16)) for _ in range(rng.randint(1, 4))]


def mutations_strategy():
    """The hypothesis strategy of mutation lists (imported lazily: benchmarks need no hypothesis)."""
    from hypothesis import strategies as st
    one = st.tuples(st.sampled_from(KINDS), st.integers(0, 1 << 16),
                    st.sampled_from((1, 2, 5, 20, 200)), st.integers(0, 1 << 16))
    return st.lists(one, min_size=1, max_size=4)


class Hang(Exception):
    """An input took longer than the time limit."""


@contextmanager
def time_limit(seconds: float):
    """Raise :class:`Hang` in the block after ``seconds`` of wall time (SIGALRM, main thread)."""
    def on_alarm(signum, frame):
        raise Hang(f"no answer within {seconds} s")
    previous = signal.signal(signal.SIGALRM, on_alarm)
    signal.setitimer(signal.ITIMER_REAL, seconds)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)


# ---------------------------------------------------------------- the readers under test
def _read_grammar(path: Path):
    import psgs
    system = psgs.load(path)
    assert psgs.loads(psgs.dumps(system)) == system, "dumps/loads round trip changed the system"


def _read_actiongram(path: Path):
    import psgs
    ag = psgs.load(path, kind="actiongram")
    text = ag.to_text()
    text.encode("utf-8")  # a loaded actiongram can always be written
    assert psgs.Actiongram.from_text(text) == ag, "to_text/from_text round trip changed it"
    assert psgs.Actiongram.from_json(ag.to_json()) == ag, "to_json/from_json round trip changed it"
    for name, starts in ag.starts.items():  # times strictly increase (PAL's time grid needs it)
        assert all(a < b for a, b in zip(starts, starts[1:])), name


def _check_motion(motion):
    import numpy as np
    from kinetology import MotionFormatError, forward_kinematics
    assert np.isfinite(motion.values).all() and math.isfinite(motion.frame_rate)
    if motion.skeleton is not None and motion.frames:
        try:
            positions = forward_kinematics(motion)
        except MotionFormatError:  # documented: finite offsets that overflow
            return
        assert np.isfinite(positions).all()


def _read_bvh(path: Path):
    from kinetology.bvh import read_bvh
    _check_motion(read_bvh(path))


def _read_asf(path: Path):
    from kinetology.asf import read_asf
    skeleton = read_asf(path)
    assert skeleton.skeleton.joints[0].name == "root"


def _read_amc(path: Path):
    from kinetology.asf import read_amc, read_asf
    _check_motion(read_amc(path, asf=read_asf(SEEDS / "small.asf")))


def _read_codec(path: Path):
    from kinetology.codec import decompress
    _check_motion(decompress(path.read_bytes(), str(path)))


def _read_codec_body(path: Path):
    """The file is a decompressed base part: packed as the encoder packs it, then decoded
    (byte edits of LZMA data mostly stop at LZMA's own check; these reach the parser)."""
    import lzma

    from kinetology.codec import decompress, stream
    from kinetology.codec.varint import encode
    # a small dictionary: the decoder's (preset 9) is larger, so it reads this; preset 9e
    # itself would take 0.1 s and 670 MB a compression
    packed = lzma.compress(path.read_bytes(), format=lzma.FORMAT_RAW,
                           filters=[{"id": lzma.FILTER_LZMA2, "preset": 1}])
    _check_motion(decompress(stream.MAGIC + encode([len(packed)]) + packed, str(path)))


def _write_bvh_back(path: Path):
    """Read a BVH file; what ``format_bvh`` writes of it reads back to the same motion (or
    the writer refuses with a ValidationError, its documented error)."""
    import numpy as np
    from kinetology.bvh import parse_bvh, read_bvh
    from kinetology.bvh_writer import format_bvh
    from psgs.errors import ValidationError
    motion = read_bvh(path)
    try:
        text = format_bvh(motion)
    except ValidationError:
        return
    back = parse_bvh(text, source="written.bvh")
    assert sorted(back.channels) == sorted(motion.channels), "channels changed"
    for name in motion.channels:
        a, b = motion.column(name), back.column(name)
        assert np.allclose(a, b, rtol=1e-12, atol=1e-6), f"{name}: values changed"
    assert math.isclose(back.frame_rate, motion.frame_rate, rel_tol=1e-9), "frame rate changed"


def _compress_back(path: Path):
    """Read a BVH file and compress it at a rate-controlled error: what decodes keeps the
    ``max_error`` promise, measured again from the decoded values rather than taken from the
    stream's report (or the encoder refuses with its documented errors)."""
    from kinetology.bvh import read_bvh
    from kinetology.codec import compress, decompress, mean_errors
    from psgs.errors import ValidationError
    motion = read_bvh(path)
    try:
        data = compress(motion, max_error=0.5)
    except ValidationError:
        return
    back = decompress(bytes(data), "compressed.kin")
    assert back.channels == motion.channels and back.frames == motion.frames, "shape changed"
    if motion.frames:
        error = mean_errors(motion, back)[0]
        assert error <= 0.5 + 1e-9, f"mean error {error} over the promised 0.5"


def _read_events(path: Path):
    """An events table: read, written back as rows, and read again to the same actiongram."""
    from psgs.actiongram import read_events_csv
    from psgs import Actiongram
    ag = read_events_csv(path)
    rows = ag.to_events()
    assert Actiongram.from_events(rows, keep_repeats=ag.keep_repeats) == ag, \
        "to_events/from_events round trip changed it"


def _read_manifest(path: Path):
    from praxicon.datasets import read_dataset
    read_dataset(path)


def _read_truelabels(path: Path):
    from kinetology.labels import read_cmu_truelabels
    read_cmu_truelabels(path)


def _read_bandai_label(path: Path):
    import shutil

    from kinetology.labels import read_bandai_json
    shutil.copytree(SEEDS / "bandai" / "cfg", path.parent / "cfg")
    (path.parent / "data").mkdir()
    label = path.parent / "data" / "dataset-1_bow_happy_001.json"
    label.write_bytes(path.read_bytes())
    read_bandai_json(label, duration=2.0)


def _praxicon_folder(path: Path, target: str) -> Path:
    """A copy of the seed praxicon with ``target`` replaced by the fuzzed bytes."""
    import shutil
    folder = path.parent / "praxicon"
    shutil.copytree(SEEDS / "praxicon", folder)
    (folder / target).write_bytes(path.read_bytes())
    return folder


def _morpheme_system(channels: dict[str, tuple[str, ...]]) -> str:
    """A grammar system of the shape PAL learns: per channel one cycle of its morpheme,
    the channels' steps synchronised."""
    lines = ["psgs pal", "mode parallel", "unsynchronised free", ""]
    for channel, kinetemes in channels.items():
        c = channel.replace(".", "_")
        lines += [f"component {c} start S_{c}", f"  more_{c}: S_{c} -> N_{c} S_{c}",
                  f"  last_{c}: S_{c} -> N_{c}",
                  f"  body_{c}: N_{c} -> " + " ".join(f'"{k}"' for k in kinetemes), ""]
    lines.append("sync")
    for rule in ("more", "last", "body"):
        lines.append("  (" + ", ".join(f"{rule}_{c.replace('.', '_')}" for c in channels) + ")")
    return "\n".join(lines) + "\n"


def praxicon_seed():
    """The praxicon the praxicon surfaces mutate: two learnt actions sharing a pattern, one
    failed action, and descriptions, at the current format versions.

    Written into ``tests/data/fuzz/praxicon`` by :func:`write_praxicon_seed`
    (``python tests/fuzz_support.py``); a test checks that the stored folder is what this
    writes, so a format change that makes it stale fails there instead of leaving every
    mutated folder refused as "another version".
    """
    from praxicon.description import ActionDescription, Descriptions, Spread
    from praxicon.records import (ActionRecord, ChannelMorpheme, JointRecord, PerformanceRecord,
                                  Praxicon, Settings)
    settings = Settings.make("pal", {"min_copies": 3, "seeds": 3})
    joints = ("hips", "arm", "leg", "head")
    actions, keys = [], []
    for name, shift in (("moves.step", 1), ("moves.wave", 0)):
        cycle = ("G", "R", "Y", "B")
        channels = {"arm.rx": cycle[shift:] + cycle[:shift], "arm.rz": cycle,
                    "leg.rx": cycle[2:] + cycle[:2]}
        morphemes = {c: ChannelMorpheme(k, (0.25, 0.3, 0.25, 0.2),
                                        (38.5, -42.25, -33.0, 36.75), 10 + shift)
                     for c, k in channels.items()}
        takes = tuple(PerformanceRecord(f"{name[6:]}_{i}.bvh", None if i else 0.5,
                                        None if i else 4.0, "moves.csv", used=True)
                      for i in range(2))
        actions.append(ActionRecord(
            name, "moves", name[6:], status="ok", performances=takes, learnt_from=(0, 1),
            actuators=("arm", "leg"),
            joints=(JointRecord("arm", tuple((c, morphemes[c]) for c in ("arm.rx", "arm.rz"))),
                    JointRecord("leg", (("leg.rx", morphemes["leg.rx"]),))),
            inducer="pal", params=settings.params, system=_morpheme_system(channels),
            component_names=tuple((c, c.replace(".", "_")) for c in channels),
            frame_rate=30.0, skeleton_source=takes[0].file, all_joints=joints,
            mean_pose=(("arm.rx", 12.0725), ("arm.rz", 1.25), ("hips.rz", 0.0085),
                       ("leg.rx", -0.205))))
        keys.append((name, f"{sum(map(ord, name)):064x}"))
    actions.insert(0, ActionRecord("moves.bow", "moves", "bow", "happy",
                                   reason="1 usable performance (at least 2 needed)",
                                   problems=("bow_2.bvh: not a BVH file (line 1, column 1)",),
                                   performances=(PerformanceRecord("bow_1.bvh", used=True),
                                                 PerformanceRecord("bow_2.bvh", used=False))))
    features = ("arm.rx:pose", "arm.rx:spread", "leg.rx:pose", "tempo")
    groups = (("arm", 4.5), ("leg", 3.25), ("tempo", 2.0))

    def described(window: float) -> Descriptions:
        spread = Spread(features, (10.0, 20.0, 5.0, 0.5), ((0.5, -0.25, 0.125, 0.0),),
                        (0.25, 0.5, 0.75, 1.0), 9.5, 1.5, window, limits=groups)
        described = Descriptions(tuple(ActionDescription(a.name, features,
                                                         (1.0, 2.0, -3.0, 0.5),
                                                         (0.5, 1.0, 0.25, 0.125), 2, window)
                                       for a in actions if a.learnt), spread)
        if window:
            return described
        # the whole takes' with a family of both learnt actions, so that the fuzzing of
        # descriptions.json reaches the families' fields too
        family = Descriptions((ActionDescription("moves.m", features, (1.0, 2.0, -3.0, 0.5),
                                                 (0.75, 1.5, 0.5, 0.25), 4),), spread)
        return Descriptions(described.actions, spread, family, ("moves.m", "moves.m"))

    return Praxicon(tuple(actions), settings, ("moves.csv",), tuple(keys), described(0.0),
                    described(2.0))


def write_praxicon_seed(folder: Path = SEEDS / "praxicon") -> None:
    """Write :func:`praxicon_seed` into ``folder`` with ``praxicon.dump`` (replacing what
    was there)."""
    import shutil

    from praxicon import dump
    shutil.rmtree(folder, ignore_errors=True)
    dump(praxicon_seed(), folder)


def _read_praxicon(folder: Path):
    from praxicon import load
    from praxicon.records import Praxicon
    from praxicon.shared import shared_patterns
    praxicon = load(folder)
    assert Praxicon.from_json(praxicon.to_json()) == praxicon, "to_json/from_json changed it"
    shared_patterns(praxicon)


def _read_praxicon_index(path: Path):
    _read_praxicon(_praxicon_folder(path, "index.json"))


def _read_praxicon_record(path: Path):
    _read_praxicon(_praxicon_folder(path, "records/moves.wave.json"))


def _read_praxicon_descriptions(path: Path):
    _read_praxicon(_praxicon_folder(path, "descriptions.json"))


@dataclass(frozen=True)
class Reader:
    """A reader under test: its seed files, the suffix it reads, the errors it documents."""

    name: str
    seeds: tuple[str, ...]
    suffix: str
    run: Callable[[Path], None]
    errors: Callable[[], tuple[type[BaseException], ...]]


def _psgs_errors():
    import psgs
    return (psgs.FormatError, psgs.ValidationError)


def _kinetology_errors():
    from kinetology import MotionFormatError
    return (MotionFormatError,)


def _dataset_errors():
    from praxicon.datasets import DatasetError
    return (DatasetError,)


def _praxicon_errors():  # praxicon.load: one PraxiconError line for a damaged folder
    from praxicon.records import PraxiconError
    return (PraxiconError,)


READERS = {r.name: r for r in (
    Reader("grammar", ("counting.psgs", "idling.psgs", "pcgs_returning.psgs"), ".psgs",
           _read_grammar, _psgs_errors),
    Reader("actiongram-text", ("small.txt",), ".txt", _read_actiongram, lambda: _psgs_errors()[:1]),
    Reader("actiongram-json", ("small.json",), ".json", _read_actiongram,
           lambda: _psgs_errors()[:1]),
    Reader("bvh", ("small.bvh",), ".bvh", _read_bvh, _kinetology_errors),
    Reader("asf", ("small.asf",), ".asf", _read_asf, _kinetology_errors),
    Reader("amc", ("small_1.amc",), ".amc", _read_amc, _kinetology_errors),
    Reader("codec", ("small.kin", "small_residual.kin"), ".kin", _read_codec,
           _kinetology_errors),
    Reader("codec-body", ("small.kinbody",), ".bin", _read_codec_body, _kinetology_errors),
    Reader("bvh-write", ("small.bvh",), ".bvh", _write_bvh_back, _kinetology_errors),
    Reader("codec-write", ("small.bvh",), ".bvh", _compress_back, _kinetology_errors),
    Reader("events-csv", ("small_events.csv",), ".csv", _read_events, _psgs_errors),
    Reader("manifest-csv", ("small_manifest.csv",), ".csv", _read_manifest, _dataset_errors),
    Reader("manifest-toml", ("small_manifest.toml",), ".toml", _read_manifest,
           _dataset_errors),
    Reader("truelabels", ("small_truelabels.txt",), ".txt", _read_truelabels,
           _kinetology_errors),
    Reader("bandai-label", ("bandai/data/dataset-1_bow_happy_001.json",), ".json",
           _read_bandai_label, _kinetology_errors),
    Reader("praxicon-index", ("praxicon/index.json",), ".json", _read_praxicon_index,
           _praxicon_errors),
    Reader("praxicon-record", ("praxicon/records/moves.wave.json",), ".json",
           _read_praxicon_record, _praxicon_errors),
    Reader("praxicon-descriptions", ("praxicon/descriptions.json",), ".json",
           _read_praxicon_descriptions, _praxicon_errors),
)}


def seed_bytes(reader: Reader, index: int) -> bytes:
    """The bytes of one of ``reader``'s seed files (``index`` wraps around)."""
    return (SEEDS / reader.seeds[index % len(reader.seeds)]).read_bytes()


def outcome(reader: Reader, data: bytes, directory: Path | None = None,
            limit: float = TIME_LIMIT) -> str:
    """Run ``reader`` on ``data`` written to a file: ``"ok"``, ``"error"`` (documented) or raise.

    Raises :class:`Hang` past ``limit`` seconds, and lets any other exception through: that
    is the finding.
    """
    with tempfile.TemporaryDirectory(dir=directory) as tmp:
        path = Path(tmp) / f"fuzz{reader.suffix}"
        path.write_bytes(data)
        try:
            with time_limit(limit):
                reader.run(path)
        except reader.errors():
            return "error"
    return "ok"


if __name__ == "__main__":  # python tests/fuzz_support.py: write the praxicon seed folder anew
    import sys

    # run as a script, this file's folder comes first on the path, and its praxicon/ test
    # folder would hide the praxicon package: the repository's root is looked in instead
    sys.path[0] = str(Path(__file__).resolve().parents[1])
    write_praxicon_seed()
