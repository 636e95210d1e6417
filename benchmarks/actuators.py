"""Which joints perform an action: PAL against two peers on labelled real motion.

Run from the repository root (heavy: under the lock on a shared machine):

    flock /tmp/heavy.lock python benchmarks/actuators.py            # everything
    python benchmarks/actuators.py --quick                           # a subset, ~1 minute
    python benchmarks/actuators.py --dataset bandai-1 --series bye   # one series

A **series** is several performances of one action, each kept apart: labelled spans of the
cmu-mocap6 takes (every span of one exercise of at least ``--min-seconds``), the takes of one
Bandai Namco dataset-1 content across its styles, the five takes of one dataset-2 content in
one style, and the two walks of CMU subject 02 (the tour's example). Every method gets the same
list of :class:`kinetology.Motion` performances and names the joints that take part:

* **PAL**: each performance segmented with kinetology's defaults, ``PAL().induce(list)``,
  reading ``Induction.actuators``. With a PAL that takes one actiongram only (an older PAL), the performances are joined into one motion, segmented, and the components mapped to
  joints by the dot rule: what a user could do then.
* **PAL (path)**: the ablation, ``PAL(evidence="path")`` (the same selection with angular path
  length in place of kineteme agreement) where PAL has that switch; "n/a" otherwise.
* **excursion rule**: a joint takes part when its angle moves more than ``--excursion`` degrees
  (default 10): per performance, the largest over the joint's rotation channels of the 5-95%
  range of the unwrapped, smoothed angle; the joint is named when the median over the
  performances exceeds the threshold. The table also gives the rule at the single threshold
  that is best in hindsight over the whole run (an upper bound for any fixed threshold).
* **stumpy**: ``stumpy.mstump`` on the performances' rotation channels (unwrapped, joined end to
  end, resampled to 30 fps), window ``--window`` seconds (default 0.8, about one cycle of the
  actions here), then ``stumpy.mmotifs(k=None)`` (the subspace chosen by minimum description
  length); the joints of the top motif's subspace.

**The truth** is written below (``TRUTH``) by one rule. Joints are grouped into limbs and the
axial body. For each action the *performing limbs* are named; their major joints (upper arm
and forearm; thigh and shank) are **active**; the major joints of the other limbs are
**inactive**; distal joints (wrist, hand, fingers, foot, toes), the shoulder girdle (clavicle,
shoulder) and the axial joints (root, hips, spine, chest, neck, head) are **don't-care**: they
follow the performing limbs by an amount that differs between performers, so no rule names them
honestly. Where an action lets the other limbs move by the performer's choice (arm swing in
walking and running, steps while gesturing) those limbs are don't-care too; the table says so
per action. Scores count active and inactive joints only. **Negative series** have no active
joint: single takes in which nothing repeats (one bow, one guiding gesture), performances of
different actions grouped by mistake, and a **composite** (the *bye* takes with each take's
left arm replaced by the left arm of a different cyclic action in another style: moving a lot,
cyclic, but not in step with the wave; truth: right arm active, left arm inactive). A negative
series is passed when a method names no joint; the composite is scored like any series.

Writes ``docs/data/actuators.csv`` (one row per series and method), the picture
``docs/img/pal_actuators.png``, and the table into docs/pal.md between
``<!-- pal-real-data:start -->`` and ``<!-- pal-real-data:end -->``.
"""

from __future__ import annotations

import argparse
import csv
import inspect
import sys
import time
import warnings
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from _common import DOCS, MOCAP, require

require("kinetology")
import kinetology  # noqa: E402
from kinetology.labels import read_cmu_truelabels  # noqa: E402
from kinetology.performances import from_spans, segment_performances  # noqa: E402
from kinetology.segmentation import DEFAULTS, segment, smooth, unwrap  # noqa: E402


# -- the truth ---------------------------------------------------------------------------

#: Joint names by limb part, CMU (ASF bones) and Bandai Namco (BVH joints).
PARTS = {
    "arm_R": ("rhumerus", "rradius", "UpperArm_R", "LowerArm_R"),
    "arm_L": ("lhumerus", "lradius", "UpperArm_L", "LowerArm_L"),
    "leg_R": ("rfemur", "rtibia", "UpperLeg_R", "LowerLeg_R"),
    "leg_L": ("lfemur", "ltibia", "UpperLeg_L", "LowerLeg_L"),
}
LIMBS = tuple(PARTS)
ARMS, LEGS, ALL = ("arm_L", "arm_R"), ("leg_L", "leg_R"), LIMBS


@dataclass(frozen=True)
class Truth:
    """Performing limbs (active), limbs left to the performer (don't-care); others inactive."""

    active: tuple[str, ...]
    free: tuple[str, ...] = ()
    why: str = ""

    def label(self, joint: str) -> str | None:
        """'active', 'inactive' or None (don't-care) for one joint."""
        for limb, names in PARTS.items():
            if joint in names:
                if limb in self.active:
                    return "active"
                return None if limb in self.free else "inactive"
        return None  # distal, girdle and axial joints


NONE = Truth((), (), "nothing repeats: no joint takes part")

#: Per action (content); keys are mocap6 labels, Bandai contents, or series names.
TRUTH = {
    # cmu-mocap6 exercises
    "JumpJack": Truth(ALL, (), "arms and legs open and close together"),
    "Jog": Truth(LEGS, ARMS, "the legs jog; arm swing is the performer's"),
    "Squat": Truth(LEGS, ARMS, "the legs bend; arms held forward or not"),
    "KneeRaise": Truth(LEGS, ARMS, "the knees rise in turn; arms are the performer's"),
    "ArmCircle": Truth(ARMS, (), "both arms circle; the legs stand"),
    "Box": Truth(ARMS, LEGS, "the arms punch; footwork is the performer's"),
    # Bandai Namco dataset 1 (checked in the files: every bye take waves the right hand)
    "bye": Truth(("arm_R",), (), "the right arm waves; the left arm and the legs stay"),
    "byebye": Truth(ARMS, (), "both arms wave; the legs stay"),
    "guide": Truth(("arm_R",), LEGS, "the right arm shows the way; steps are the performer's"),
    "punch": Truth(ARMS, LEGS, "both arms punch; footwork is the performer's"),
    # walking and running, both datasets
    "walk": Truth(LEGS, ARMS, "the legs walk; arm swing differs between styles"),
    "run": Truth(LEGS, ARMS, "the legs run; arm swing differs between styles"),
    "dash": Truth(LEGS, ARMS, "the legs run; arm swing differs between styles"),
    "walk-back": Truth(LEGS, ARMS, "the legs walk; arm swing differs between styles"),
    "walk-turn-left": Truth(LEGS, ARMS, "the legs walk; arm swing differs between styles"),
    "walk-turn-right": Truth(LEGS, ARMS, "the legs walk; arm swing differs between styles"),
    # the composite: the left arm of another cyclic action in each take
    "bye+foreign-left-arm": Truth(("arm_R",), (), "right arm waves in every take; the left "
                                  "arm does a different thing in each"),
}


# -- series ------------------------------------------------------------------------------

@dataclass
class Series:
    dataset: str
    name: str
    action: str
    performances: tuple
    negative: bool = False
    note: str = ""
    truth: Truth = field(default=None)

    def __post_init__(self):
        if self.truth is None:
            self.truth = NONE if self.negative else TRUTH[self.action]


def _bandai(folder: str, pattern: str):
    return sorted((MOCAP / folder / "data").glob(pattern))


def _read_all(paths):
    return tuple(kinetology.read(p) for p in paths)


def mocap6_series(quick: bool, min_seconds: float):
    folder = MOCAP / "cmu-mocap6"
    takes = {}
    for labels in sorted((folder / "truelabels").glob("*.txt")):
        amc = folder / "amc" / f"{labels.stem}.amc"
        if amc.is_file():
            motion = kinetology.read(amc)
            takes[labels.stem] = (motion, read_cmu_truelabels(labels, motion.frame_rate))
    actions = ("ArmCircle", "KneeRaise") if quick else \
        ("JumpJack", "Jog", "Squat", "KneeRaise", "ArmCircle", "Box")
    for action in actions:
        perfs = []
        for motion, spans in takes.values():
            perfs.extend(from_spans(motion, spans, action, min_seconds=min_seconds))
        if len(perfs) >= 2:
            yield Series("cmu-mocap6", action, action, tuple(perfs[:4] if quick else perfs),
                         note=f"{len(perfs)} labelled spans")


def subject02_series(quick: bool):
    folder = MOCAP / "cmu-subject02"
    yield Series("cmu-subject02", "walk (tour)", "walk",
                 _read_all([folder / "02_01.amc", folder / "02_02.amc"]), note="2 takes")


def bandai1_series(quick: bool):
    contents = ("bye", "byebye", "walk") if quick else \
        ("bye", "byebye", "guide", "punch", "walk", "run", "dash", "walk-back")
    for content in contents:
        paths = _bandai("bandai-namco-1", f"dataset-1_{content}_*.bvh")
        if quick:
            paths = paths[:5]
        yield Series("bandai-1", content, content, _read_all(paths),
                     note=f"{len(paths)} styles, one take each")


def bandai2_series(quick: bool):
    contents = ("walk", "run") if quick else ("walk", "run", "walk-turn-left", "walk-turn-right")
    styles = ("normal", "elderly") if quick else \
        ("normal", "active", "elderly", "exhausted", "feminine", "masculine", "youthful")
    for content in contents:
        for style in styles:
            paths = _bandai("bandai-namco-2-subset", f"dataset-2_{content}_{style}_*.bvh")
            if quick:
                paths = paths[:3]
            if paths:
                yield Series("bandai-2", f"{content} {style}", content, _read_all(paths),
                             note=f"{len(paths)} takes")


def _left_arm(joint: str) -> bool:
    return joint in ("Shoulder_L", "UpperArm_L", "LowerArm_L", "Hand_L")


def _transplant(host, donor):
    """``host`` with the left-arm channels of ``donor`` (tiled back and forth to length)."""
    values = np.array(host.values)
    for channel in host.channels:
        if _left_arm(channel.split(".", 1)[0]):
            column = donor.column(channel)
            # forwards then backwards: a long enough donor without a jump at the seam
            loop = np.concatenate([column, column[::-1]])
            values[:, host.index(channel)] = np.resize(loop, host.frames)
    return kinetology.Motion(values, host.channels, host.frame_rate, host.skeleton,
                             host.source + "+left-arm-of-" + Path(donor.source).stem, host.meta)


def negative_series(quick: bool):
    b1 = lambda name: kinetology.read(MOCAP / "bandai-namco-1" / "data" / f"dataset-1_{name}.bvh")  # noqa: E731
    singles = ("bow_normal_001", "guide_normal_001") if quick else \
        ("bow_normal_001", "bow_sad_001", "guide_normal_001", "guide_proud_001",
         "respond_normal_001")
    for name in singles:
        yield Series("negative", f"single {name[:-4]}", name, (b1(name),), negative=True,
                     note="one take, no repetition in it")
    mixed = ("bow_happy_001", "guide_sad_001", "respond_normal_001")
    yield Series("negative", "mixed: bow, guide, respond", "mixed",
                 tuple(b1(n) for n in mixed), negative=True,
                 note="different actions grouped by mistake")
    hosts = ("bye_normal_001", "bye_happy_001", "bye_sad_001", "bye_proud_001",
             "bye_musical_001")
    donors = ("byebye_angry_001", "walk_happy_001", "run_normal_001", "punch_normal_001",
              "dash_sad_001")
    if quick:
        hosts, donors = hosts[:3], donors[:3]
    perfs = tuple(_transplant(b1(h), b1(d)) for h, d in zip(hosts, donors))
    yield Series("composite", "bye + foreign left arm", "bye+foreign-left-arm",
                 perfs, note="left arm from " + ", ".join(d.split("_")[0] for d in donors))


# -- methods -----------------------------------------------------------------------------

def rotation_joints(motion):
    """Joint -> its rotation channels (columns), in skeleton order."""
    from kinetology.joints import actuator_map
    owners = actuator_map(motion, motion.rotation_channels())
    out: dict[str, list[int]] = {}
    for channel, joint in owners.items():
        out.setdefault(joint, []).append(motion.index(channel))
    return out


def excursions(motion) -> dict[str, float]:
    """Per joint: largest 5-95% range over its rotation channels (unwrapped, smoothed)."""
    out = {}
    for joint, columns in rotation_joints(motion).items():
        values = smooth(unwrap(motion.values[:, columns]), motion.frame_rate,
                        DEFAULTS["smoothing"])
        spread = np.percentile(values, 95, axis=0) - np.percentile(values, 5, axis=0)
        out[joint] = float(spread.max())
    return out


def excursion_rule(perfs, threshold):
    table = [excursions(m) for m in perfs]
    joints = list(table[0])
    median = {j: float(np.median([t.get(j, 0.0) for t in table])) for j in joints}
    return [j for j in joints if median[j] > threshold], median


def _pal_class():
    from psgs.induce.pal import PAL
    return PAL


def pal_supports(option: str) -> bool:
    return option in inspect.signature(_pal_class().__init__).parameters


def pal_joints(perfs, **options):
    """Joints PAL names; ``(joints, how)`` where ``how`` says which PAL interface was used."""
    PAL = _pal_class()
    inducer = PAL(**options)
    grams = segment_performances(perfs)
    try:
        induction = inducer.induce(grams if len(grams) > 1 else grams[0])
    except (TypeError, AttributeError, ValueError):
        induction = None
    if induction is not None and hasattr(induction, "actuators"):
        verdict = getattr(induction, "verdict", "") or ""
        return list(induction.actuators), ("performances" + (f": {verdict}" if verdict else ""))
    # a PAL of one actiongram: join the performances, as a user had to
    joined = kinetology.Motion(np.vstack([m.values for m in perfs]), perfs[0].channels,
                               perfs[0].frame_rate, perfs[0].skeleton, "joined")
    induction = inducer.induce(segment(joined))
    from kinetology.joints import actuator_map
    owners = actuator_map(joined)
    return list(dict.fromkeys(owners.get(c, c.split(".", 1)[0])
                              for c in induction.components)), "joined"


def stumpy_joints(perfs, window: float, rate: float = 30.0):
    import stumpy

    motion = perfs[0]
    joints = rotation_joints(motion)
    # the channels that move (as kinetology's min_range): a constant channel z-normalises
    # to a perfect match of every window, which would win every motif
    moving = set()
    for m in perfs:
        spread = np.ptp(unwrap(m.values), axis=0)
        moving |= {c for c in range(m.values.shape[1]) if spread[c] >= DEFAULTS["min_range"]}
    columns = [c for cols in joints.values() for c in cols if c in moving]
    owner = [j for j, cols in joints.items() for c in cols if c in moving]
    parts = []
    for m in perfs:
        values = unwrap(m.values[:, columns])
        step = max(1, int(round(m.frame_rate / rate)))
        if step > 1:  # block means: the 120 fps files at 30 fps, as stumpy's cost is n^2
            n = values.shape[0] // step * step
            values = values[:n].reshape(-1, step, values.shape[1]).mean(axis=1)
        parts.append(values)
    series = np.vstack(parts).T.copy()
    m = max(4, int(round(window * rate)))
    if series.shape[1] < 3 * m:
        return []
    with warnings.catch_warnings():  # stumpy 1.14 warns about its own use of numpy.less
        warnings.simplefilter("ignore", UserWarning)
        P, I = stumpy.mstump(series, m)
        _, _, subspaces, _ = stumpy.mmotifs(series, P, I, k=None)
    if not subspaces or len(subspaces[0]) == 0:
        return []
    chosen = {owner[d] for d in np.asarray(subspaces[0]).ravel()}
    return [j for j in joints if j in chosen]


# -- scoring -----------------------------------------------------------------------------

def score(named, joints, truth: Truth):
    named = set(named)
    tp = fp = fn = 0
    for j in joints:
        label = truth.label(j)
        if label == "active":
            tp += j in named
            fn += j not in named
        elif label == "inactive":
            fp += j in named
    precision = tp / (tp + fp) if tp + fp else (1.0 if not fn else 0.0)
    recall = tp / (tp + fn) if tp + fn else 1.0
    f1 = 2 * precision * recall / (precision + recall) if precision + recall else 0.0
    return precision, recall, f1


def run_method(function):
    started = time.perf_counter()
    result = function()
    return result, time.perf_counter() - started


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="a few series, fewer performances")
    parser.add_argument("--dataset", action="append",
                        choices=("cmu-mocap6", "cmu-subject02", "bandai-1", "bandai-2",
                                 "negative"), help="only these datasets (repeatable)")
    parser.add_argument("--series", action="append", help="only series whose name contains this")
    parser.add_argument("--excursion", type=float, default=10.0,
                        help="excursion rule threshold in degrees (default 10)")
    parser.add_argument("--window", type=float, default=0.8,
                        help="stumpy window in seconds (default 0.8)")
    parser.add_argument("--min-seconds", type=float, default=3.0,
                        help="shortest cmu-mocap6 span taken as a performance (default 3)")
    parser.add_argument("--no-stumpy", action="store_true", help="leave the stumpy peer out")
    parser.add_argument("--no-write", action="store_true", help="print only")
    parser.add_argument("--picture-only", action="store_true",
                        help="redraw docs/img/pal_actuators.png from docs/data/actuators.csv")
    args = parser.parse_args(argv)
    if args.picture_only:
        with (DOCS / "data" / "actuators.csv").open() as handle:
            rows = [{**r, "f1": float(r["f1"]), "negative": r["negative"] == "True"}
                    for r in csv.DictReader(handle)]
        picture(rows, DOCS / "img" / "pal_actuators.png")
        return 0
    if not MOCAP.is_dir():
        print(f"no motion data at {MOCAP}", file=sys.stderr)
        return 1
    makers = {"cmu-mocap6": lambda: mocap6_series(args.quick, args.min_seconds),
              "cmu-subject02": lambda: subject02_series(args.quick),
              "bandai-1": lambda: bandai1_series(args.quick),
              "bandai-2": lambda: bandai2_series(args.quick),
              "negative": lambda: negative_series(args.quick)}
    path_ablation = pal_supports("evidence")
    if not args.no_stumpy:  # compile stumpy's numba kernels first: its times are without that
        warm = np.random.default_rng(0).normal(size=(3, 64))
        import stumpy
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", UserWarning)
            stumpy.mmotifs(warm, *stumpy.mstump(warm, 8), k=None)
    rows, named_rows = [], []
    started = time.perf_counter()
    for dataset, make in makers.items():
        if args.dataset and dataset not in args.dataset:
            continue
        for series in make():
            if args.series and not any(s in series.name for s in args.series):
                continue
            perfs = series.performances
            joints = list(rotation_joints(perfs[0]))
            results = {}
            results["PAL"] = run_method(lambda: pal_joints(perfs))
            if path_ablation:
                results["PAL (path)"] = run_method(lambda: pal_joints(perfs, evidence="path"))
            (named, medians), seconds = run_method(lambda: excursion_rule(perfs, args.excursion))
            results["excursion"] = ((named, "rule"), seconds)
            if not args.no_stumpy:
                results["stumpy"] = run_method(lambda: (stumpy_joints(perfs, args.window),
                                                        "mmotifs"))
            line = [f"{series.dataset:13s} {series.name:34s} {len(perfs):2d} perf"]
            for method, ((named, how), seconds) in results.items():
                p, r, f = score(named, joints, series.truth)
                rows.append({"dataset": series.dataset, "series": series.name,
                             "action": series.action, "performances": len(perfs),
                             "negative": series.negative, "method": method,
                             "precision": round(p, 3), "recall": round(r, 3), "f1": round(f, 3),
                             "named": len(named), "seconds": round(seconds, 3), "how": how,
                             "joints": " ".join(named)})
                verdict = f"{len(named)} named" if series.negative else f"F1 {f:.2f}"
                line.append(f"{method} {verdict} {seconds:.2f}s")
            named_rows.append((series, medians))
            print(" | ".join(line), flush=True)
    print(f"total {time.perf_counter() - started:.1f} s", flush=True)
    summary = summarise(rows, args) + "\n\n" + threshold_sweep(named_rows, args.excursion)
    print(summary)
    if not args.no_write and not args.quick and not args.dataset and not args.series:
        write_outputs(rows, summary)
    return 0


METHODS = ("PAL", "PAL (path)", "excursion", "stumpy")


def summarise(rows, args) -> str:
    methods = [m for m in METHODS if any(r["method"] == m for r in rows)]
    positive = [r for r in rows if not r["negative"]]
    datasets = list(dict.fromkeys(r["dataset"] for r in positive))
    lines = ["| dataset | series | " + " | ".join(f"{m} F1" for m in methods) + " |",
             "|---|---:|" + "---:|" * len(methods)]
    for d in datasets + ["all"]:
        chosen = [r for r in positive if d in ("all", r["dataset"])]
        count = len({r["series"] + r["dataset"] for r in chosen})
        cells = []
        for m in methods:
            f1 = [r["f1"] for r in chosen if r["method"] == m]
            cells.append(f"{np.mean(f1):.3f}" if f1 else "n/a")
        name = "**all positive series**" if d == "all" else d
        lines.append(f"| {name} | {count} | " + " | ".join(cells) + " |")
    negatives = [r for r in rows if r["negative"] and r["action"] in ("mixed",)
                 or (r["negative"] and r["series"].startswith("single"))]
    if negatives:
        lines += ["", "| negative series (truth: no joint) | " +
                  " | ".join(f"{m}: joints named" for m in methods) + " |",
                  "|---|" + "---:|" * len(methods)]
        for name in dict.fromkeys(r["series"] for r in negatives):
            cells = [next((str(r["named"]) for r in negatives
                           if r["series"] == name and r["method"] == m), "n/a")
                     for m in methods]
            lines.append(f"| {name} | " + " | ".join(cells) + " |")
    seconds = {m: sum(r["seconds"] for r in rows if r["method"] == m) for m in methods}
    lines += ["", "Wall time over the run: " + ", ".join(f"{m} {s:.1f} s"
                                                       for m, s in seconds.items())]
    if "stumpy" in seconds and seconds.get("PAL"):
        lines[-1] += f" (stumpy / PAL = {seconds['stumpy'] / seconds['PAL']:.1f})"
    return "\n".join(lines)


THRESHOLDS = (2, 5, 10, 15, 20, 30, 45, 60)


def threshold_sweep(named_rows, default) -> str:
    """The excursion rule at other thresholds: mean F1 (positive series), joints named
    (negative series). The best threshold in hindsight bounds any fixed threshold."""
    cells = []
    for threshold in THRESHOLDS:
        f1, named = [], 0
        for series, medians in named_rows:
            chosen = [j for j, v in medians.items() if v > threshold]
            if series.negative:
                named += len(chosen)
            else:
                f1.append(score(chosen, list(medians), series.truth)[2])
        cells.append((threshold, float(np.mean(f1)) if f1 else float("nan"), named))
    best = max(cells, key=lambda c: (c[1], -c[2]))
    lines = ["Excursion rule by threshold (deg): mean F1 over the positive series; joints named "
             "over the negative series (truth: none)", "",
             "| threshold | " + " | ".join(f"{t:g}" + (" (default)" if t == default else "")
                                         for t, _, _ in cells) + " |",
             "|---|" + "---:|" * len(cells),
             "| mean F1 | " + " | ".join(f"{f:.3f}" for _, f, _ in cells) + " |",
             "| joints named, negatives | " + " | ".join(str(n) for _, _, n in cells) + " |",
             "", f"Best threshold in hindsight: {best[0]:g} deg (mean F1 {best[1]:.3f})."]
    return "\n".join(lines)


def truth_table(actions) -> str:
    """The truth of the series run, as a table (the rule is in the module docstring)."""
    lines = ["| action | active (upper arm + forearm, thigh + shank) | don't-care limbs | why |",
             "|---|---|---|---|"]
    for action in actions:
        truth = TRUTH.get(action)
        if truth is not None:
            lines.append(f"| {action} | {', '.join(truth.active) or 'none'} | "
                         f"{', '.join(truth.free) or '-'} | {truth.why} |")
    lines.append("| negative series | none | - | nothing repeats across or within the "
                 "performances |")
    return "\n".join(lines)


def write_outputs(rows, summary) -> None:
    data = DOCS / "data" / "actuators.csv"
    with data.open("w", newline="") as handle:
        writer = csv.DictWriter(handle, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)
    picture(rows, DOCS / "img" / "pal_actuators.png")
    actions = list(dict.fromkeys(r["action"] for r in rows if not r["negative"]))
    text = ("Measured by `python benchmarks/actuators.py` (per-series rows in "
            "[data/actuators.csv](data/actuators.csv)).\n\n" + summary +
            "\n\nThe truth, by the rule in `benchmarks/actuators.py` (the major joints of "
            "the performing limbs active, of the other limbs inactive; distal, girdle and "
            "axial joints, and limbs left to the performer, don't-care):\n\n" +
            truth_table(actions) +
            "\n\n![F1 per dataset and method](img/pal_actuators.png)")
    page = DOCS / "pal.md"
    content = page.read_text()
    start, end = "<!-- pal-real-data:start -->", "<!-- pal-real-data:end -->"
    if start not in content:
        content += f"\n## Real motion: which joints perform an action\n\n{start}\n{end}\n"
    head, rest = content.split(start, 1)
    _, tail = rest.split(end, 1)
    page.write_text(f"{head}{start}\n{text}\n{end}{tail}")


def picture(rows, path: Path) -> None:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    methods = [m for m in METHODS if any(r["method"] == m for r in rows)]
    positive = [r for r in rows if not r["negative"] or r["action"] == "bye+foreign-left-arm"]
    datasets = list(dict.fromkeys(r["dataset"] for r in positive))
    fig, ax = plt.subplots(figsize=(8, 3.9))
    width = 0.8 / len(methods)
    for k, m in enumerate(methods):
        means = [np.mean([r["f1"] for r in positive if r["dataset"] == d and r["method"] == m]
                         or [0]) for d in datasets]
        ax.bar(np.arange(len(datasets)) + k * width, means, width, label=m)
    ax.set_xticks(np.arange(len(datasets)) + 0.4 - width / 2, datasets)
    ax.set_ylabel("mean F1 (joints)")
    ax.set_ylim(0, 1.05)
    ax.legend(ncol=len(methods), fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.1),
              frameon=False)
    ax.set_title("Which joints take part: F1 against the truth table, per dataset")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


if __name__ == "__main__":
    sys.exit(main())
