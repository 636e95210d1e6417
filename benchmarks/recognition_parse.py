"""The recognition benchmark's parsing: recordings parsed into spans of learnt actions.

``cmu-parse``: the cmu-mocap6 sequences, each parsed with what the others learnt, against
their ``truelabels/`` (frame accuracy, segment F1). ``joined-parse``: recordings joined from
three takes of different Bandai dataset-1 contents of one style, parsed with what every other
style learnt (time precision and recall of the spans, absent actions reported). ``open-parse``:
the same recordings with the middle take's content not learnt (how much of its time is
answered none of these). Each beside a sliding-window MiniRocket where it can answer; the
praxicon's default reading beside the windows' threshold alone (``support=0, unfit=inf``:
every span standing, whatever its windows' feature-group test). ``recognition.py`` runs them
and writes the rows.
"""

from __future__ import annotations

import time
from collections import defaultdict

# first: one thread per method and the praxicon package from the repository (see there)
from recognition_methods import _resampled, series  # isort: skip

import numpy as np  # noqa: E402

from _common import MOCAP  # noqa: E402


# the windows' threshold alone answering none of these: every span standing, whatever its
# windows' feature-group test (the praxicon's reading before spans were checked by it)
_ALONE = {"support": 0.0, "unfit": float("inf")}
_ALONE_NAME = "praxicon threshold alone"

# -- parsing -----------------------------------------------------------------------------------
def _rate(motion, rate: float = 30.0):
    """The motion at about ``rate`` fps (every k-th frame after smoothing): parsing's input."""
    from kinetology import Motion
    from kinetology.segmentation import smooth

    k = max(1, int(round(motion.frame_rate / rate)))
    values = smooth(np.asarray(motion.values, dtype=float), motion.frame_rate, 0.5 * k /
                    motion.frame_rate)[::k]
    return Motion(values, motion.channels, motion.frame_rate / k, motion.skeleton,
                  motion.source)


def _cut(motion, start, stop):
    from kinetology import Motion
    a, b = int(round(start * motion.frame_rate)), int(round(stop * motion.frame_rate))
    return Motion(motion.values[a:b], motion.channels, motion.frame_rate, motion.skeleton,
                  motion.source)


def _window_peer(takes: dict, window: float, hop: float, length: int = 64, *, peers=True):
    """Sliding-window MiniRocket: fit on the training takes' windows, label every window
    (``peers=False``: no peer, every window unlabelled)."""
    if not peers:
        return lambda motion: (np.array([0.0]), [None])
    from aeon.classification.convolution_based import MiniRocketClassifier
    from praxicon.parsing import windows

    x, y = [], []
    for name, motions in takes.items():
        for m in motions:
            for w in windows(m, window, 2 * hop)[1]:
                x.append(_resampled(series(w, 30.0), length))
                y.append(name)
    model = MiniRocketClassifier(random_state=0, n_jobs=1).fit(np.stack(x), np.array(y))

    def label(motion):
        starts, cuts = windows(motion, window, hop)
        z = np.stack([_resampled(series(w, 30.0), length) for w in cuts])
        centres = np.array(starts) + min(window, motion.duration) / 2
        return centres, list(model.predict(z))
    return label


def _peer_labels(centres, labels, times):
    idx = np.abs(np.asarray(times)[:, None] - centres[None, :]).argmin(axis=1)
    return [labels[i] for i in idx]


def _segments(labels, times, step):
    out = []
    i = 0
    while i < len(labels):
        j = i
        while j + 1 < len(labels) and labels[j + 1] == labels[i]:
            j += 1
        out.append((labels[i], times[i] - step / 2, times[j] + step / 2))
        i = j + 1
    return out


def segment_f1(truth, found, step):
    """Segments (runs of one label) matched when the label agrees and IoU >= 0.5."""
    times = np.arange(len(truth)) * step + step / 2
    t = [s for s in _segments(truth, times, step) if s[0] is not None]
    f = [s for s in _segments(found, times, step) if s[0] is not None]
    hit = 0
    for label, a, b in t:
        for label2, c, d in f:
            inter = max(0.0, min(b, d) - max(a, c))
            if label == label2 and inter / (max(b, d) - min(a, c)) >= 0.5:
                hit += 1
                break
    precision = hit / len(f) if f else 0.0
    recall = hit / len(t) if t else 0.0
    return 2 * precision * recall / (precision + recall) if hit else 0.0


def parse_cmu(results, window=2.0, hop=0.25, *, peers=True):
    import kinetology
    from praxicon.parsing import describe_windows, parse

    root = MOCAP / "cmu-mocap6"
    sequences = {}
    for path in sorted((root / "amc").glob("*.amc")):
        labels = kinetology.read_cmu_truelabels(root / "truelabels" / f"{path.stem}.txt", 120.0)
        sequences[path.stem] = (_rate(kinetology.read(path)), labels)
    for left in sequences:
        takes = defaultdict(list)
        for name, (motion, spans) in sequences.items():
            if name == left:
                continue
            for span in spans:
                if span.stop - span.start >= 2.0:
                    takes[span.label].append(_cut(motion, span.start, min(span.stop,
                                                                          motion.duration)))
        motion, spans = sequences[left]
        step = 0.1
        times = np.arange(int(motion.duration / step)) * step + step / 2
        truth = [next((s.label for s in spans if s.start <= t < s.stop), None) for t in times]
        known = [lab in takes for lab in truth]
        descriptions = describe_windows(takes, window=window, hop=hop)
        began = time.process_time()
        found = parse(descriptions, motion, hop=hop).labels(times)
        cpu_ours = time.process_time() - began
        began = time.process_time()
        alone = parse(descriptions, motion, hop=hop, **_ALONE).labels(times)
        cpu_alone = time.process_time() - began
        peer = _window_peer(takes, window, hop, peers=peers)
        began = time.process_time()
        centres, labels = peer(motion)
        other = _peer_labels(centres, labels, times)
        cpu_peer = time.process_time() - began
        for method, pred, cpu in (("praxicon", found, cpu_ours),
                                  (_ALONE_NAME, alone, cpu_alone),
                                  ("minirocket-windows", other, cpu_peer)):
            r = results["cmu-parse", method]
            r["frames"] += sum(known)
            r["right"] += sum(k and p == t for k, p, t in zip(known, pred, truth))
            r["f1"].append(segment_f1([t if k else None for t, k in zip(truth, known)],
                                      pred, step))
            r["cpu"] += cpu
            r["seconds"] += motion.duration


def _joined(takes, rng):
    """Takes one after another, the root's position continued where the last take stopped."""
    from kinetology import Motion

    pieces, spans, t = [], [], 0.0
    last = None
    for take in takes:
        values = np.array(take.motion.values, dtype=float)
        trans = [c for c, ch in enumerate(take.motion.channels) if ch[-2:] in ("tx", "ty", "tz")]
        if last is not None:
            values[:, trans] += last[trans] - values[0, trans]
        last = values[-1]
        pieces.append(values)
        spans.append((take.content, t, t + take.motion.duration))
        t += take.motion.duration
    m = takes[0].motion
    return Motion(np.concatenate(pieces), m.channels, m.frame_rate, m.skeleton,
                  "<joined>"), spans


# the root's features also scored in each action's own spread: none of them, and the drift
# with the sway (the praxicon's default is the drift alone)
_OWN_VARIANTS = (("none", ()), ("drift+sway", ("drift", "energy")))


def parse_joined(results, data, per_style: int = 4, window=2.0, hop=0.25, *,
                 peers=True):
    """Recordings joined from three takes of different contents of one style, parsed with
    what every other style learnt (``joined-parse``); and the same recordings parsed with the
    middle take's content not learnt (``open-parse``): its time should be none of these."""
    from praxicon.parsing import describe_windows, parse

    rng = np.random.default_rng(0)
    for style in sorted({t.style for t in data}):
        train = defaultdict(list)
        for t in data:
            if t.style != style:
                train[t.content].append(t.motion)
        mine = [t for t in data if t.style == style and t.content in train]
        contents = sorted({t.content for t in mine})
        if len(contents) < 3:
            continue
        descriptions = describe_windows(train, window=window, hop=hop)
        without = {}  # per content not learnt, the descriptions of the others
        peer = _window_peer(train, window, hop, peers=peers)
        for _ in range(per_style):
            chosen = rng.choice(contents, 3, replace=False)
            takes = [next(t for t in mine if t.content == c) for c in chosen]
            motion, spans = _joined(takes, rng)
            step = 0.05
            times = np.arange(int(motion.duration / step)) * step + step / 2
            truth = [next((c for c, a, b in spans if a <= x < b), None) for x in times]
            began = time.process_time()
            found = parse(descriptions, motion, hop=hop).labels(times)
            cpu_ours = time.process_time() - began
            # the same descriptions read otherwise: the trade-off of the own-spread terms, and
            # the windows' threshold alone (every span standing, whatever its windows' test)
            variants = [(f"praxicon own={name}", parse(descriptions, motion, hop=hop,
                                                       own=own).labels(times), 0.0)
                        for name, own in _OWN_VARIANTS]
            variants.append((_ALONE_NAME, parse(descriptions, motion, hop=hop,
                                                **_ALONE).labels(times), 0.0))
            centres, labels = peer(motion)
            other = _peer_labels(centres, labels, times)
            for method, pred, cpu in (("praxicon", found, cpu_ours), *variants,
                                      ("minirocket-windows", other, 0.0)):
                _tally_parse(results["joined-parse", method], list(pred), truth,
                             set(train) - set(chosen))
                results["joined-parse", method]["cpu"] += cpu
                results["joined-parse", method]["seconds"] += motion.duration
            # the middle take's content not learnt: a window classifier answers a learnt
            # action in every window, so only the praxicon's readings are counted
            gone = str(chosen[1])
            if gone not in without:
                without[gone] = describe_windows({c: m for c, m in train.items() if c != gone},
                                                 window=window, hop=hop)
            unknown = [None if c == gone else c for c in truth]
            for method, kw in (("praxicon", {}), (_ALONE_NAME, _ALONE)):
                pred = parse(without[gone], motion, hop=hop, **kw).labels(times)
                r = results["open-parse", method]
                _tally_parse(r, list(pred), unknown, set(without[gone].names) - set(chosen))
                r["gone"] += sum(c == gone for c in truth)
                r["gone_none"] += sum(c == gone and p is None for c, p in zip(truth, pred))


def _tally_parse(r, pred, truth, absent) -> None:
    """One parsed recording counted: time claimed by an action and right, true time covered,
    actions ``absent`` from the recording that were reported."""
    r["claimed"] += sum(p is not None for p in pred)
    r["inside"] += sum(p is not None and p == t for p, t in zip(pred, truth))
    r["true"] += sum(t is not None for t in truth)
    r["covered"] += sum(p == t and t is not None for p, t in zip(pred, truth))
    r["absent_pairs"] += len(absent)
    r["absent_reported"] += len(absent & set(pred))
    r["recordings"] += 1
    r["any_absent"] += int(bool(absent & set(pred)))


def report_parse(results, protocol, say) -> list[dict]:
    """The rows of one parsing protocol (``cmu-parse``, ``joined-parse`` or ``open-parse``),
    each said in one line."""
    methods = {"cmu-parse": ("praxicon", _ALONE_NAME, "minirocket-windows"),
               "joined-parse": ("praxicon", _ALONE_NAME,
                                *(f"praxicon own={name}" for name, _ in _OWN_VARIANTS),
                                "minirocket-windows"),
               "open-parse": ("praxicon", _ALONE_NAME)}[protocol]
    rows = []
    for method in methods:
        r = results[protocol, method]
        if protocol == "cmu-parse":
            row = {"protocol": protocol, "method": method,
                   "frame_accuracy": r["right"] / r["frames"],
                   "segment_f1": float(np.mean(r["f1"])),
                   "cpu_ms_per_second": 1000 * r["cpu"] / r["seconds"]}
            say(f"{protocol:12s} {method:24s} frame accuracy={row['frame_accuracy']:.3f} "
                f"segment F1={row['segment_f1']:.3f} cpu={row['cpu_ms_per_second']:.2f} "
                f"ms per second of motion")
        else:
            row = {"protocol": protocol, "method": method,
                   "recordings": int(r["recordings"]),
                   "time_precision": r["inside"] / max(1, r["claimed"]),
                   "time_recall": r["covered"] / r["true"],
                   "absent_reported": r["absent_reported"] / r["absent_pairs"],
                   "recordings_with_absent": r["any_absent"] / r["recordings"]}
            unlearnt = ""
            if protocol == "open-parse":
                row["unlearnt_none"] = r["gone_none"] / r["gone"]
                unlearnt = f" unlearnt take's time none of these={row['unlearnt_none']:.3f}"
            say(f"{protocol:12s} {method:24s} recordings={row['recordings']} time precision="
                f"{row['time_precision']:.3f} recall={row['time_recall']:.3f} absent action "
                f"reported={row['absent_reported']:.3f} (recordings with one: "
                f"{row['recordings_with_absent']:.2f}){unlearnt}")
        rows.append(row)
    return rows
