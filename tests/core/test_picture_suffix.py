"""The one check that matplotlib writes a picture to a path (psgs._foundation.pictures)."""

from __future__ import annotations

import sys

import pytest

from psgs._foundation.pictures import picture_suffix
from psgs.errors import MissingDependency, ValidationError


@pytest.mark.parametrize("name", ["walk.txt", "walk", "walk.png.bvh"])
def test_a_suffix_matplotlib_cannot_write_is_refused_naming_the_path(name):
    with pytest.raises(ValidationError, match=rf"^{name}: matplotlib cannot write .* give one "
                                              r"of \.png, \.svg, \.pdf, "):
        picture_suffix(name)


def test_the_suffix_is_read_in_any_case():
    assert picture_suffix("walk.SVG") == ".svg" and picture_suffix("a.b/walk.Pdf") == ".pdf"


def test_without_matplotlib_the_extra_is_named_though_a_submodule_was_imported(monkeypatch):
    # a submodule imported before stays in sys.modules: importing it alone would succeed
    import matplotlib.backend_bases  # noqa: F401

    monkeypatch.setitem(sys.modules, "matplotlib", None)
    with pytest.raises(MissingDependency, match=r"pip install 'psgs\[praxicon\]'"):
        picture_suffix("walk.png", needs="pip install 'psgs[praxicon]'")
