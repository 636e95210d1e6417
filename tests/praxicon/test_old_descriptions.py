"""A folder whose descriptions are of another version: recognition refuses it with the command
that learns them again; generation and the pictures, which read the records only, do not."""

from __future__ import annotations

import json

import pytest

from fuzz_support import praxicon_seed
from praxicon import dump, load
from praxicon.description import FORMAT_VERSION
from praxicon.records import PraxiconError


@pytest.fixture()
def old_folder(tmp_path):
    folder = tmp_path / "px"
    dump(praxicon_seed(), folder)
    path = folder / "descriptions.json"
    data = json.loads(path.read_text())
    data["version"] = 4  # as psgs wrote it before families
    path.write_text(json.dumps(data))
    return folder


def test_load_refuses_old_descriptions_unless_told_not_to_read_them(old_folder):
    with pytest.raises(PraxiconError, match="descriptions of version 4, this psgs reads "
                                            f"version {FORMAT_VERSION} .*resumes the build"):
        load(old_folder)
    px = load(old_folder, descriptions=False)
    assert px.descriptions is None and px.window_descriptions is None
    assert px.actions == praxicon_seed().actions


def test_the_pictures_read_a_folder_with_old_descriptions(old_folder, tmp_path):
    from praxicon import draw_actuator_matrix

    path = draw_actuator_matrix(old_folder, tmp_path / "matrix.svg")
    assert path.stat().st_size > 0


def test_generation_loads_without_the_descriptions(old_folder):
    from praxicon import generate

    # the seed's takes are not on disk: generation gets past the folder to the action's
    # skeleton file, which is what it reads next
    with pytest.raises(ValueError, match="^step_0.bvh: no such file: the skeleton of "
                                         "'moves.step' is read from its first performance"):
        generate(old_folder, "moves.step", repeat=1)


@pytest.mark.parametrize("value", [None, "no", 1])
def test_the_flag_is_a_bool(old_folder, value):
    with pytest.raises(PraxiconError, match="descriptions must be True or False"):
        load(old_folder, descriptions=value)


def test_recognise_and_parse_say_a_praxicon_read_without_descriptions_has_none(old_folder):
    from kinetology import synthetic_motion
    from praxicon import parse, recognise
    from praxicon.description import DescriptionError

    px = load(old_folder, descriptions=False)
    for name, call in (("recognise", recognise), ("parse", parse)):
        with pytest.raises(DescriptionError, match=f"^{name}: this praxicon holds no "
                                                   f"descriptions \\(load\\(folder\\) reads"):
            call(px, synthetic_motion(3, seed=1))


def test_verify_reports_old_descriptions_and_checks_every_other_file(old_folder):
    from praxicon import repair, verify

    (old_folder / "shared.json").unlink()
    old = (old_folder / "descriptions.json").read_bytes()
    found = verify(old_folder)
    assert found.problems == (
        f"{old_folder / 'descriptions.json'}: descriptions of version 4, this psgs reads "
        f"version {FORMAT_VERSION} (learn them again: 'psgs praxicon build DATASET... -o FOLDER' resumes the "
        f"build and describes its actions)",
        f"{old_folder / 'shared.json'}: missing")
    mended = repair(old_folder)  # the derived files again; the descriptions left for build
    assert mended.problems == found.problems[:1]
    assert (old_folder / "descriptions.json").read_bytes() == old


def test_verify_still_refuses_a_folder_whose_records_load_refuses(old_folder):
    from praxicon import verify

    (old_folder / "records" / "moves.wave.json").write_text("[]")
    with pytest.raises(PraxiconError, match=r"moves\.wave\.json: not a praxicon record file"):
        verify(old_folder)


@pytest.mark.parametrize("later", [1, 100])
def test_descriptions_of_a_later_version_say_to_upgrade_not_to_learn_again(old_folder, later):
    """Learning them again would write over what a later psgs learnt."""
    path = old_folder / "descriptions.json"
    data = json.loads(path.read_text())
    data["version"] = FORMAT_VERSION + later
    path.write_text(json.dumps(data))
    with pytest.raises(PraxiconError, match=f"descriptions of version {FORMAT_VERSION + later}, "
                                            r"this psgs reads version \d+ \(a later psgs wrote "
                                            r"them; upgrade psgs to read them\)$"):
        load(old_folder)


@pytest.mark.parametrize("name", ["index.json", "descriptions.json"])
def test_build_refuses_a_folder_a_later_psgs_wrote_and_leaves_it(old_folder, name):
    """build learnt a later version's folder or descriptions again and wrote over them."""
    from praxicon.builder import build

    path = old_folder / name
    data = json.loads(path.read_text())
    data["version"] = 10**6
    path.write_text(json.dumps(data))
    before = {p: p.read_bytes() for p in old_folder.rglob("*") if p.is_file()}
    with pytest.raises(PraxiconError, match=f"^{path}: of version 1000000, written by a later "
                                            "psgs .*upgrade psgs"):
        build([], old_folder)
    assert {p: p.read_bytes() for p in old_folder.rglob("*") if p.is_file()} == before


def test_build_refuses_an_empty_folder_name(tmp_path, monkeypatch):
    from praxicon.builder import build
    from psgs.errors import ValidationError

    monkeypatch.chdir(tmp_path)
    with pytest.raises(ValidationError, match="folder's name is empty"):
        build([], "")
    assert not any(tmp_path.iterdir())
