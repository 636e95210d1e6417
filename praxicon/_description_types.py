"""The values :mod:`praxicon.description` learns and recognition reads:
:class:`ActionDescription` (one action), :class:`Spread` (how the copies of any action vary,
shared by every action) and :class:`Descriptions` (every action and their spread), each
checked when made and written to and read from JSON.

They are :mod:`praxicon.description`'s names, imported and documented there; their fields
are read and checked by :mod:`praxicon._description_json`, whose errors become
:class:`~praxicon.description.DescriptionError`.
"""

from __future__ import annotations

import json
import math
from collections import Counter
from dataclasses import dataclass

import numpy as np

from ._arguments import DescriptionError
from ._description_json import (FieldError, action_fields, check_action, check_format,
                                check_spread, json_object, spread_fields)

__all__ = ["FORMAT_VERSION", "ActionDescription", "Spread", "Descriptions"]

#: Bumped when what a description holds or how features are computed changes (6: the
#: spread's ``tail``, heavy-tailed likelihoods for whole takes; 5: the descriptions of families, several actions that are styles of one content, decide "none of
#: these" for their members; 4: each action keeps its own features, which need not be the
#: spread's, so that actions learnt from different skeletons keep their joints; before, only
#: the features every take had were kept).
FORMAT_VERSION = 6


@dataclass(frozen=True)
class ActionDescription:
    """One action: per feature the mean of its takes and their spread (standard deviation).

    ``features`` are the ones every take of the action has (a subset of the spread's: actions
    learnt from other skeletons have other joints); ``takes`` counts the takes (or windows)
    learnt from; ``window`` is the length in seconds of the windows learnt from (0: whole
    takes). Checked when made, as a file's are (:func:`~praxicon._description_json.check_action`).
    """

    name: str
    features: tuple[str, ...]
    mean: tuple[float, ...]
    spread: tuple[float, ...]
    takes: int
    window: float = 0.0
    version: int = FORMAT_VERSION

    def __post_init__(self) -> None:
        _fields(check_action, *vars(self).values(), FORMAT_VERSION)

    def __repr__(self) -> str:  # a summary, not every feature's mean and spread
        windows = f", windows of {self.window:g} s" if self.window else ""
        return (f"<ActionDescription {self.name!r}: {len(self.features)} features from "
                f"{self.takes} takes{windows}, format {self.version}>")

    def to_dict(self) -> dict:
        """Plain JSON values (floats kept exactly: JSON writes them with ``repr``)."""
        return {"format": "praxicon-action-description", "version": self.version,
                "name": self.name, "features": list(self.features), "mean": list(self.mean),
                "spread": list(self.spread), "takes": self.takes, "window": self.window}

    def to_json(self) -> str:
        """JSON text of :meth:`to_dict`."""
        return json.dumps(self.to_dict())

    @classmethod
    def from_dict(cls, data: dict) -> "ActionDescription":
        """The description :meth:`to_dict` wrote (another format or version: a clear error)."""
        return cls(*_fields(action_fields, data, FORMAT_VERSION))

    @classmethod
    def from_json(cls, text: str) -> "ActionDescription":
        """The description :meth:`to_json` wrote.

        Examples
        --------
        >>> d = ActionDescription("wave", ("a.rx:pose",), (0.1,), (2.0 / 3,), 2)
        >>> ActionDescription.from_json(d.to_json()) == d
        True
        """
        return cls.from_dict(_fields(json_object, text))


@dataclass(frozen=True)
class Spread:
    """How copies of an action vary around its mean, shared by every action of a praxicon.

    Features are divided by ``scale``; in those units the covariance is
    ``diag(noise) + factorsᵀ factors`` (``factors``: rows of shared directions). Checked when
    made, as a file's are (:func:`~praxicon._description_json.check_spread`).
    """

    features: tuple[str, ...]
    scale: tuple[float, ...]
    factors: tuple[tuple[float, ...], ...]
    noise: tuple[float, ...]
    threshold: float
    temperature: float
    window: float = 0.0
    version: int = FORMAT_VERSION
    limits: tuple[tuple[str, float], ...] = ()  # per feature group: its largest distance
    tail: float = math.inf  # of the likelihoods (scoring.log_likelihoods): inf is Gaussian

    def __post_init__(self) -> None:
        _fields(check_spread, self.features, self.scale, self.factors, self.noise,
                self.threshold, self.temperature, self.window, self.limits, self.tail,
                self.version, FORMAT_VERSION)

    def __repr__(self) -> str:  # a summary, not the factors
        return (f"<Spread: {len(self.features)} features, {len(self.factors)} shared "
                f"directions, format {self.version}>")

    def to_dict(self) -> dict:
        """Plain JSON values (floats kept exactly)."""
        return {"format": "praxicon-spread", "version": self.version,
                "features": list(self.features), "scale": list(self.scale),
                "factors": [list(f) for f in self.factors], "noise": list(self.noise),
                "threshold": self.threshold, "temperature": self.temperature,
                "window": self.window, "limits": [[g, v] for g, v in self.limits],
                "tail": None if math.isinf(self.tail) else self.tail}

    @classmethod
    def from_dict(cls, data: dict) -> "Spread":
        """The spread :meth:`to_dict` wrote."""
        features, scale, factors, noise, threshold, temperature, window, limits, tail = \
            _fields(spread_fields, data, FORMAT_VERSION)
        return cls(features, scale, factors, noise, threshold, temperature, window,
                   FORMAT_VERSION, limits, tail)


@dataclass(frozen=True)
class Descriptions:
    """Every action's description and their shared spread: what recognition reads.

    ``families``: when several actions are styles of one content (a praxicon built one action
    per content and style), descriptions of the families, each family's takes pooled (and
    every other action as its own family, named by its name), which decide "none of these"
    for a family's members; ``family_of`` names each action's family (``""``: an action
    alone, decided by its own description). See :func:`describe`'s ``families``.
    """

    actions: tuple[ActionDescription, ...]
    spread: Spread
    families: "Descriptions | None" = None
    family_of: tuple[str, ...] = ()

    def __post_init__(self) -> None:
        if not isinstance(self.spread, Spread):
            raise DescriptionError(f"the spread must be a Spread, not "
                                   f"{type(self.spread).__name__}")
        if not (isinstance(self.actions, tuple) and self.actions and all(
                isinstance(a, ActionDescription) for a in self.actions)):
            raise DescriptionError("'actions' must be a tuple of action descriptions, one or "
                                   "more")
        named = Counter(a.name for a in self.actions)  # not names.count per action (quadratic)
        for a in self.actions:
            if named[a.name] > 1:
                raise DescriptionError(f"action {a.name!r} is described twice")
            if a.window != self.spread.window:  # parse cuts windows of the spread's length
                raise DescriptionError(f"action {a.name!r}: 'window' {a.window:g} is not the "
                                       f"spread's {self.spread.window:g}")
        self._check_families()
        known = set(self.spread.features)
        for a in self.actions:
            if not known.issuperset(a.features):
                extra = sorted(set(a.features) - known)[:3]
                raise DescriptionError(f"action {a.name!r} has features the spread has not "
                                       f"({', '.join(extra)})")

    def _check_families(self) -> None:
        if not isinstance(self.family_of, tuple) or not all(
                isinstance(f, str) for f in self.family_of):
            raise DescriptionError(f"'family_of' must be a tuple of family names, not "
                                   f"{self.family_of!r:.60}")
        if self.families is None:
            if self.family_of:
                raise DescriptionError("'family_of' without the families' descriptions")
            return
        if self.spread.window:
            raise DescriptionError("window descriptions have no families (parsing reads "
                                   "each action's own)")
        if not isinstance(self.families, Descriptions):
            raise DescriptionError(f"families must be Descriptions, not "
                                   f"{type(self.families).__name__}")
        if self.families.families is not None:
            raise DescriptionError("the families' descriptions have families of their own")
        if len(self.family_of) != len(self.actions):
            raise DescriptionError(f"'family_of' names {len(self.family_of)} families for "
                                   f"{len(self.actions)} actions")
        named = set(self.families.names)
        members = Counter(self.family_of)  # not family_of.count per action (quadratic)
        for a, f in zip(self.actions, self.family_of):
            wanted = f or a.name  # an action alone is its own family
            if wanted not in named:
                raise DescriptionError(f"action {a.name!r}: no description of its family "
                                       f"{wanted!r}")
            if f and members[f] < 2:
                raise DescriptionError(f"action {a.name!r}: family {f!r} has one member "
                                       f"(an action alone has the family '')")
        if self.families.spread.window != self.spread.window:
            raise DescriptionError("the families' descriptions are of other windows")

    @property
    def names(self) -> tuple[str, ...]:
        """The actions' names, in order."""
        return tuple(a.name for a in self.actions)

    def __repr__(self) -> str:  # a summary, not every action's features
        window = self.spread.window
        of = f"windows of {window:g} s" if window else "whole takes"
        return (f"<Descriptions of {len(self.actions)} actions ({of}): "
                f"{len(self.spread.features)} features, format {FORMAT_VERSION}>")

    def aligned(self, field: str = "mean") -> np.ndarray:
        """Actions x the spread's features: each action's ``field`` (``"mean"`` or
        ``"spread"``), NaN where the action lacks the feature.

        Examples
        --------
        >>> spread = Spread(("a", "b"), (1.0, 1.0), (), (1.0, 1.0), 1.0, 1.0)
        >>> d = Descriptions((ActionDescription("x", ("b",), (2.0,), (0.5,), 2),), spread)
        >>> d.aligned().tolist()
        [[nan, 2.0]]
        """
        index = {f: i for i, f in enumerate(self.spread.features)}
        out = np.full((len(self.actions), len(index)), np.nan)
        for k, a in enumerate(self.actions):
            values = np.asarray(getattr(a, field), dtype=float)
            if a.features == self.spread.features:
                out[k] = values
            else:
                out[k, [index[f] for f in a.features]] = values
        return out

    def to_dict(self) -> dict:
        """Plain JSON values (floats kept exactly)."""
        out = {"format": "praxicon-descriptions", "version": FORMAT_VERSION,
               "actions": [a.to_dict() for a in self.actions], "spread": self.spread.to_dict()}
        if self.families is not None:
            out.update(families=self.families.to_dict(), family_of=list(self.family_of))
        return out

    def to_json(self) -> str:
        """JSON text; floats come back exactly from :meth:`from_json`."""
        return json.dumps(self.to_dict())

    @classmethod
    def from_dict(cls, data: dict) -> "Descriptions":
        """The descriptions :meth:`to_dict` wrote (another version: a clear error)."""
        _fields(check_format, data, "praxicon-descriptions", FORMAT_VERSION)
        listed = data.get("actions")
        if not isinstance(listed, list) or not listed:
            raise DescriptionError("'actions' must be a list of action descriptions, one or "
                                   "more")
        spread = Spread.from_dict(data.get("spread"))
        actions = tuple(ActionDescription.from_dict(a) for a in listed)
        if "families" not in data:
            if "family_of" in data:
                raise DescriptionError("'family_of' without the families' descriptions")
            return cls(actions, spread)
        family_of = data.get("family_of")
        if not isinstance(family_of, list) or not all(isinstance(f, str) for f in family_of):
            raise DescriptionError("'family_of' must be a list of family names, one per action")
        families = data["families"]
        if isinstance(families, dict) and "families" in families:
            raise DescriptionError("the families' descriptions have families of their own")
        try:
            families = cls.from_dict(families)
        except DescriptionError as exc:
            raise DescriptionError(f"families: {exc}") from None
        return cls(actions, spread, families, tuple(family_of))

    @classmethod
    def from_json(cls, text: str) -> "Descriptions":
        """The descriptions :meth:`to_json` wrote (another version: a clear error)."""
        return cls.from_dict(_fields(json_object, text))


def _fields(check, *args):
    """``check(*args)`` (a reader or a check of :mod:`praxicon._description_json`), its errors
    :mod:`praxicon.description`'s (``DescriptionError``)."""
    try:
        return check(*args)
    except FieldError as exc:
        raise DescriptionError(str(exc)) from None
