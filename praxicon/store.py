"""A praxicon on disk: ``index.json``, one ``ACTION.psgs`` per action, the actuator matrix.

Layout of a praxicon folder ``DIR`` (schema in ``docs/praxicon.md``)::

    DIR/index.json            every action's record, sorted by name (deterministic bytes)
    DIR/actuators.csv         the actuator-set matrix: one row per learnt action, one
                              column per joint, 1 where the joint takes part
    DIR/shared.json           kineteme sub-patterns several actions share, per joint
    DIR/ACTION.psgs           the grammar system learnt for ACTION
    DIR/records/ACTION.json   one record per action with its input key (what resume reads)
    DIR/timings.json          wall seconds per action (kept out of index.json, whose
                              bytes must not change between runs)

Every file is written to a temporary name and renamed into place, so an
interrupted build never leaves a half-written file.
"""

from __future__ import annotations

import csv
import io
import json
import os
from pathlib import Path

__all__ = ["write_atomic", "dump_json", "write_record", "read_records", "write_index",
           "load_index", "load_record", "actuator_matrix", "INDEX_FORMAT"]

INDEX_FORMAT = "psgs-praxicon"


def write_atomic(path: Path, text: str) -> None:
    """Write ``text`` to ``path`` through a temporary file and a rename."""
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    tmp.write_text(text, encoding="utf-8", newline="\n")
    os.replace(tmp, path)


def dump_json(value) -> str:
    """Canonical JSON: sorted keys, two-space indent, a final newline."""
    return json.dumps(value, indent=2, sort_keys=True, ensure_ascii=False) + "\n"


def write_record(out: Path, record: dict, key: str) -> None:
    """Store one action's record (with its input key) and its ``.psgs`` file."""
    system = record.get("system")
    psgs_path = out / f"{record['name']}.psgs"
    if system:
        write_atomic(psgs_path, system)
    elif psgs_path.exists():
        psgs_path.unlink()
    write_atomic(out / "records" / f"{record['name']}.json",
                 dump_json({"key": key, "record": record}))


def read_records(out: Path) -> dict[str, tuple[str, dict]]:
    """name -> (input key, record) of every readable record in ``out/records``."""
    found = {}
    for path in sorted((out / "records").glob("*.json")):
        try:
            data = json.loads(path.read_text(encoding="utf-8"))
            found[data["record"]["name"]] = (data["key"], data["record"])
        except (OSError, ValueError, KeyError, TypeError):
            continue  # a damaged record is learnt again
    return found


def _index_entry(record: dict) -> dict:
    entry = {k: v for k, v in record.items() if k not in ("system", "mean_pose")}
    if record.get("system"):
        entry["file"] = f"{record['name']}.psgs"
    return entry


def actuator_matrix(records: list[dict]) -> tuple[list[str], list[str], list[list[int]]]:
    """(action names, joint names, 0/1 rows) of the learnt actions.

    Joints are in order of first appearance over the actions sorted by name, in
    each action's skeleton order (so one dataset's joints stay together).
    """
    learnt = [r for r in records if r.get("status") == "ok"]
    joints: list[str] = []
    for r in learnt:
        for joint in _pose_joints(r):
            if joint not in joints:
                joints.append(joint)
    rows = [[int(j in r["actuators"]) for j in joints] for r in learnt]
    return [r["name"] for r in learnt], joints, rows


def _pose_joints(record: dict) -> list[str]:
    if record.get("all_joints"):
        return list(record["all_joints"])
    seen: list[str] = []
    for channel in record.get("mean_pose", {}):
        joint = channel.rsplit(".", 1)[0]
        if joint not in seen:
            seen.append(joint)
    return seen


def write_index(out: Path, records: list[dict], settings: dict, datasets: list[str],
                timings: dict[str, float] | None = None) -> dict:
    """Write ``index.json``, ``actuators.csv``; with ``timings`` (the build's last write) also
    ``timings.json`` and ``shared.json``. Returns the index."""
    records = sorted(records, key=lambda r: r["name"])
    index = {
        "format": INDEX_FORMAT,
        "version": 1,
        "datasets": list(datasets),
        "settings": settings,
        "counts": {"actions": len(records),
                   "learnt": sum(r["status"] == "ok" for r in records),
                   "failed": sum(r["status"] != "ok" for r in records)},
        "actions": [_index_entry(r) for r in records],
    }
    names, joints, rows = actuator_matrix(records)
    buffer = io.StringIO()
    writer = csv.writer(buffer, lineterminator="\n")
    writer.writerow(["action", *joints])
    for name, row in zip(names, rows):
        writer.writerow([name, *row])
    write_atomic(out / "actuators.csv", buffer.getvalue())
    write_atomic(out / "index.json", dump_json(index))
    if timings is not None:
        write_atomic(out / "timings.json", dump_json({k: round(v, 3) for k, v in
                                                     sorted(timings.items())}))
    return index


def load_index(path: str | Path) -> dict:
    """Read ``DIR/index.json`` (``path`` is ``DIR`` or the file); ValueError when it is not one."""
    path = Path(path)
    if path.is_dir():
        path = path / "index.json"
    try:
        index = json.loads(path.read_text(encoding="utf-8"))
    except FileNotFoundError:
        raise ValueError(f"{path}: no praxicon index (run 'psgs praxicon build' first)") from None
    except ValueError as exc:
        raise ValueError(f"{path}: not JSON ({exc})") from None
    if not isinstance(index, dict) or index.get("format") != INDEX_FORMAT:
        raise ValueError(f"{path}: not a praxicon index (format is not {INDEX_FORMAT!r})")
    return index


def load_record(folder: str | Path, action: str) -> dict:
    """The full record of ``action`` (with its system text and mean pose)."""
    folder = Path(folder)
    path = folder / "records" / f"{action}.json"
    try:
        return json.loads(path.read_text(encoding="utf-8"))["record"]
    except FileNotFoundError:
        names = [r["name"] for r in load_index(folder)["actions"]]
        raise ValueError(f"no action {action!r} in {folder} (actions: "
                         f"{', '.join(names[:8])}{' ...' if len(names) > 8 else ''})") from None
