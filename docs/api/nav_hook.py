"""A mkdocs hook: pages of docs/ that the nav of mkdocs.yml leaves out are listed under "More".

A page added to docs/ by a change that did not touch mkdocs.yml then still appears in the site's
navigation (and ``--strict`` does not fail on an omitted page); the nav in mkdocs.yml only sets
the order of the pages it names.
"""

from __future__ import annotations

from pathlib import Path


def _named(nav) -> set[str]:
    found: set[str] = set()
    for item in nav or []:
        if isinstance(item, str):
            found.add(item)
        elif isinstance(item, dict):
            for value in item.values():
                found |= _named(value) if isinstance(value, list) else {value}
    return found


def on_config(config, **kwargs):
    """Append the pages the nav does not name (sorted), under "More"."""
    if not config.nav:
        return config
    docs = Path(config.docs_dir)
    named = _named(config.nav)
    missing = sorted(p.relative_to(docs).as_posix() for p in docs.rglob("*.md")
                     if p.relative_to(docs).as_posix() not in named)
    if missing:
        config.nav = [*config.nav, {"More": missing}]
    return config
