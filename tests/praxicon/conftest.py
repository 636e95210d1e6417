"""Fixtures of the praxicon tests (helpers in praxicon_fixtures.py)."""

from praxicon_fixtures import manifest  # noqa: F401  (a fixture)
