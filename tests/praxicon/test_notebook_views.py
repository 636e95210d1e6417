"""Systems, actiongrams and inductions show themselves in a notebook (_repr_svg_/_repr_html_)."""

from __future__ import annotations

import psgs
from psgs import Actiongram
from psgs.induce import PAL


def test_system_svg():
    svg = psgs.load("grammars/paper_example.psgs")._repr_svg_()
    assert svg.lstrip().startswith("<?xml") and "N13" in svg
    assert psgs.load("grammars/pcgs_abc.psgs")._repr_svg_().lstrip().startswith("<?xml")


def test_actiongram_html_shows_every_string():
    ag = Actiongram.from_strings({"knee": "BGRYBGRY", "hip": "BY"}, {"knee": [1] * 8,
                                                                     "hip": [2, 6]})
    html = ag._repr_html_()
    assert html.count("<tr>") == 3 and "<code>knee</code>" in html and "width:25.00%" in html


def test_induction_html():
    ag = Actiongram.from_strings({"a": "BGRY" * 6, "b": "GRYB" * 6, "c": "BYBGYRBGYRBY"})
    html = PAL().induce(ag)._repr_html_()
    assert "<b>pal</b>" in html and "<svg" in html and "<code>a</code>" in html
