"""Every error kinetology and praxicon name in their public surface is under psgs's root
(``psgs.PSGSError``), so one ``except PSGSError`` catches what any part of the distribution
raises for bad input, and a command line catches nothing wider."""

from __future__ import annotations

import importlib
import inspect

import pytest

from psgs.errors import PSGSError

MODULES = ("kinetology", "kinetology.viewer", "kinetology.codec", "praxicon",
           "praxicon.records", "praxicon.description", "praxicon.features",
           "praxicon.datasets")


@pytest.mark.parametrize("module", MODULES)
def test_every_public_error_is_a_psgs_error(module):
    mod = importlib.import_module(module)
    errors = [name for name in getattr(mod, "__all__", ())
              if inspect.isclass(getattr(mod, name, None))
              and issubclass(getattr(mod, name), BaseException)]
    assert errors or module in ("kinetology.codec",)
    for name in errors:
        assert issubclass(getattr(mod, name), PSGSError), f"{module}.{name}"
