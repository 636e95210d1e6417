"""Every reader of a praxicon's versioned files tells a later psgs's file from an earlier one's
alike: the index and the descriptions file (``load``), the descriptions inside it
(``Descriptions.from_dict``) and the build's check of its folder. Each wrote the test again;
a version that is no whole number (a text, a float, true) is an earlier one's everywhere."""

from __future__ import annotations

import json

import pytest

from fuzz_support import praxicon_seed
from praxicon import dump, load
from praxicon.builder import build
from praxicon.description import FORMAT_VERSION as DESCRIBED, DescriptionError, Descriptions
from praxicon.jsonvalues import written_by
from praxicon.records import FORMAT_VERSION as RECORDED, PraxiconError

SAID = [None, "99", 99.0, True, -1, "later", 10**6]


def _folder(tmp_path, name: str, said):
    folder = tmp_path / "px"
    dump(praxicon_seed(), folder)
    path = folder / name
    data = json.loads(path.read_text())
    data["version"] = said
    path.write_text(json.dumps(data))
    return folder, path


def _later(said, version: int) -> bool:
    """What each reader tested before: a whole number (not a bool) above its version."""
    return type(said) is int and said > version


@pytest.mark.parametrize("said", SAID)
@pytest.mark.parametrize("name, version", [("index.json", RECORDED),
                                           ("descriptions.json", DESCRIBED)])
def test_load_and_build_agree_on_which_psgs_wrote_a_file(tmp_path, said, name, version):
    folder, path = _folder(tmp_path, name, said)
    later = written_by(said, version) == "later"
    assert later == _later(said, version)
    with pytest.raises(PraxiconError) as refused:
        load(folder)
    assert str(refused.value).startswith(f"{path}: ")
    assert ("upgrade psgs" in str(refused.value)) == later
    assert (("rebuild it" in str(refused.value)) or ("learn them again" in str(refused.value))) \
        == (not later)
    if later:  # not written over: the build stops before any change
        with pytest.raises(PraxiconError, match="written by a later psgs"):
            build([], folder)
    else:  # an earlier one's folder is built again, as the message says
        build([], folder, progress=False, log=lambda line: None)
        assert json.loads((folder / "index.json").read_text())["version"] == RECORDED


@pytest.mark.parametrize("said", SAID)
def test_the_descriptions_inside_the_file_agree_too(said):
    data = praxicon_seed().descriptions.to_dict()
    data["version"] = said
    with pytest.raises(DescriptionError) as refused:
        Descriptions.from_dict(data)
    assert ("upgrade psgs" in str(refused.value)) == (written_by(said, DESCRIBED) == "later")
    assert ("learn the descriptions again" in str(refused.value)) == (not _later(said, DESCRIBED))
