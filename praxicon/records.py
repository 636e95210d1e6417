"""Typed praxicon records: what the praxicon keeps per action, and the praxicon as a whole.

An :class:`ActionRecord` is one action as learnt (where it comes from, the joints that take
part, per actuator channel its :class:`ChannelMorpheme`, the grammar system's text, the mean
pose); a :class:`Praxicon` is every record of a folder with the settings and datasets it was
built from. Both are frozen values: fields are tuples, and what JSON writes as an object is
a tuple of ``(key, value)`` pairs sorted by key (so a value read back from disk equals the one
learnt in memory, field for field). ``to_json`` gives plain JSON values, ``from_json`` reads
them back, with a one-line :class:`PraxiconError` naming what is wrong.

Versioning
----------
:data:`FORMAT_VERSION` is the version of what a record holds, written in the folder's
``index.json`` (``"version"``) and part of every record's input key. Any change to the
fields (one added, removed, or read differently) bumps it. A folder of an earlier version is
refused by :func:`praxicon.load` with one line that names the command that rebuilds it
(:data:`REBUILD`), and ``psgs praxicon build`` on such a folder learns every action again
(the input keys differ), which rewrites it at this version; of a later version, both refuse
it (a later psgs wrote it: upgrade psgs).

A further per-action description (e.g. what recognition learns) is added as one more
optional field of :class:`ActionRecord` holding a frozen value with its own
``to_json``/``from_json``; ``to_json`` writes its key only when it is set, ``from_json``
reads a missing key as ``None``, and the version is bumped with it.
"""

from __future__ import annotations

from dataclasses import dataclass

from kinetology.motion import FRAME_RATE_RANGE
from psgs.errors import NotFound, PSGSError, ValidationError

from ._description_json import FieldError, check_named_alike
from ._errors import DAMAGED, REBUILD
from ._record_checks import MAX_NAME_BYTES, lookup_problem, name_problem
from ._values import settings_fields
from .description import DescriptionError, Descriptions
from .jsonvalues import Fields, as_dict, one_each, pairs as _pairs, written_by

__all__ = ["FORMAT", "FORMAT_VERSION", "REBUILD", "FRAME_RATES", "PraxiconError",
           "PerformanceRecord", "ChannelMorpheme", "JointRecord", "ActionRecord", "Praxicon",
           "Settings", "check_index", "name_problem", "MAX_NAME_BYTES"]

#: The ``"format"`` of a praxicon's ``index.json``.
FORMAT = "psgs-praxicon"
#: The version of what a record holds (see the module's versioning rule).
FORMAT_VERSION = 3
#: Lowest and highest frame rate (frames per second) a learnt record may hold: the rates
#: kinetology reads motion at (motion capture records at 24 fps to a few kHz; the shared data
#: at 30 and 120); generation makes rate x seconds frames, so a rate far outside is a damaged
#: record, not a recording.
FRAME_RATES = FRAME_RATE_RANGE
class PraxiconError(PSGSError, ValueError):
    """A praxicon folder, index or record that cannot be read; the message is one line.

    Examples
    --------
    >>> ActionRecord.from_json({"name": "a"}, where="records/a.json")
    Traceback (most recent call last):
    ...
    praxicon.records.PraxiconError: records/a.json: not a praxicon record (no 'status')
    """


@dataclass(frozen=True)
class Settings:
    """How every action is learnt: the inducer by name and its parameters, segmentation.

    ``params`` and ``segmentation`` are (name, value) pairs (a list of them or a dict is kept
    as a tuple of pairs). ``min_performances`` (2): an action with fewer usable performances
    fails with that reason (one performance cannot show what repeats across them).
    """

    inducer: str = "pal"
    params: tuple[tuple[str, object], ...] = ()
    segmentation: tuple[tuple[str, object], ...] = ()
    min_performances: int = 2

    def __post_init__(self) -> None:
        # copied into tuples (a list or a dict given is not shared with the caller, who could
        # change the settings of a praxicon already built); np.int64 kept as the int it holds
        for name, value in zip(("params", "segmentation", "min_performances"), settings_fields(
                self.inducer, self.params, self.segmentation, self.min_performances)):
            object.__setattr__(self, name, value)

    @classmethod
    def make(cls, inducer: str = "pal", params: dict | None = None,
             segmentation: dict | None = None, min_performances: int = 2) -> "Settings":
        """Settings from plain dicts (sorted, so equal settings compare and hash equal)."""
        return cls(inducer, tuple(sorted((params or {}).items())),
                   tuple(sorted((segmentation or {}).items())), min_performances)

    def to_dict(self) -> dict:
        """The settings as plain JSON values (for index.json)."""
        return {"inducer": self.inducer, "params": dict(self.params),
                "segmentation": dict(self.segmentation),
                "min_performances": self.min_performances}

    @classmethod
    def from_dict(cls, value, where: str = "settings") -> "Settings":
        """Read :meth:`to_dict`'s value back (:class:`~praxicon.records.PraxiconError` when
        malformed).

        Examples
        --------
        >>> s = Settings.make("pal", {"min_copies": 3})
        >>> Settings.from_dict(s.to_dict()) == s
        True
        """
        ok = (isinstance(value, dict) and isinstance(value.get("inducer"), str)
              and isinstance(value.get("params"), dict)
              and isinstance(value.get("segmentation"), dict)
              and type(value.get("min_performances")) is int)
        if not ok:
            raise PraxiconError(f"{where}: 'settings' must hold inducer, params, segmentation "
                                f"and min_performances")
        # JSON lists come back as lists; the settings made from a command line hold the same
        try:
            return cls.make(value["inducer"], value["params"], value["segmentation"],
                            value["min_performances"])
        except ValidationError as exc:  # min_performances 0: the folder's error, as the rest
            raise PraxiconError(f"{where}: {exc}") from None


def _count(n: int, noun: str) -> str:
    return f"{n} {noun}{'' if n == 1 else 's'}"


def _Json(value, where: str, what: str) -> Fields:
    """Typed access to a JSON object whose errors are :class:`PraxiconError` s."""
    return Fields(value, where, what, PraxiconError)


# -- the records --------------------------------------------------------------------------------
@dataclass(frozen=True)
class PerformanceRecord:
    """One performance of an action as the record keeps it.

    ``file`` and optional ``start``/``stop`` seconds and ``label`` (the label file the span
    came from); ``used`` says whether it was learnt from (``None`` before the files were read,
    e.g. for an action that failed earlier).

    Examples
    --------
    >>> p = PerformanceRecord("a.bvh", 0.5, 2.0, "m.csv", used=True)
    >>> PerformanceRecord.from_json(p.to_json()) == p
    True
    """

    file: str
    start: float | None = None
    stop: float | None = None
    label: str | None = None
    used: bool | None = None

    def to_json(self) -> dict:
        """The performance as plain JSON values."""
        out = {"file": self.file, "start": self.start, "stop": self.stop, "label": self.label}
        if self.used is not None:
            out["used"] = self.used
        return out

    @classmethod
    def from_json(cls, value, where: str = "performance") -> "PerformanceRecord":
        """Read :meth:`to_json`'s value back (:class:`PraxiconError` when malformed)."""
        j = _Json(value, where, "performance")
        used = j.value.get("used")
        if used is not None and not isinstance(used, bool):
            raise j._bad("used", "true or false")
        # seconds as a build writes them: else generation cut a take at a negative frame
        start = j.bounded("start", j.number("start", True), 0)
        stop = j.bounded("stop", j.number("stop", True), 0)
        if start is not None and stop is not None and not start < stop:
            raise j._bad("stop", f"after its start {start}")
        return cls(j.text("file"), start, stop, j.text("label", True), used)


@dataclass(frozen=True)
class ChannelMorpheme:
    """The morpheme of one actuator channel: its kinetemes, and per kineteme its typical
    duration (seconds) and angular displacement (degrees), medians over ``occurrences``
    exact copies of the pattern in the performances (``None`` when there was none).

    Examples
    --------
    >>> m = ChannelMorpheme(("B", "Y"), (0.5, 0.5), (30.0, -30.0), 4)
    >>> m.to_json()["kinetemes"], ChannelMorpheme.from_json(m.to_json()) == m
    (['B', 'Y'], True)
    """

    kinetemes: tuple[str, ...]
    durations: tuple[float, ...] | None = None
    displacements: tuple[float, ...] | None = None
    occurrences: int = 0

    def to_json(self) -> dict:
        """The morpheme as plain JSON values."""
        return {"kinetemes": list(self.kinetemes),
                "durations": None if self.durations is None else list(self.durations),
                "displacements": None if self.displacements is None else list(self.displacements),
                "occurrences": self.occurrences}

    @classmethod
    def from_json(cls, value, where: str = "morpheme") -> "ChannelMorpheme":
        """Read :meth:`to_json`'s value back (:class:`PraxiconError` when malformed)."""
        j = _Json(value, where, "morpheme")
        kinetemes = j.texts("kinetemes")
        # typical seconds: 0 or less divided by zero or ran a kineteme backwards in generation
        durations = j.bounded("durations", j.numbers("durations", True), 0, strict=True)
        displacements = j.numbers("displacements", True)
        for key, got in (("durations", durations), ("displacements", displacements)):
            if got is not None and len(got) != len(kinetemes):
                raise PraxiconError(f"{where}: {key!r} has {len(got)} values for "
                                    f"{len(kinetemes)} kinetemes")
        occurrences = j.number("occurrences", True) or 0
        if not isinstance(occurrences, int) or occurrences < 0:
            raise j._bad("occurrences", "a whole number >= 0")
        return cls(kinetemes, durations, displacements, occurrences)


@dataclass(frozen=True)
class JointRecord:
    """One actuator: its channels (in skeleton order) and each one's morpheme.

    Examples
    --------
    >>> j = JointRecord("arm", (("arm.rx", ChannelMorpheme(("B", "Y"))),))
    >>> j.channels, j.morpheme("arm.rx").kinetemes
    (('arm.rx',), ('B', 'Y'))
    """

    name: str
    morphemes: tuple[tuple[str, ChannelMorpheme], ...]

    @property
    def channels(self) -> tuple[str, ...]:
        """The joint's actuator channels."""
        return tuple(c for c, _ in self.morphemes)

    def morpheme(self, channel: str) -> ChannelMorpheme:
        """The morpheme of ``channel`` (KeyError when it is not one of the joint's)."""
        for c, m in self.morphemes:
            if c == channel:
                return m
        raise NotFound(channel)

    def to_json(self) -> dict:
        """The joint as plain JSON values (its name is the key it is stored under)."""
        return {"channels": list(self.channels),
                "morphemes": {c: m.to_json() for c, m in self.morphemes}}

    @classmethod
    def from_json(cls, name: str, value, where: str = "joint") -> "JointRecord":
        """Read :meth:`to_json`'s value of joint ``name`` back."""
        j = _Json(value, where, "joint")
        channels = j.texts("channels")
        morphemes = j.object("morphemes")
        if problem := one_each(morphemes, channels, "morpheme", "channel"):
            raise PraxiconError(f"{where}: {problem}")
        return cls(name, tuple((c, ChannelMorpheme.from_json(morphemes[c], f"{where}: {c}"))
                               for c in channels))


_BASE = ("name", "dataset", "content", "style", "status", "reason", "problems", "performances")


@dataclass(frozen=True)
class ActionRecord:
    """Everything the praxicon keeps of one action (the schema is in ``docs/praxicon.md``).

    Only a learnt action (``status == "ok"``) has what was learnt: ``actuators`` (joints in
    skeleton order), ``joints`` (one :class:`JointRecord` per actuator), the grammar
    ``system`` as text, ``mean_pose`` and the rest; a failed one has its ``reason``.
    Mapping-like fields (``params``, ``segmentation``, ``component_names``, ``mean_pose``)
    are ``(key, value)`` pairs sorted by key; :meth:`joint` and :meth:`morphemes` look
    things up by name.

    Examples
    --------
    >>> r = ActionRecord("m.wave", "m", "wave", status="failed", reason="1 usable performance",
    ...                  performances=(PerformanceRecord("a.bvh", used=True),))
    >>> r.learnt, ActionRecord.from_json(r.to_json()) == r
    (False, True)
    >>> r
    <ActionRecord 'm.wave': failed (1 usable performance), 1 performance>
    """

    name: str
    dataset: str
    content: str
    style: str | None = None
    status: str = "failed"
    reason: str | None = None
    problems: tuple[str, ...] = ()
    performances: tuple[PerformanceRecord, ...] = ()
    learnt_from: tuple[int, ...] = ()
    note: str | None = None
    actuators: tuple[str, ...] = ()
    joints: tuple[JointRecord, ...] = ()
    verdict: str = ""
    inducer: str | None = None
    params: tuple = ()
    system: str | None = None
    component_names: tuple[tuple[str, str], ...] = ()
    frame_rate: float | None = None
    skeleton_source: str | None = None
    all_joints: tuple[str, ...] = ()
    mean_pose: tuple[tuple[str, float], ...] = ()
    segmentation: tuple = ()

    @property
    def learnt(self) -> bool:
        """Whether the action was learnt (``status == "ok"``)."""
        return self.status == "ok"

    @property
    def file(self) -> str | None:
        """The name of the action's ``.psgs`` file in the folder (None without a system)."""
        return f"{self.name}.psgs" if self.system else None

    def joint(self, name: str) -> JointRecord:
        """The actuator ``name`` (KeyError when it is not one)."""
        for joint in self.joints:
            if joint.name == name:
                return joint
        raise NotFound(name)

    def morphemes(self) -> dict[str, ChannelMorpheme]:
        """Every actuator channel's morpheme, channel -> morpheme, actuators in order."""
        return {c: m for joint in self.joints for c, m in joint.morphemes}

    def __repr__(self) -> str:  # a summary, not the dataclass dump of the system and pose
        used = sum(bool(p.used) for p in self.performances)
        takes = _count(len(self.performances), "performance")
        if not self.learnt:
            why = self.reason if self.reason and self.reason.strip() else "no reason recorded"
            return f"<ActionRecord {self.name!r}: failed ({why}), {takes}>"
        joints = ", ".join(self.actuators[:4]) + (", ..." if len(self.actuators) > 4 else "")
        return (f"<ActionRecord {self.name!r}: learnt from {used} of {takes}, "
                f"{_count(len(self.actuators), 'actuator')} ({joints or 'none'}), "
                f"{_count(len(self.morphemes()), 'morpheme')}>")

    def __str__(self) -> str:  # the summary, then one line per actuator (at most six)
        lines = [repr(self)]
        for joint in self.joints[:6]:
            lines.append(f"  {joint.name}: " + "; ".join(
                f"{c.rsplit('.', 1)[-1]} {' '.join(m.kinetemes)}" for c, m in joint.morphemes))
        if len(self.joints) > 6:
            lines.append(f"  ... and {len(self.joints) - 6} more actuators")
        return "\n".join(lines)

    def to_json(self) -> dict:
        """The record as plain JSON values (what ``records/ACTION.json`` holds)."""
        out = {"name": self.name, "dataset": self.dataset, "content": self.content,
               "style": self.style, "status": self.status, "reason": self.reason,
               "problems": list(self.problems),
               "performances": [p.to_json() for p in self.performances]}
        if not self.learnt:
            return out
        out.update({
            "learnt_from": list(self.learnt_from), "note": self.note,
            "actuators": list(self.actuators),
            "joints": {j.name: j.to_json() for j in self.joints},
            "verdict": self.verdict, "inducer": self.inducer, "params": as_dict(self.params),
            "system": self.system, "component_names": dict(self.component_names),
            "frame_rate": self.frame_rate, "skeleton_source": self.skeleton_source,
            "all_joints": list(self.all_joints), "mean_pose": dict(self.mean_pose),
            "segmentation": as_dict(self.segmentation)})
        return out

    def index_entry(self) -> dict:
        """The record as ``index.json`` lists it: without the system text and the mean pose,
        with the ``.psgs`` file's name."""
        entry = {k: v for k, v in self.to_json().items() if k not in ("system", "mean_pose")}
        if self.system:
            entry["file"] = self.file
        return entry

    @classmethod
    def from_json(cls, value, where: str = "record") -> "ActionRecord":
        """Read :meth:`to_json`'s value back (:class:`PraxiconError` when malformed)."""
        j = _Json(value, where, "record")
        status = j.text("status")
        if status not in ("ok", "failed"):
            raise j._bad("status", "'ok' or 'failed'")
        base = dict(name=j.text("name"), dataset=j.text("dataset"), content=j.text("content"),
                    style=j.text("style", True), status=status, reason=j.text("reason", True),
                    problems=j.texts("problems"),
                    performances=tuple(PerformanceRecord.from_json(p, f"{where}: performance "
                                                                      f"{i + 1}")
                                       for i, p in enumerate(j.objects("performances"))))
        if status != "ok":
            return cls(**base)
        actuators = j.texts("actuators")
        joints = j.object("joints")
        if problem := one_each(joints, actuators, "joint", "actuator"):
            raise PraxiconError(f"{where}: {problem}")
        names = j.object("component_names")
        pose = j.object("mean_pose")
        j.items("component_names", lambda v: isinstance(v, str), "channel -> text")
        j.items("mean_pose", lambda v: isinstance(v, (int, float)) and not isinstance(v, bool),
                "channel -> number")
        learnt_from = j.numbers("learnt_from", whole=True)
        count = len(base["performances"])  # an index past them was an IndexError
        j.items("learnt_from", lambda i: 0 <= i < count, f"indices of its {count} performances")
        record = cls(**base, learnt_from=learnt_from, note=j.text("note", True),
                     actuators=actuators,
                     joints=tuple(JointRecord.from_json(a, joints[a], f"{where}: joint {a}")
                                  for a in actuators),
                     verdict=j.text("verdict", True) or "", inducer=j.text("inducer", True),
                     params=_pairs(j.object("params", True)), system=j.text("system", True),
                     component_names=tuple(sorted(names.items())),
                     frame_rate=_frame_rate(j),
                     skeleton_source=j.text("skeleton_source"),
                     all_joints=j.texts("all_joints"), mean_pose=tuple(sorted(pose.items())),
                     segmentation=_pairs(j.object("segmentation", True)))
        # a key generation finds nothing under: refused here, not when generation poses 0
        if problem := lookup_problem(record):
            raise PraxiconError(f"{where}: {problem}: {DAMAGED}")
        return record


def _frame_rate(j: Fields) -> float:
    rate = j.number("frame_rate")
    if not FRAME_RATES[0] <= rate <= FRAME_RATES[1]:  # NaN is neither
        raise j._bad("frame_rate", f"frames per second from {FRAME_RATES[0]:g} to "
                                   f"{FRAME_RATES[1]:g}")
    return rate


@dataclass(frozen=True)
class Praxicon:
    """A whole praxicon: its records sorted by name, the settings and datasets it was built
    from, each record's input key (what resume compares; ``""`` when unknown), and the
    descriptions that recognition and parsing read (learnt by the build after the actions).

    Read one from a folder with :func:`praxicon.load`, write one with :func:`praxicon.dump`;
    ``to_json`` is the whole praxicon as one JSON value (the index with every full record).

    Examples
    --------
    >>> px = Praxicon((ActionRecord("m.a", "m", "a"),), Settings.make(), ("m.csv",))
    >>> px.names, px["m.a"].learnt, px.counts
    (('m.a',), False, {'actions': 1, 'learnt': 0, 'failed': 1})
    >>> print(px)
    <Praxicon: 0 actions learnt of 1, 1 dataset, inducer pal, no descriptions>
      failed: m.a
    >>> Praxicon.from_json(px.to_json()) == px
    True
    """

    actions: tuple[ActionRecord, ...]
    settings: Settings
    datasets: tuple[str, ...] = ()
    keys: tuple[tuple[str, str], ...] = ()
    #: what recognition reads: every learnt action's description of whole takes, with the
    #: spread the actions share (``praxicon.recognition``); None before they are learnt
    descriptions: Descriptions | None = None
    #: the same for windows of a recording (``praxicon.parsing``)
    window_descriptions: Descriptions | None = None

    def __post_init__(self) -> None:
        names = [a.name for a in self.actions]
        if names != sorted(set(names)):
            raise PraxiconError("a praxicon's actions must have distinct names, sorted")

    @property
    def names(self) -> tuple[str, ...]:
        """Every action's name, sorted."""
        return tuple(a.name for a in self.actions)

    @property
    def counts(self) -> dict:
        """How many actions, learnt and failed."""
        learnt = sum(a.learnt for a in self.actions)
        return {"actions": len(self.actions), "learnt": learnt,
                "failed": len(self.actions) - learnt}

    def __repr__(self) -> str:  # a summary, not the dataclass dump of every record
        described = (f"descriptions format {self.descriptions.actions[0].version}"
                     if self.descriptions is not None and self.descriptions.actions
                     else "no descriptions")
        return (f"<Praxicon: {self.counts['learnt']} actions learnt of {len(self.actions)}, "
                f"{_count(len(self.datasets), 'dataset')}, inducer {self.settings.inducer}, "
                f"{described}>")

    def __str__(self) -> str:  # the summary, then the learnt and the failed actions by name
        lines = [repr(self)]
        for what, names in (("learnt", [a.name for a in self.actions if a.learnt]),
                            ("failed", [a.name for a in self.actions if not a.learnt])):
            if names:
                shown = ", ".join(names[:4]) + (f" and {len(names) - 4} more"
                                                if len(names) > 4 else "")
                lines.append(f"  {what}: {shown}")
        return "\n".join(lines)

    def __getitem__(self, name: str) -> ActionRecord:
        for action in self.actions:
            if action.name == name:
                return action
        shown = ", ".join(self.names[:8]) + (" ..." if len(self.names) > 8 else "")
        raise PraxiconError(f"no action {name!r} in the praxicon (actions: {shown})")

    def __contains__(self, name: object) -> bool:
        return name in self.names

    def key(self, name: str) -> str:
        """The input key of action ``name`` (``""`` when unknown)."""
        return dict(self.keys).get(name, "")

    def index(self) -> dict:
        """What ``index.json`` holds: the records without system texts and mean poses."""
        return {"format": FORMAT, "version": FORMAT_VERSION, "datasets": list(self.datasets),
                "settings": self.settings.to_dict(), "counts": self.counts,
                "actions": [a.index_entry() for a in self.actions]}

    def to_json(self) -> dict:
        """The whole praxicon as plain JSON values: the index with every full record, and the
        records' input keys."""
        out = {**self.index(), "actions": [a.to_json() for a in self.actions],
               "keys": dict(self.keys)}
        if self.descriptions is not None and self.window_descriptions is not None:
            out["descriptions"] = {"takes": self.descriptions.to_dict(),
                                   "windows": self.window_descriptions.to_dict()}
        return out

    @classmethod
    def from_json(cls, value, where: str = "praxicon") -> "Praxicon":
        """Read :meth:`to_json`'s value back (:class:`PraxiconError` when malformed or of
        another version)."""
        check_index(value, where)
        j = _Json(value, where, "praxicon")
        keys = j.object("keys", True) or {}
        j.items("keys", lambda k: isinstance(k, str), "action -> text")
        actions = sorted((ActionRecord.from_json(a, f"{where}: action {i + 1}")
                          for i, a in enumerate(j.objects("actions"))), key=lambda a: a.name)
        names = [a.name for a in actions]
        if len(set(names)) != len(names):
            raise PraxiconError(f"{where}: an action is listed twice")
        described = j.object("descriptions", True)
        takes = windows = None
        if described is not None:
            try:
                takes = Descriptions.from_dict(described["takes"])
                windows = Descriptions.from_dict(described["windows"])
                check_named_alike(takes, windows)
            except (KeyError, TypeError, DescriptionError, FieldError) as exc:
                raise PraxiconError(f"{where}: descriptions: {exc}") from None
        return cls(tuple(actions), Settings.from_dict(j.object("settings"), where),
                   j.texts("datasets"), tuple(sorted((n, keys[n]) for n in names if n in keys)),
                   takes, windows)


def check_index(index, where: str) -> None:
    """Raise :class:`PraxiconError` unless ``index`` is a praxicon index of this version.

    Examples
    --------
    >>> check_index({"format": "psgs-praxicon", "version": 1}, "px/index.json")
    Traceback (most recent call last):
    ...
    praxicon.records.PraxiconError: px/index.json: a praxicon of format version 1; this psgs reads version 3: rebuild it with 'psgs praxicon build DATASET... -o FOLDER'
    """
    if not isinstance(index, dict) or index.get("format") != FORMAT:
        raise PraxiconError(f"{where}: not a praxicon index (its format is not {FORMAT!r})")
    version = index.get("version")
    if age := written_by(version, FORMAT_VERSION):  # a later one's is not rebuilt over
        raise PraxiconError(f"{where}: a praxicon of format version {version!r}; this psgs "
                            f"reads version {FORMAT_VERSION}: " + ("a later psgs wrote it; "
                            "upgrade psgs to read it" if age == "later" else
                            f"rebuild it with '{REBUILD}'"))
