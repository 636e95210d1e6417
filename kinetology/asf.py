"""Reading Acclaim ASF skeletons and AMC motions (the CMU database's format).

An ASF bone is turned into a BVH-style :class:`~kinetology.motion.Joint`
placed at the bone's *start*: its offset is the parent bone's vector
(``direction * length``, in the ASF's global rest frame), its fixed rotation
``axis`` is the ASF ``axis`` and its channels are the bone's ``dof``. With the
local rotation ``C @ R @ C.T`` (``C`` from ``axis``) forward kinematics gives
the ASF positions exactly, and a skeleton converted to BVH by the usual tools
(joint ``LeftUpLeg`` = bone ``lfemur``) lines up joint for joint. ``axis ...
XYZ`` means the matrix ``Rz @ Ry @ Rx`` (x applied first), for the axis and
for the dof angles alike.

An AMC file without its ASF still reads: channel names then come from a
``SkeletonJoints.key`` beside it (lines ``bone dof dof ..``) when there is one,
else they are ``bone.1``, ``bone.2`` .. (``root`` gets ``tx ty tz rx ry rz``).
"""

from __future__ import annotations

from dataclasses import dataclass
from numbers import Real
from pathlib import Path
from types import MappingProxyType

import numpy as np

from psgs._foundation.text import decimal, split_lines
from psgs.errors import ValidationError

from ._amc_frames import read_at_once, read_by_lines
from ._file_motion import build_motion, file_text
from ._frame_block import Lines
from .motion import (FRAME_RATE_RANGE, Joint, Motion, MotionFormatError, Skeleton, as_path,
                     counted, rebuilt)
from .textblocks import token_column

__all__ = ["AsfSkeleton", "read_asf", "parse_asf", "read_amc", "parse_amc", "find_asf"]

_DOFS = {"tx", "ty", "tz", "rx", "ry", "rz"}
_DEFAULT_FRAME_RATE = 120.0  # the CMU database's capture rate; AMC files do not say


@dataclass(frozen=True)
class AsfSkeleton:
    """What an ASF file says: bone dofs and the skeleton in joint form.

    Parameters
    ----------
    dofs : types.MappingProxyType
        Bone name to its dof names (``"rx"``, ...) in AMC value order, ``"root"`` included.
    skeleton : Skeleton
        The bones as joints (each bone a joint at its start, its end an end site).
    length_scale : float
        The ``:units length`` value.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> folder = Path(tempfile.mkdtemp())
    >>> _ = (folder / "07.asf").write_text(''':root
    ...   order TX TY TZ RX RY RZ
    ...   axis XYZ
    ... :bonedata
    ...   begin
    ...     name femur
    ...     direction 0 -1 0
    ...     length 10
    ...     axis 0 0 0 XYZ
    ...     dof rx
    ...   end
    ... :hierarchy
    ...   begin
    ...     root femur
    ...   end
    ... ''')
    >>> bones = read_asf(folder / "07.asf")
    >>> dict(bones.dofs)
    {'root': ('tx', 'ty', 'tz', 'rx', 'ry', 'rz'), 'femur': ('rx',)}
    """

    dofs: MappingProxyType  # read-only: bone name -> tuple of dof names, in AMC value order ("root" included)
    skeleton: Skeleton
    length_scale: float  # the :units length (inches per unit is 1/scale in CMU's files)

    def __post_init__(self) -> None:  # a dict given is copied: the value stays read-only
        object.__setattr__(self, "dofs", MappingProxyType(dict(self.dofs)))

    __reduce__ = rebuilt  # pickle and copy.deepcopy cannot take the mappingproxy


def read_asf(path: str | Path) -> AsfSkeleton:
    """Read an ASF skeleton file (errors name ``file:line:col``); see :func:`parse_asf`.

    Parameters
    ----------
    path : str or Path
        The ``.asf`` file.

    Returns
    -------
    AsfSkeleton

    Raises
    ------
    MotionFormatError
        For malformed text, naming ``file:line:col``.
    FileNotFoundError
        When the file does not exist.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> folder = Path(tempfile.mkdtemp())
    >>> _ = (folder / "07.asf").write_text(''':root
    ...   order TX TY TZ RX RY RZ
    ...   axis XYZ
    ... :bonedata
    ...   begin
    ...     name femur
    ...     direction 0 -1 0
    ...     length 10
    ...     axis 0 0 0 XYZ
    ...     dof rx
    ...   end
    ... :hierarchy
    ...   begin
    ...     root femur
    ...   end
    ... ''')
    >>> read_asf(folder / "07.asf").skeleton.names
    ('root', 'femur', 'femur.end')
    """
    path = as_path(path)
    return parse_asf(file_text(path), source=str(path))


def parse_asf(text: str, source: str = "<asf>") -> AsfSkeleton:
    """Parse ASF text into bone dofs and a :class:`Skeleton`.

    Parameters
    ----------
    text : str
        The contents of an ASF file.
    source : str, default "<asf>"
        The name errors give.

    Returns
    -------
    AsfSkeleton

    Raises
    ------
    MotionFormatError
        For malformed text, naming ``source:line:col``.

    Examples
    --------
    >>> parse_asf(":root\\n  order TX TY TZ RX RY RZ\\n", source="empty.asf")
    Traceback (most recent call last):
    ...
    kinetology.motion.MotionFormatError: empty.asf: no :bonedata bones
    """
    lines = split_lines(_without_bom(text))
    section = None
    root = {"order": ("tx", "ty", "tz", "rx", "ry", "rz"), "axis": "XYZ",
            "position": (0.0, 0.0, 0.0), "orientation": (0.0, 0.0, 0.0)}
    bones: dict[str, dict] = {}
    children: dict[str, list[str]] = {}
    named_at: dict[str, tuple] = {}  # bone -> where :hierarchy names it as a child
    current: dict | None = None
    scale = 1.0
    radians = False  # ':units angle rad': axis and orientation angles given in radians

    def fail(message, number, column=1):
        raise MotionFormatError(message, source=source, line=number, column=column)

    def after(raw):  # the column just after a line's last word (before a comment)
        return len(raw.split("#", 1)[0].rstrip()) + 1

    def numbers(parts, count, number, raw):
        """``parts[1:count + 1]`` as floats; an error names the column in ``raw``."""
        given = parts[1:count + 1]
        if len(given) < count:
            fail(f"expected {counted(count, 'number')}, found {len(given)}", number)
        values = []
        for k, part in enumerate(given, 1):
            value = decimal(part)  # not float(): it takes '1_0' and other scripts' digits
            if value is None:
                fail(f"expected a number, found {part!r}", number, token_column(raw, k))
            if not np.isfinite(value):
                fail(f"number {part!r} is not finite", number, token_column(raw, k))
            values.append(value)
        return tuple(values)

    for number, raw in enumerate(lines, 1):
        line = raw.split("#", 1)[0].strip()
        if not line:
            continue
        if line.startswith(":"):
            head, *rest = line.split()
            section = head[1:].lower()
            continue
        parts = line.split()
        key = parts[0].lower()
        if section == "units" and key == "length":
            scale = numbers(parts, 1, number, raw)[0]
        elif section == "units" and key == "angle":
            if len(parts) < 2 or parts[1].lower() not in ("deg", "rad"):
                fail(f"angle unit must be deg or rad, not {' '.join(parts[1:])!r}", number,
                     token_column(raw, 1) if len(parts) > 1 else after(raw))
            radians = parts[1].lower() == "rad"
        elif section == "root":
            if key == "order":
                order = tuple(p.lower() for p in parts[1:])
                if (bad := _first_bad(order)) is not None:
                    fail(f"bad root order {' '.join(parts[1:])!r}", number,
                         token_column(raw, bad + 1))
                root["order"] = order
            elif key == "axis":
                if len(parts) < 2:
                    fail("root axis needs an order such as XYZ", number, after(raw))
                root["axis"] = _axis_order(parts[1], fail, number, token_column(raw, 1))
            elif key in ("position", "orientation"):
                root[key] = numbers(parts, 3, number, raw)
        elif section == "bonedata":
            if key == "begin":
                current = {"dof": (), "axis": (0.0, 0.0, 0.0), "order": "XYZ",
                           "direction": (0.0, 0.0, 0.0), "length": 0.0, "line": number}
            elif key == "end":
                if current is None or "name" not in current:
                    fail("bone without a name", number, token_column(raw, 0))
                twin = bones.get(current["name"])
                if twin is not None:  # the second would replace the first without a word
                    fail(f"two bones are named {current['name']!r} (the first at line "
                         f"{twin['name_at'][0]})", *current["name_at"])
                bones[current["name"]] = current
                current = None
            elif current is None:
                fail(f"{parts[0]!r} outside a begin/end bone block", number,
                     token_column(raw, 0))
            elif key == "name":
                current["name"] = (parts[1] if len(parts) > 1
                                   else fail("bone name missing", number, after(raw)))
                current["name_at"] = (number, token_column(raw, 1))
            elif key == "direction":
                current["direction"] = numbers(parts, 3, number, raw)
            elif key == "length":
                current["length"] = numbers(parts, 1, number, raw)[0]
                current["length_at"] = (number, token_column(raw, 1))
            elif key == "axis":
                current["axis"] = numbers(parts, 3, number, raw)
                current["order"] = _axis_order(parts[4] if len(parts) > 4 else "XYZ", fail,
                                               number, token_column(raw, 4)
                                               if len(parts) > 4 else 1)
            elif key == "dof":
                dof = tuple(p.lower() for p in parts[1:])
                if (bad := _first_bad(dof)) is not None:
                    fail(f"bad dof list {' '.join(parts[1:])!r}", number,
                         token_column(raw, bad + 1))
                current["dof"] = dof
        elif section == "hierarchy":
            if key in ("begin", "end"):
                continue
            children.setdefault(parts[0], []).extend(parts[1:])
            for k, child in enumerate(parts[1:], 1):
                if child not in bones:
                    fail(f"hierarchy names unknown bone {child!r}", number,
                         token_column(raw, k))
                if child in named_at:  # two parents, or a cycle: no tree to place
                    fail(f"hierarchy gives bone {child!r} a parent twice (first at line "
                         f"{named_at[child][0]})", number, token_column(raw, k))
                named_at[child] = (number, token_column(raw, k))
    if not bones:
        raise MotionFormatError("no :bonedata bones", source=source)
    if radians:
        root["orientation"] = tuple(np.degrees(root["orientation"]).tolist())
        for info in bones.values():
            info["axis"] = tuple(np.degrees(info["axis"]).tolist())
    joints: list[Joint] = []
    root_order = root["axis"][::-1]
    joints.append(Joint("root", None, root["position"],
                        tuple(f"root.{d}" for d in root["order"]), root_order,
                        root["orientation"]))
    dofs = {"root": tuple(root["order"])}
    placed: set[str] = set()
    last = [None]  # the bone placed last: where nesting too deeply is named

    def place(bone: str, parent_index: int, offset) -> None:
        if bone in placed:
            fail(f"bone {bone!r} appears twice in the hierarchy", *named_at[bone])
        placed.add(bone)
        last[0] = bone
        info = bones[bone]
        dofs[bone] = info["dof"]
        index = len(joints)
        joints.append(Joint(bone, parent_index, offset,
                            tuple(f"{bone}.{d}" for d in info["dof"]), info["order"][::-1],
                            info["axis"]))
        with np.errstate(over="ignore", invalid="ignore"):
            vector = tuple(float(info["length"]) * np.asarray(info["direction"]))
        if not np.isfinite(vector).all():  # only a length given can make it overflow
            fail(f"bone {bone!r}: length x direction overflows",
                 *info.get("length_at", (info["line"], 1)))
        kids = children.get(bone, [])
        for child in kids:
            place(child, index, vector)
        if not kids:
            joints.append(Joint(f"{bone}.end", index, vector, (), "ZYX", (0.0, 0.0, 0.0), True))

    try:
        for child in children.get("root", []):
            place(child, 0, (0.0, 0.0, 0.0))
    except RecursionError:  # bones are placed by recursion; real skeletons are shallow
        raise MotionFormatError("bones nested too deeply in :hierarchy", source=source,
                                line=named_at[last[0]][0],
                                column=named_at[last[0]][1]) from None
    missing = [b for b in bones if b not in placed]
    if missing:  # named where the first of them is defined
        fail(f"bones not in the hierarchy: {', '.join(missing)}", *bones[missing[0]]["name_at"])
    return AsfSkeleton(MappingProxyType(dofs), Skeleton(tuple(joints), length_unit=f"ASF units (length {scale})"),
                       scale)


def _without_bom(text: str) -> str:
    """``text`` without a leading UTF-8 byte-order mark (it is not part of the first word)."""
    return text[1:] if text.startswith("\ufeff") else text


def _axis_order(text: str, fail, number, column) -> str:
    order = text.upper()
    if sorted(order) != ["X", "Y", "Z"]:
        fail(f"bad axis order {text!r}", number, column)
    return order


def _first_bad(dofs) -> int | None:
    """The index of the first of ``dofs`` that is no dof or repeats one before it; None."""
    seen = set()
    for k, dof in enumerate(dofs):
        if dof not in _DOFS or dof in seen:
            return k
        seen.add(dof)
    return None


def find_asf(amc_path: Path) -> Path | None:
    """The ASF for ``SS_TT.amc``: ``SS.asf`` beside it, else the only ``.asf`` there.

    Parameters
    ----------
    amc_path : Path
        The AMC file.

    Returns
    -------
    Path or None
        None when there is no ``SS.asf`` and not exactly one ``.asf`` in the folder.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> folder = Path(tempfile.mkdtemp())
    >>> find_asf(folder / "07_01.amc") is None
    True
    >>> _ = (folder / "skeleton.asf").write_text("")
    >>> find_asf(folder / "07_01.amc").name
    'skeleton.asf'
    """
    stem = amc_path.stem.split("_")[0]
    candidate = amc_path.with_name(f"{stem}.asf")
    if candidate.is_file():
        return candidate
    others = sorted(amc_path.parent.glob("*.asf"))
    return others[0] if len(others) == 1 else None


def read_amc(path: str | Path, asf: str | Path | AsfSkeleton | None = "auto",
             frame_rate: float = _DEFAULT_FRAME_RATE) -> Motion:
    """Read an AMC motion; ``asf="auto"`` looks for its skeleton beside it.

    Without an ASF the channels are named from a ``SkeletonJoints.key`` beside the file
    (as in cmu-mocap6), else ``bone.1``, ``bone.2``, ...; the motion then has no skeleton.

    Parameters
    ----------
    path : str or Path
        The ``.amc`` file.
    asf : "auto", str, Path, AsfSkeleton or None, default "auto"
        The skeleton: found by :func:`find_asf` (``"auto"``), read from a path, given, or
        none.
    frame_rate : float, default 120.0
        AMC files do not state their rate; 120 fps is the CMU database's. From 0.1 to
        10,000 fps (:data:`~kinetology.motion.FRAME_RATE_RANGE`, as a BVH file's frame time).

    Returns
    -------
    Motion
        Channels ``bone.dof`` in the ASF's dof order, degrees (``:RADIANS`` files converted).

    Raises
    ------
    MotionFormatError
        For a malformed AMC, ASF or key file, naming ``file:line:col`` (see
        :func:`parse_amc`); for a file that is not UTF-8 or not a regular file.
    ValidationError
        For a frame rate outside :data:`~kinetology.motion.FRAME_RATE_RANGE`.
    FileNotFoundError
        When a file does not exist.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> folder = Path(tempfile.mkdtemp())
    >>> _ = (folder / "07.asf").write_text(''':root
    ...   order TX TY TZ RX RY RZ
    ...   axis XYZ
    ... :bonedata
    ...   begin
    ...     name femur
    ...     direction 0 -1 0
    ...     length 10
    ...     axis 0 0 0 XYZ
    ...     dof rx
    ...   end
    ... :hierarchy
    ...   begin
    ...     root femur
    ...   end
    ... ''')
    >>> _ = (folder / "07_01.amc").write_text(''':DEGREES
    ... 1
    ... root 0 0 0 0 0 0
    ... femur 10
    ... 2
    ... root 0 0 0 0 0 0
    ... femur 20
    ... ''')
    >>> walk = read_amc(folder / "07_01.amc")             # finds 07.asf beside it
    >>> walk
    Motion('...07_01.amc', 2 frames x 7 channels at 120 fps)
    >>> walk.column("femur.rx").tolist(), walk.skeleton.names
    ([10.0, 20.0], ('root', 'femur', 'femur.end'))
    """
    path = as_path(path)
    if isinstance(asf, str) and asf == "auto":
        found = find_asf(path)
        asf = read_asf(found) if found is not None else None
    elif isinstance(asf, (str, Path)):
        asf = read_asf(asf)
    elif asf is not None and not isinstance(asf, AsfSkeleton):
        raise ValidationError(f"asf must be 'auto', a path, an AsfSkeleton or None, not "
                              f"{type(asf).__name__}")
    dofs = asf.dofs if asf is not None else _key_file_dofs(path.with_name("SkeletonJoints.key"))
    return parse_amc(file_text(path), dofs=dofs,
                     skeleton=asf.skeleton if asf is not None else None, source=str(path),
                     frame_rate=frame_rate)


def _key_file_dofs(path: Path) -> dict | None:
    if not path.is_file():
        return None
    dofs = {}
    for number, line in enumerate(split_lines(file_text(path)), 1):
        parts = line.split()
        if parts:
            bad = next((k for k, p in enumerate(parts[1:], 1) if p.lower() not in _DOFS), None)
            if bad is not None:
                raise MotionFormatError(f"bad dof names in {line.strip()!r}", source=str(path),
                                        line=number, column=token_column(line, bad))
            dofs[parts[0]] = tuple(p.lower() for p in parts[1:])
    return dofs


def parse_amc(text: str, *, dofs: dict | None = None, skeleton: Skeleton | None = None,
              source: str = "<amc>", frame_rate: float = _DEFAULT_FRAME_RATE) -> Motion:
    """Parse AMC text. ``dofs`` (bone -> dof names) names the channels and checks counts.

    Frame 1's bone lines set the order every frame repeats; no bone appears twice in a frame.
    Frames are numbered one after another from the first frame's number (usually 1): a
    jump or a repeat would lose or double frames without a word, so it is an error at the
    number's line and column.

    Parameters
    ----------
    text : str
        The contents of an AMC file.
    dofs : dict, optional
        Bone name to its dof names (from an ASF); without it the root's channels are its six
        standard dofs and another bone's ``bone.1``, ``bone.2``, ...
    skeleton : Skeleton, optional
        Attached to the motion.
    source : str, default "<amc>"
        The name errors give.
    frame_rate : float, default 120.0
        Frames per second, from 0.1 to 10,000 (:data:`~kinetology.motion.FRAME_RATE_RANGE`).

    Returns
    -------
    Motion

    Raises
    ------
    MotionFormatError
        For malformed text, naming ``source:line:col``.
    ValidationError
        For a frame rate outside :data:`~kinetology.motion.FRAME_RATE_RANGE`.

    Examples
    --------
    >>> motion = parse_amc(":DEGREES\\n1\\nroot 1 2 3 0 0 0\\n2\\nroot 1 2 4 0 0 0\\n")
    >>> motion.channels, motion.column("root.tz").tolist()
    (('root.tx', 'root.ty', 'root.tz', 'root.rx', 'root.ry', 'root.rz'), [3.0, 4.0])
    >>> parse_amc("1\\nroot 1 2\\n2\\nroot 1\\n", source="bad.amc")
    Traceback (most recent call last):
    ...
    kinetology.motion.MotionFormatError: bad.amc:4:...
    >>> parse_amc("1\\nroot 1 2 3 0 0 0\\n3\\nroot 1 2 4 0 0 0\\n", source="gap.amc")
    Traceback (most recent call last):
    ...
    kinetology.motion.MotionFormatError: gap.amc:3:1: expected frame number 2, found '3' (frames are numbered one after another from 1)
    """
    if isinstance(frame_rate, bool) or not isinstance(frame_rate, Real):  # "120" was a TypeError
        raise ValidationError(f"frame rate must be a number, not {frame_rate!r}")
    slowest, fastest = FRAME_RATE_RANGE
    if not slowest <= frame_rate <= fastest:  # nan fails both comparisons
        raise ValidationError(f"frame rate {frame_rate!r} is outside {slowest:g} .. "
                              f"{fastest:g} frames a second")
    lines = Lines(_without_bom(text))  # the header's lines: the frames are read from the text
    start = 0
    degrees = True
    while start < len(lines) and (not lines[start].strip() or lines[start].lstrip()[0] in "#:"):
        if lines[start].strip().upper() == ":RADIANS":
            degrees = False
        start += 1
    # a chunk at a time, about twice the file's size in all; frames that way does not read
    # (malformed ones) are split into lines, a piece of frames at a time, to name the bad line
    read = read_at_once(lines, start, dofs, degrees)
    if read is not None:
        del text, lines  # let go before the motion is built (read_amc holds neither)
        return build_motion(read[0], read[1], frame_rate, skeleton, source, {"format": "amc"})
    values, names = read_by_lines(lines, start, dofs, degrees, source)
    del text, lines
    return build_motion(values, tuple(names), frame_rate, skeleton, source, {"format": "amc"})

