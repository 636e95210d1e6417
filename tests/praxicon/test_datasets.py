"""Dataset readers: manifests, the Bandai layout (a small one made here), cmu-mocap6, errors."""

from __future__ import annotations

import json

import pytest

from praxicon.datasets import DatasetError, read_dataset, read_datasets

from praxicon_fixtures import SHARED, needs_mocap, take


def test_csv_manifest_groups_performances_by_action(manifest):
    actions = {a.name: a for a in read_dataset(manifest)}
    assert sorted(actions) == ["moves.alone", "moves.ghost", "moves.step", "moves.wave"]
    assert len(actions["moves.wave"].performances) == 3
    ghost = actions["moves.ghost"].performances
    assert (ghost[1].start, ghost[1].stop) == (0.0, 1.0)
    assert ghost[0].file.endswith("data/nowhere.bvh")  # relative to the manifest's folder


def test_toml_manifest(tmp_path):
    (tmp_path / "m.toml").write_text(
        '[[performance]]\naction = "wave"\nfile = "a.bvh"\nstart = 1.5\nstop = 3\n'
        '[[performance]]\naction = "wave"\nfile = "b.bvh"\n')
    (action,) = read_dataset(tmp_path / "m.toml")
    assert action.name == "m.wave"
    assert [(p.start, p.stop) for p in action.performances] == [(1.5, 3.0), (None, None)]


def test_a_manifest_style_column_groups_as_a_bandai_folders_styles(tmp_path):
    (tmp_path / "m.csv").write_text(
        "action,file,style\nwalk,a.bvh,happy\nwalk,b.bvh, happy\nwalk,c.bvh,sad\n"
        "walk,d.bvh,sad\nrun,e.bvh,\nrun,f.bvh,\n")
    by_style = read_dataset(tmp_path / "m.csv")  # most pairs have several: per style
    assert [(a.name, a.content, a.style, len(a.performances)) for a in by_style] == [
        ("m.run", "run", None, 2), ("m.walk.happy", "walk", "happy", 2),
        ("m.walk.sad", "walk", "sad", 2)]
    by_content = read_dataset(tmp_path / "m.csv", "content")
    assert [(a.name, a.style, len(a.performances)) for a in by_content] == [
        ("m.run", None, 2), ("m.walk", None, 4)]
    (tmp_path / "n.toml").write_text(
        '[[performance]]\naction = "wave"\nfile = "a.bvh"\nstyle = "calm"\n'
        '[[performance]]\naction = "wave"\nfile = "b.bvh"\nstyle = "calm"\n')
    (wave,) = read_dataset(tmp_path / "n.toml")
    assert (wave.name, wave.content, wave.style) == ("n.wave.calm", "wave", "calm")
    (tmp_path / "o.toml").write_text('[[performance]]\naction = "wave"\nfile = "a.bvh"\n'
                                     'style = 3\n')
    with pytest.raises(DatasetError, match="performance 1: style must be text, not 3"):
        read_dataset(tmp_path / "o.toml")


def test_a_manifest_built_per_style_has_families(tmp_path):
    """The styles a manifest names become families, as a Bandai folder's do."""
    from praxicon import build, load
    from praxicon_fixtures import write_manifest

    data = tmp_path / "data"
    data.mkdir()
    path = write_manifest(data, {"wave": [1, 2, 3, 4], "step": [5, 6, 7, 8]})
    lines = path.read_text().splitlines()
    rows = [f"{line},{'calm' if int(line.split('_')[1].split('.')[0]) % 2 else 'brisk'}"
            for line in lines[1:]]
    path.write_text("\n".join([lines[0] + ",style", *rows]) + "\n")
    build(read_dataset(path), tmp_path / "px", progress=False, log=lambda line: None)
    px = load(tmp_path / "px")
    assert px.names == ("moves.step.brisk", "moves.step.calm", "moves.wave.brisk",
                        "moves.wave.calm")
    assert px.descriptions.family_of == ("moves.step",) * 2 + ("moves.wave",) * 2


@pytest.mark.parametrize("text, message", [
    ("file\na.bvh\n", "manifest needs columns action,file"),
    ("action,file,start,stop\nwave,a.bvh,two,\n", "start/stop must be seconds"),
    ("action,file,start,stop\nwave,a.bvh,3,1\n", "stop 1.0 is not after start 3.0"),
])
def test_bad_manifest_is_one_line_naming_the_row(tmp_path, text, message):
    (tmp_path / "m.csv").write_text(text)
    with pytest.raises(DatasetError, match=message) as info:
        read_dataset(tmp_path / "m.csv")
    assert "\n" not in str(info.value) and "m.csv" in str(info.value)


def test_unknown_layout_and_missing_path(tmp_path):
    with pytest.raises(DatasetError, match="not a known dataset layout"):
        read_dataset(tmp_path)
    with pytest.raises(DatasetError, match="no such file or folder"):
        read_dataset(tmp_path / "nope")
    with pytest.raises(DatasetError, match="--group-by"):
        read_dataset(tmp_path, group_by="style")


def _bandai(root, takes, mismatch=None):
    """A Bandai-style folder: takes = [(content, style, id)]; ``mismatch`` gets a wrong JSON."""
    from kinetology import write_bvh

    contents = sorted({c for c, _, _ in takes})
    styles = sorted({s for _, s, _ in takes})
    (root / "cfg").mkdir(parents=True)
    (root / "data").mkdir()
    (root / "cfg" / "content_label.txt").write_text(
        "\n".join(f"dataset-9_{c}" for c in contents) + "\n")
    (root / "cfg" / "style_label.txt").write_text("\n".join(f"dataset-9_{s}" for s in styles))
    for seed, (content, style, ident) in enumerate(takes):
        stem = f"dataset-9_{content}_{style}_{ident:03d}"
        write_bvh(take(seed, seconds=2), root / "data" / f"{stem}.bvh")
        label = {"content": contents.index(content), "style": styles.index(style)}
        if stem == mismatch:
            label["content"] = (label["content"] + 1) % len(contents)
        (root / "data" / f"{stem}.json").write_text(json.dumps(label))
    return root


def test_bandai_default_grouping_and_mismatching_label(tmp_path):
    takes = [(c, s, i) for c in ("wave", "walk") for s in ("calm", "brisk") for i in (1, 2)]
    root = _bandai(tmp_path / "set", takes, mismatch="dataset-9_walk_calm_002")
    actions = {a.name: a for a in read_dataset(root)}
    # most (content, style) pairs have several takes: one action per content and style
    assert sorted(actions) == ["set.walk.brisk", "set.walk.calm", "set.wave.brisk",
                               "set.wave.calm"]
    calm = actions["set.walk.calm"]
    assert len(calm.performances) == 1
    (problem,) = calm.problems
    assert "dataset-9_walk_calm_002.json" in problem and "does not match" in problem
    by_content = {a.name: a for a in read_dataset(root, group_by="content")}
    assert sorted(by_content) == ["set.walk", "set.wave"]
    assert len(by_content["set.wave"].performances) == 4


def test_a_label_file_that_does_not_match_is_one_line_and_the_build_goes_on(tmp_path, capsys):
    from praxicon import build, load

    takes = [(c, "calm", i) for c in ("wave", "walk") for i in (1, 2, 3)]
    root = _bandai(tmp_path / "set", takes, mismatch="dataset-9_wave_calm_003")
    build(read_dataset(root, group_by="content"), tmp_path / "px", progress=False)
    px = load(tmp_path / "px")
    wave = px["set.wave"]
    assert px["set.walk"].learnt and not px["set.walk"].problems
    assert wave.learnt  # learnt from the two takes whose labels match
    (problem,) = wave.problems
    assert "dataset-9_wave_calm_003.json" in problem and "does not match" in problem
    assert "\n" not in problem
    assert f"set.wave: {problem}" in capsys.readouterr().err


def test_bandai_one_take_per_style_groups_by_content(tmp_path):
    root = _bandai(tmp_path / "one", [("wave", s, 1) for s in ("a", "b", "c")])
    (action,) = read_dataset(root)
    assert action.name == "one.wave" and len(action.performances) == 3


@needs_mocap()
def test_shared_data_actions():
    actions = read_datasets([SHARED / "cmu-mocap6", SHARED / "bandai-namco-1",
                             SHARED / "bandai-namco-2-subset"])
    names = {a.name: a for a in actions}
    assert len(names) == 56  # 12 exercises + 16 Bandai-1 contents + 4 x 7 Bandai-2 pairs
    assert len(names["bandai-namco-1.bye"].performances) == 15  # one take per style
    assert len(names["bandai-namco-2-subset.walk.elderly"].performances) == 5
    jog = names["cmu-mocap6.Jog"].performances
    assert all(p.label.endswith(".txt") and p.stop - p.start >= 2 for p in jog)
