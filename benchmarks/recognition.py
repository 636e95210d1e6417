"""Recognising and parsing real motion: the praxicon's descriptions against three peers.

Run from the repository root (heavy: under the lock on a shared machine)::

    flock /tmp/heavy.lock python benchmarks/recognition.py           # everything, writes docs
    python benchmarks/recognition.py --only d2-in-style --no-docs     # one protocol

Peers, in the same run, on the same split and the same channels (every rotation channel of the
non-root joints, unwrapped, and the root's travel and turning velocities in its own frame):
DTW 1-nearest-neighbour (``dtaidistance``, multivariate, at 10 fps), MiniRocket (``aeon``,
every take resampled to 64 steps) and a nearest centroid on each joint's angle range.

Protocols: Bandai dataset 1 leave one style out; the dataset-2 subset in style (takes 1-3
learn, 4-5 test) and leave one style out; open set (one content left out of the learning: its
takes must come back "none of these"; DTW 1-NN and MiniRocket with a rejection threshold
calibrated on held-out known takes beside the praxicon; and the bound: the same splits
classified by every method with the left-out content learnt too); parsing cmu-mocap6 leave one
sequence out (frame accuracy and segment F1) and recordings joined from three takes of
different Bandai dataset-1 contents (time precision and recall of the spans, absent actions
reported), each against a sliding-window MiniRocket, and the same recordings with one content
not learnt (its time should be none of these). CPU per take is ``time.process_time``
of classifying the test takes (features included, reading the files not), divided by their
number.

The takes, the peers' input and the four classifiers are in ``recognition_methods.py``, the
open set (its protocols, rules, the peers' readings and the bound) in ``recognition_open.py``,
parsing in ``recognition_parse.py``; this module runs the closed-set protocols, calls the
others, and prints every row.
"""

from __future__ import annotations

import argparse
import sys
import time
from collections import Counter, defaultdict

# first: it runs every method on one thread (set before numpy and numba load) and loads the
# praxicon package from the repository, not benchmarks/praxicon.py; then the open set's part
from recognition_methods import METHODS, read_bandai  # isort: skip

import numpy as np  # noqa: E402

from _common import DATA, DOCS, IMG, MOCAP, require, write_csv  # noqa: E402
from recognition_open import report_open_sets, run_open_sets  # noqa: E402
from recognition_parse import _joined, parse_cmu, parse_joined, report_parse  # noqa: E402


# -- the closed-set protocols ------------------------------------------------------------------
def run_split(results, protocol, train, test, methods=METHODS):
    """Fit and predict every method on one split; accumulate predictions and CPU."""
    labels = [t.content for t in train]
    known = set(labels)
    test = [t for t in test if t.content in known]
    if not test:
        return
    for name, fit in methods.items():
        if getattr(fit, "needs_styles", False):
            predict = fit([t.motion for t in train], labels, [t.style for t in train])
        else:
            predict = fit([t.motion for t in train], labels)
        began = time.process_time()
        ranked, decided = predict([t.motion for t in test])
        cpu = time.process_time() - began
        r = results[protocol, name]
        if hasattr(predict, "left_out"):
            r.setdefault("left_out", []).append(predict.left_out)
        r["truth"] += [t.content for t in test]
        r["pred"] += list(ranked)
        if hasattr(predict, "probabilities"):
            r.setdefault("probabilities", []).extend(predict.probabilities)
        r["cpu"] += cpu
        r["n"] += len(test)


def summarise(results, protocol, methods=METHODS):
    rows = []
    for name in methods:
        r = results.get((protocol, name))
        if not r or not r["n"]:
            continue
        truth, pred = np.array(r["truth"]), np.array(r["pred"])
        recall = {c: float((pred[truth == c] == c).mean()) for c in sorted(set(truth))}
        rows.append({"protocol": protocol, "method": name, "takes": int(r["n"]),
                     "accuracy": float((truth == pred).mean()),
                     "min_recall": min(recall.values()),
                     "cpu_ms_per_take": 1000 * r["cpu"] / r["n"], "recall": recall,
                     "left_out": r.get("left_out"),
                     **calibration(r.get("probabilities"), truth, pred)})
    return rows


def calibration(probabilities, truth, pred, bins: int = 10) -> dict:
    """How well a method's probabilities say how often it is right: the mean probability of
    its answer (``confidence``, against the accuracy), the expected calibration error over
    ``bins`` equal bins of that probability (``ece``) and the mean negative log probability of
    the true content (``nll``, a probability under 1e-300 counted as 1e-300). Empty for a
    method without probabilities."""
    if not probabilities:
        return {}
    best = np.array([p.get(a, 0.0) for p, a in zip(probabilities, pred)])
    right = np.asarray(truth) == np.asarray(pred)
    bin_of = np.minimum((best * bins).astype(int), bins - 1)
    ece = sum(float(np.mean(bin_of == b)) * abs(float(right[bin_of == b].mean())
                                               - float(best[bin_of == b].mean()))
              for b in range(bins) if np.any(bin_of == b))
    nll = float(np.mean([-np.log(max(p.get(t, 0.0), 1e-300))
                         for p, t in zip(probabilities, truth)]))
    return {"confidence": float(best.mean()), "ece": ece, "nll": nll}




def cost_growth(data, counts=(2, 4, 8, 10)):
    """CPU per take as the number of actions grows (takes of those actions only)."""
    contents = sorted({t.content for t in data}, key=lambda c: -sum(t.content == c
                                                                    for t in data))
    rows = []
    for k in counts:
        chosen = set(contents[:k])
        pool = [t for t in data if t.content in chosen]
        train = [t for t in pool if t.take == 1 and t.style not in ("normal", "old")]
        learnt = {t.content for t in train}
        test = [t for t in pool if t.style in ("normal", "old") and t.content in learnt][:20]
        row = {"actions": len(learnt), "train_takes": len(train), "test_takes": len(test)}
        for name in ("praxicon", "dtw-1nn"):
            predict = METHODS[name]([t.motion for t in train], [t.content for t in train])
            began = time.process_time()
            predict([t.motion for t in test])
            row[name] = 1000 * (time.process_time() - began) / len(test)
        rows.append(row)
    return rows


def pictures(data, say, style="active", contents=("walk", "byebye", "bow")):
    """The docs' pictures: a joined recording of one unseen style parsed, and a recognition's
    explanation (learnt from every other style)."""
    from praxicon.description import describe
    from praxicon.parsing import describe_windows, parse
    from praxicon.recognition import recognise
    from praxicon.recognition_pictures import draw_explanation, draw_timeline

    train = defaultdict(list)
    for t in data:
        if t.style != style:
            train[t.content].append(t.motion)
    takes = [next(t for t in data if t.style == style and t.content == c) for c in contents]
    motion, spans = _joined(takes, None)
    timeline = parse(describe_windows(train), motion)
    draw_timeline(timeline, motion, IMG / "recognition_timeline.png")
    say("truth: " + ", ".join(f"{c} {a:.2f}-{b:.2f}" for c, a, b in spans))
    for span in timeline.spans:
        say(f"parsed: {span.start:6.2f} {span.stop:6.2f} {span.action or '-'} {span.score:.3f}")
    found = recognise(describe(train), next(t.motion for t in data if t.style == style
                                            and t.content == "byebye"))
    draw_explanation(found, IMG / "recognition_explanation.png")
    for line in found.explain().splitlines():
        say(line.replace(str(MOCAP), "../shared/data/mocap"))


def _kind(feature: str) -> str:
    from praxicon.feature_choice import feature_kind

    kind = feature_kind(feature)
    return "root drift and sway" if kind == "root" else kind


def ablation(say, d1, d2):
    """What each kind of feature buys: accuracy with the kind left out (same splits)."""
    from praxicon.description import OWN_KINDS, common_table, describe_table, feature_rows, scores

    splits = []
    for name, data, folds in (
            ("d2-in-style", d2, [(lambda t: t.take <= 3, lambda t: t.take > 3)]),
            ("d2-loso", d2, [(lambda t, s=s: t.style != s, lambda t, s=s: t.style == s)
                             for s in sorted({t.style for t in d2})]),
            ("d1-loso", d1, [(lambda t, s=s: t.style != s, lambda t, s=s: t.style == s)
                             for s in sorted({t.style for t in d1})])):
        rows = feature_rows([t.motion for t in data])
        order, table = common_table({"all": rows})
        splits.append((name, data, folds, order, table["all"]))
    kinds = (["none"] + sorted({_kind(f) for f in splits[0][3]})
             + ["rank 0", "own: none", "own: drift and sway"])
    out = []
    for kind in kinds:
        rank = 0 if kind == "rank 0" else 16
        own = {"own: none": (), "own: drift and sway": ("drift", "energy")}.get(kind, OWN_KINDS)
        accs = []
        for name, data, folds, order, x in splits:
            keep = np.array([_kind(f) != kind for f in order])
            feats = tuple(f for f, k in zip(order, keep) if k)
            right = total = 0
            for is_train, is_test in folds:
                tr = [i for i, t in enumerate(data) if is_train(t)]
                labels = sorted({data[i].content for i in tr})
                te = [i for i, t in enumerate(data) if is_test(t) and t.content in labels]
                d = describe_table({c: x[[i for i in tr if data[i].content == c]][:, keep]
                                    for c in labels}, feats, rank=rank)
                score = scores(d, x[te][:, keep], np.arange(len(feats)), kinds=own)[1]
                pred = np.array(d.names)[score.argmin(axis=1)]
                right += int((pred == np.array([data[i].content for i in te])).sum())
                total += len(te)
            accs.append(right / total)
        label = {"none": "all features", "rank 0": "no shared directions (diagonal)",
                 "own: none": "root drift not in own spread",
                 "own: drift and sway": "root drift and sway in own spread"}.get(
                     kind, f"without {kind}")
        say(f"ablation {label:33s} " + "  ".join(f"{n} {a:.3f}" for (n, *_), a in
                                                  zip(splits, accs)))
        out.append({"protocol": "ablation", "method": label,
                    **{n: a for (n, *_), a in zip(splits, accs)}})
    return out


def _fmt(x, digits=3):
    return f"{x:.{digits}f}" if isinstance(x, float) else str(x)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--only", action="append", default=None,
                        help="d1-loso, d2-in-style, d2-loso, d2-to-d1, open-set (open-d1, open-d2: one dataset's "
                             "part), cmu-parse, joined-parse (and open-parse), "
                             "growth, ablation, pictures (repeatable; default all)")
    parser.add_argument("--methods", default=",".join(METHODS))
    parser.add_argument("--no-docs", action="store_true")
    parser.add_argument("--no-peers", action="store_true",
                        help="parsing and the open set without their peers (a quick check)")
    args = parser.parse_args(argv)
    peers = not args.no_peers
    require("praxicon")
    methods = {k: METHODS[k] for k in args.methods.split(",")}
    want = (lambda p: args.only is None or p in args.only)
    results = defaultdict(lambda: defaultdict(float, truth=[], pred=[], f1=[]))
    rows, lines = [], []

    def say(line):
        print(line, flush=True)
        lines.append(line)

    d1 = d2 = None
    peer_cache = {}  # the peers' DTW distances, once per dataset
    if want("d2-in-style") or want("d2-loso") or want("open-set") or want("open-d2") or \
            want("ablation") or want("d2-to-d1"):
        d2 = read_bandai(MOCAP / "bandai-namco-2-subset")
    if want("d1-loso") or want("open-set") or want("open-d1") or want("joined-parse") or want("growth") or \
            want("pictures") or want("ablation") or want("d2-to-d1"):
        d1 = read_bandai(MOCAP / "bandai-namco-1")
    if want("d1-loso"):
        for style in sorted({t.style for t in d1}):
            run_split(results, "d1-loso", [t for t in d1 if t.style != style],
                      [t for t in d1 if t.style == style], methods)
        rows += summarise(results, "d1-loso", methods)
    if want("d2-in-style"):
        run_split(results, "d2-in-style", [t for t in d2 if t.take <= 3],
                  [t for t in d2 if t.take > 3], methods)
        rows += summarise(results, "d2-in-style", methods)
    if want("d2-loso"):
        for style in sorted({t.style for t in d2}):
            run_split(results, "d2-loso", [t for t in d2 if t.style != style],
                      [t for t in d2 if t.style == style], methods)
        rows += summarise(results, "d2-loso", methods)
    if want("d2-to-d1"):
        # another dataset's performer and styles: every take of the subset learns, dataset 1's
        # walks and runs (the contents the two share by name) are asked
        run_split(results, "d2-to-d1", d2, [t for t in d1 if t.content in {u.content for u in d2}],
                  methods)
        rows += summarise(results, "d2-to-d1", methods)
    for row in rows:
        best_peer = max((r["accuracy"] for r in rows if r["protocol"] == row["protocol"]
                         and r["method"] not in ("praxicon",)), default=float("nan"))
        dtw = next((r["cpu_ms_per_take"] for r in rows if r["protocol"] == row["protocol"]
                    and r["method"] == "dtw-1nn"), float("nan"))
        row["vs_best_peer"] = row["accuracy"] - best_peer
        row["cpu_vs_dtw"] = row["cpu_ms_per_take"] / dtw
        say(f"{row['protocol']:12s} {row['method']:15s} n={row['takes']:4d} "
            f"acc={row['accuracy']:.3f} (best peer {best_peer:.3f}) min-recall="
            f"{row['min_recall']:.2f} cpu={row['cpu_ms_per_take']:.2f} ms/take "
            f"(x{row['cpu_vs_dtw']:.2f} DTW)")
        # every class's recall, the lowest first (docs/data/recognition_recall.csv holds them)
        say(f"{'':12s} {'':15s} recall: " + ", ".join(
            f"{c} {v:.2f}" for c, v in sorted(row["recall"].items(), key=lambda kv: kv[1])))
        if "ece" in row:
            say(f"{row['protocol']:12s} {row['method']:15s} calibration: the probability of its "
                f"answer {row['confidence']:.3f} on average against accuracy "
                f"{row['accuracy']:.3f}, expected calibration error {row['ece']:.3f}, the true "
                f"content's -log p {row['nll']:.3f}")
        if row.get("left_out"):
            kinds = Counter(row["left_out"])
            say(f"{row['protocol']:12s} {row['method']:15s} kinds of features left out by the "
                f"choice, splits: " + ", ".join(f"{k} {n}" for k, n in sorted(kinds.items())))
    run_open_sets(results, d1, d2, want, peer_cache, peers=peers)
    if want("open-set") or want("open-d1") or want("open-d2"):
        rows += report_open_sets(results, say)
    if want("cmu-parse"):
        parse_cmu(results, peers=peers)
        rows += report_parse(results, "cmu-parse", say)
    if want("joined-parse"):
        parse_joined(results, d1, peers=peers)
        rows += report_parse(results, "joined-parse", say)
        rows += report_parse(results, "open-parse", say)
    if want("ablation"):
        rows += ablation(say, d1, d2)
    if want("pictures"):
        pictures(d1, say)
    if want("growth"):
        for g in cost_growth(d1):
            say(f"growth  actions={g['actions']:2d} train takes={g['train_takes']:3d} "
                f"praxicon {g['praxicon']:.2f} ms/take, DTW 1-NN {g['dtw-1nn']:.2f} ms/take "
                f"(ratio {g['praxicon'] / g['dtw-1nn']:.2f})")
            rows.append({"protocol": "growth", "method": "praxicon/dtw-1nn", **g})
    if not args.no_docs:
        header = ["protocol", "method", "takes", "accuracy", "min_recall", "vs_best_peer",
                  "cpu_ms_per_take", "cpu_vs_dtw", "none_of_these", "closed_accuracy",
                  "frame_accuracy", "segment_f1", "recordings", "time_precision",
                  "time_recall", "absent_reported", "recordings_with_absent", "actions",
                  "train_takes", "praxicon", "dtw-1nn", "d2-in-style", "d2-loso", "d1-loso",
                  "known_at_recall_0.9", "confidence", "ece", "nll", "unlearnt_none"]
        write_csv(DATA / "recognition.csv", header,
                  [[_fmt(r.get(h, "")) if not isinstance(r.get(h, ""), float)
                    else f"{r[h]:.4f}" for h in header] for r in rows])
        write_csv(DATA / "recognition_recall.csv", ["protocol", "method", "action", "recall"],
                  [[r["protocol"], r["method"], c, f"{v:.4f}"] for r in rows
                   for c, v in sorted(r.get("recall", {}).items())])
        from _common import replace_section
        replace_section(DOCS / "praxicon.md", "recognition",
                        "Measured by `flock /tmp/heavy.lock python benchmarks/recognition.py` "
                        "(one run, every method on the same split and channels):\n\n```text\n"
                        + "\n".join(lines) + "\n```")
    return 0


if __name__ == "__main__":
    sys.exit(main())
