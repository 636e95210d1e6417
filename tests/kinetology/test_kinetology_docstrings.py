"""The examples in the docstrings of the kinetology modules for performances run as written."""

from __future__ import annotations

import doctest
import importlib

import pytest

from kinetology_fixtures import REPO


@pytest.mark.parametrize("module", ["kinetology.labels", "kinetology.performances",
                                    "kinetology.joints", "kinetology.segmentation"])
@pytest.mark.usefixtures("examples_tempdir")
def test_docstring_examples(module, monkeypatch):
    monkeypatch.chdir(REPO)  # examples name the data as ../shared/...
    result = doctest.testmod(importlib.import_module(module), optionflags=doctest.ELLIPSIS)
    assert result.attempted > 0 and result.failed == 0
