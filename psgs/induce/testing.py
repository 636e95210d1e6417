"""The conformance kit for inducers: :func:`check_inducer` runs the contract on one inducer.

An inducer, built in or a plug-in, must keep the contract every caller relies
on (the CLI, the benchmarks, the praxicon): ``induce`` takes one actiongram or
a sequence of performances and returns an :class:`~psgs.induce.Induction`
that describes that input; bad input is a clear error; the same input gives
the same result; and, for an inducer with parameters, ``get_params``,
``set_params`` and ``clone`` agree. The suite runs the kit on every registered
inducer (entry points included); a plug-in author runs it in their own tests::

    from psgs.induce.testing import check_inducer

    def test_my_inducer_keeps_the_contract():
        check_inducer(MyInducer())

Nothing here needs a test framework: a broken rule raises :class:`AssertionError`
saying which rule and for which inducer.
"""

from __future__ import annotations

import pickle
from collections.abc import Sequence

from ..actiongram import Actiongram
from ..errors import ValidationError
from .results import Induction
from .synthetic import generate

__all__ = ["check_inducer", "examples"]


def examples() -> tuple[Actiongram, ...]:
    """The small actiongrams :func:`check_inducer` learns from by default.

    A synthetic case with a few patterned strings (the paper's protocol made
    small), another of the same sizes, and one in which nothing repeats.

    Returns
    -------
    tuple of Actiongram

    Examples
    --------
    >>> [len(ag.names) for ag in examples()]
    [6, 6, 3]
    """
    sizes = dict(noise=0.1, strings=6, patterned=3, copies=6)
    return (generate(3, **sizes).actiongram, generate(4, **sizes).actiongram,
            Actiongram.from_strings({"x": "abcdefgh", "y": "pqrstu", "z": "k"}))


def check_inducer(inducer, actiongrams: Sequence[Actiongram] | None = None) -> None:
    """Check that ``inducer`` keeps the inducer contract; raise AssertionError if not.

    Parameters
    ----------
    inducer : object
        An inducer: an :class:`~psgs.induce.Inducer` or any object with an
        ``induce`` method (then the parameter rules are checked only when it
        has ``get_params``).
    actiongrams : sequence of Actiongram, optional
        At least two performances of one action to learn from (same strings);
        by default :func:`examples` (the first two learnt from, the third
        checked as one actiongram too).

    Raises
    ------
    AssertionError
        Naming the inducer and the rule it breaks.

    Notes
    -----
    The rules:

    * ``induce(actiongram)`` returns an :class:`~psgs.induce.Induction` of one
      performance whose components are strings of the actiongram, in its order,
      each with a pattern and occurrences (start <= end); its reports, when
      given, are one per string in order; its system is None exactly when there
      is no component, else has one component per component string; its
      ``inducer`` is the inducer's ``name`` when it has one.
    * the same input gives an equal Induction; one actiongram, a list or a
      tuple of it give the same; the Induction survives pickling.
    * several performances give an Induction of that many performances, each
      occurrence in one of them, well-formed as above (components among the
      first performance's strings, in its order, the inducer's name...), or a
      :class:`~psgs.errors.ValidationError` (an inducer that learns from one
      actiongram says so).
    * bad input: an empty sequence is a ValidationError; a string, a mapping,
      a number, or a sequence holding something other than actiongrams, a
      TypeError.
    * parameters: ``get_params`` is a dict that rebuilds an equal inducer;
      ``clone`` is a new object of the same class with equal parameters and
      ``repr``; ``set_params`` returns the inducer, and refuses a name that is
      not a parameter with a ValidationError that changes nothing.

    Examples
    --------
    >>> from psgs.induce import Sequential
    >>> check_inducer(Sequential())
    >>> class Careless(Sequential):
    ...     name = "careless"
    ...     def induce(self, performances):  # learns from a default when given nothing
    ...         return super().induce(performances or examples()[2])
    >>> check_inducer(Careless())  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    AssertionError: check_inducer(careless): induce([]) must raise ValidationError...
    """
    who = getattr(inducer, "name", "") or type(inducer).__name__
    given = tuple(actiongrams) if actiongrams is not None else examples()
    _require(who, len(given) >= 2 and all(isinstance(a, Actiongram) for a in given),
             "needs at least two actiongrams to learn from")
    _require(who, callable(getattr(inducer, "induce", None)), "has no induce method")
    for actiongram in given if actiongrams is None else given[:1]:
        _check_one(who, inducer, actiongram)
    _check_several(who, inducer, given[:2])
    _check_bad_input(who, inducer, given[0])
    if callable(getattr(inducer, "get_params", None)):
        _check_params(who, inducer)


def _require(who: str, ok: bool, what: str) -> None:
    if not ok:
        raise AssertionError(f"check_inducer({who}): {what}")


def _induce(who: str, inducer, data) -> Induction:
    result = inducer.induce(data)
    _require(who, isinstance(result, Induction),
             f"induce must return an Induction, not {type(result).__name__}")
    return result


def _check_one(who: str, inducer, actiongram: Actiongram) -> None:
    """One actiongram: a well-formed, deterministic, picklable Induction."""
    result = _induce(who, inducer, actiongram)
    _require(who, result.performances == 1, "one actiongram must give performances == 1")
    _check_shape(who, inducer, result, actiongram.names)
    _require(who, _induce(who, inducer, actiongram) == result,
             "the same actiongram must give an equal Induction")
    _require(who, _induce(who, inducer, [actiongram]) == result
             == _induce(who, inducer, (actiongram,)),
             "one actiongram and a sequence holding it must give the same Induction")
    _require(who, pickle.loads(pickle.dumps(result)) == result,
             "the Induction must survive pickling")


def _check_shape(who: str, inducer, result: Induction, names: tuple[str, ...]) -> None:
    """An Induction that describes input whose strings are ``names``: of one actiongram or
    of several performances alike (a caller reads both the same way)."""
    _require(who, set(result.components) <= set(names),
             f"components {result.components} must be strings of the actiongram")
    order = [names.index(c) for c in result.components]
    _require(who, order == sorted(order) and len(set(order)) == len(order),
             "components must be distinct and in actiongram order")
    _require(who, set(result.patterns) == set(result.components)
             and all(result.patterns[c] for c in result.components),
             "every component (and nothing else) must have a non-empty pattern")
    _require(who, set(result.occurrences) == set(result.components),
             "every component (and nothing else) must have occurrences")
    for name, spans in result.occurrences.items():
        _require(who, all(a <= b for a, b in spans), f"{name}: an occurrence ends before it starts")
    if result.reports:
        _require(who, tuple(r.name for r in result.reports) == names,
                 "reports, when given, must be one per string, in actiongram order")
    if result.system is None:
        _require(who, not result.components, "a result with components must hold a system")
    else:
        _require(who, len(result.system.components) == len(result.components),
                 "the system must have one component per component string")
        if result.component_names:
            system_names = {g.name for g in result.system.components}
            _require(who, set(result.component_names.values()) == system_names,
                     "component_names must name the system's components")
    name = getattr(inducer, "name", "")
    if name:
        _require(who, result.inducer == name, f"the Induction must name its inducer ({name!r}), "
                                              f"not {result.inducer!r}")


def _check_several(who: str, inducer, takes: tuple[Actiongram, ...]) -> None:
    """Several performances: learnt from, each occurrence in one, or refused clearly."""
    try:
        result = _induce(who, inducer, list(takes))
    except ValidationError:
        return  # an inducer of one actiongram refuses several, saying so
    _require(who, result.performances == len(takes),
             f"{len(takes)} performances must give performances == {len(takes)}")
    _check_shape(who, inducer, result, takes[0].names)
    for name, where in result.occurrence_performance.items():
        _require(who, all(0 <= k < len(takes) for k in where),
                 f"{name}: an occurrence lies outside the performances given")
    _require(who, _induce(who, inducer, list(takes)) == result,
             "the same performances must give an equal Induction")


def _check_bad_input(who: str, inducer, actiongram: Actiongram) -> None:
    """Bad input is a clear error of the right kind, never a result or a traceback."""
    try:
        inducer.induce([])
    except ValidationError:
        pass
    except Exception as exc:
        raise AssertionError(f"check_inducer({who}): induce([]) must raise ValidationError, "
                             f"not {type(exc).__name__}: {exc}") from None
    else:
        raise AssertionError(f"check_inducer({who}): induce([]) must raise ValidationError "
                             f"(no performance), but returned")
    for wrong in ("abab", {"x": "abab"}, 3, [actiongram, "abab"]):
        try:
            inducer.induce(wrong)
        except TypeError:
            continue
        except Exception as exc:
            raise AssertionError(f"check_inducer({who}): induce({wrong!r}) must raise TypeError, "
                                 f"not {type(exc).__name__}: {exc}") from None
        raise AssertionError(f"check_inducer({who}): induce({wrong!r}) must raise TypeError, "
                             f"but returned")


def _check_params(who: str, inducer) -> None:
    """get_params, set_params and clone agree (scikit-learn's estimator contract)."""
    params = inducer.get_params()
    _require(who, isinstance(params, dict), "get_params must return a dict")
    try:
        rebuilt = type(inducer)(**params)
    except Exception as exc:
        raise AssertionError(f"check_inducer({who}): its own get_params() must rebuild it, "
                             f"but {type(exc).__name__}: {exc}") from None
    _require(who, rebuilt.get_params() == params, "rebuilding from get_params() changed them")
    for method in ("clone", "set_params"):
        _require(who, callable(getattr(inducer, method, None)),
                 f"has get_params but no {method}")
    copy = inducer.clone()
    _require(who, type(copy) is type(inducer) and copy is not inducer,
             "clone must give a new inducer of the same class")
    _require(who, copy.get_params() == params and repr(copy) == repr(inducer),
             "a clone must have equal parameters and repr")
    unknown = "no_such_parameter_" + "x" * 3
    try:
        inducer.set_params(**{unknown: 1})
    except ValidationError as exc:
        _require(who, unknown in str(exc), "the error for an unknown parameter must name it")
    else:
        raise AssertionError(f"check_inducer({who}): set_params({unknown}=1) must raise "
                             f"ValidationError")
    _require(who, inducer.get_params() == params, "a refused set_params must change nothing")
    _require(who, inducer.set_params(**params) is inducer, "set_params must return the inducer")
    _require(who, inducer.get_params() == params, "set_params with its own values changed them")
