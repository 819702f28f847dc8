"""What a parameter may be, checked before any work: the scenarios' parameters
(``sim.generator.*``) and their effects' (``sim.generator.effect_params.<effect>.*``), a
volumetric set-up read from outside (``volumetric.json``), and config keys of the shell.

A value outside its domain used to fail deep inside the work (a division by zero, an empty
array: exit 1 with a traceback) or quietly produce nonsense (a negative noise).  An owner lists
a :class:`Rule` per parameter in ``param_rules`` (and relations between parameters in
``param_relations``); :func:`check_params` / :func:`check_values` apply them and raise a
:class:`~thermocomp.base.errors.ConfigError` naming the key, the value and what it may be (exit 2).

Hand-written: scikit-learn's parameter validation (``sklearn.utils._param_validation``) is
private API, and these rules need lists and pairs of numbers it does not describe.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from numbers import Integral, Real

import numpy as np

from thermocomp.base.errors import ConfigError, ParameterError


@dataclass(frozen=True)
class Rule:
    """A test of one value and what it says a valid value is (``"a number > 0"``)."""

    test: Callable[[object], bool]
    says: str

    def __call__(self, value) -> bool:
        try:
            return bool(self.test(value))
        except (TypeError, ValueError):
            return False


def _number(v) -> bool:
    return isinstance(v, Real) and not isinstance(v, bool) and math.isfinite(v)


def _integer(v) -> bool:
    return isinstance(v, Integral) and not isinstance(v, bool)


def _boolean(v) -> bool:
    return isinstance(v, (bool, np.bool_))


def _items(v) -> list | None:
    if isinstance(v, (str, bytes, Mapping)) or not hasattr(v, "__iter__"):
        return None
    return list(v)


def number(lo: float = -math.inf, hi: float = math.inf, *, open_lo: bool = False,
           open_hi: bool = False) -> Rule:
    """A finite number in the interval (open or closed at each end)."""
    def test(v):
        return (_number(v) and (v > lo if open_lo else v >= lo) and (v < hi if open_hi else v <= hi))
    left, right = "(" if open_lo else "[", ")" if open_hi else "]"
    if lo == -math.inf and hi == math.inf:
        says = "a finite number"
    elif hi == math.inf:
        says = f"a number {'>' if open_lo else '>='} {lo:g}"
    else:
        says = f"a number in {left}{lo:g}, {hi:g}{right}"
    return Rule(test, says)


# Every integer knob sizes something (an array, a loop, a pool): a billion samples of a monitor
# window was OOM-killed at 24 GB, a billion Monte Carlo machines ran until killed.  So a count
# is bounded unless its rule says more: a million is beyond every documented use.
MAX_COUNT = 1_000_000


def integer(lo: int, hi: int | None = None, *, at_most: int = MAX_COUNT) -> Rule:
    """An integer in [``lo``, ``hi``]; without ``hi``, a count of at most ``at_most``."""
    top = at_most if hi is None else hi
    return Rule(lambda v: _integer(v) and lo <= v <= top, f"an integer {_between(lo, hi, at_most)}")


def _between(lo, hi, at_most) -> str:
    return f">= {lo}, at most {at_most:,}" if hi is None else f"in [{lo}, {hi}]"


def numbers(lo: float = 0.0, hi: float = math.inf, *, length: int | None = None,
            open_lo: bool = False, empty: bool = False) -> Rule:
    """A non-empty list of finite numbers in ``[lo, hi]`` (exactly ``length`` of them when given;
    ``> lo`` when ``open_lo``; possibly empty when ``empty``)."""
    def test(v):
        items = _items(v)
        return (items is not None and (empty or len(items) >= 1)
                and (length is None or len(items) == length)
                and all(_number(x) and (x > lo if open_lo else x >= lo) and x <= hi for x in items))
    count = (f"{length} finite numbers" if length else
             f"a {'' if empty else 'non-empty '}list of finite numbers")
    if lo == -math.inf and hi == math.inf:
        return Rule(test, count)
    if hi == math.inf:
        return Rule(test, f"{count} {'>' if open_lo else '>='} {lo:g}")
    return Rule(test, f"{count} in {'(' if open_lo else '['}{lo:g}, {hi:g}]")


def integers(lo: int, hi: int | None = None, *, empty: bool = False, at_most: int = MAX_COUNT) -> Rule:
    """A list of integers in [``lo``, ``hi``] (non-empty unless ``empty``); without ``hi``, counts
    of at most ``at_most``."""
    top = at_most if hi is None else hi

    def test(v):
        items = _items(v)
        return items is not None and (empty or len(items) >= 1) and all(
            _integer(x) and lo <= x <= top for x in items)
    return Rule(test, f"a {'' if empty else 'non-empty '}list of integers {_between(lo, hi, at_most)}")


def either(*rules: Rule) -> Rule:
    """Any one of ``rules``."""
    return Rule(lambda v: any(r(v) for r in rules), " or ".join(r.says for r in rules))


def span(lo: float = 0.0, hi: float = math.inf, *, open_lo: bool = False) -> Rule:
    """A pair ``[a, b]`` of numbers with ``lo <= a <= b <= hi`` (``lo < a`` when open)."""
    def test(v):
        items = _items(v)
        return (items is not None and len(items) == 2 and all(_number(x) for x in items)
                and (items[0] > lo if open_lo else items[0] >= lo) and items[0] <= items[1] <= hi)
    where = f"{'>' if open_lo else '>='} {lo:g}" + ("" if hi == math.inf else f" and <= {hi:g}")
    return Rule(test, f"a pair [low, high] of numbers {where}, low <= high")


def subset(options, *, empty: bool = False) -> Rule:
    """A list of some of ``options`` (non-empty unless ``empty``)."""
    def test(v):
        items = _items(v)
        return items is not None and (empty or len(items) >= 1) and all(x in options for x in items)
    return Rule(test, f"a {'' if empty else 'non-empty '}list of {', '.join(map(str, options))}")


def choice(*options) -> Rule:
    """One of ``options``; ``True``/``False`` only as themselves (``1`` is not ``True``)."""
    def test(v):
        return any(v is o or (not _boolean(v) and not _boolean(o) and v == o) for o in options)
    names = ", ".join(_spelled(o) for o in options)
    return Rule(test, f"one of {names}" if len(options) > 1 else names)


def _spelled(option) -> str:
    """An option as a config file spells it."""
    if option is None:
        return "null"
    return ("true" if option else "false") if _boolean(option) else str(option)


def overrides(cls) -> Rule:
    """``None`` or a map of some of the dataclass ``cls``'s fields to numbers (or lists of them)."""
    names = list(getattr(cls, "__dataclass_fields__", {}))

    def value(x):
        items = _items(x)
        return _number(x) or (items is not None and all(_number(i) for i in items))

    def test(v):
        return v is None or (isinstance(v, Mapping) and all(k in names and value(x)
                                                            for k, x in v.items()))
    return Rule(test, f"null or a map of some of {', '.join(names)} to numbers")


def optional(rule: Rule) -> Rule:
    return Rule(lambda v: v is None or rule(v), f"null or {rule.says}")


def number_map(lo: float = -math.inf) -> Rule:
    """A map of names to finite numbers >= ``lo``."""
    return Rule(lambda v: isinstance(v, Mapping) and all(_number(x) and x >= lo for x in v.values()),
                "a map of names to numbers" + ("" if lo == -math.inf else f" >= {lo:g}"))


def text() -> Rule:
    return Rule(lambda v: isinstance(v, str) and v != "", "a non-empty text")


def file_name(most: int = 100) -> Rule:
    """A name that is one path component: it names folders (``data/interim/<name>``), and ``..``,
    a ``/`` or nothing would put them outside their parent, or make them the parent itself.
    At most ``most`` characters, none a control character: the stages stage their folders as
    ``.<name>.stage-<pid>-<random>``, and 300 characters ended a run in 'File name too long'."""
    return Rule(lambda v: isinstance(v, str) and v not in ("", ".", "..") and "/" not in v
                and "\\" not in v and not v.startswith("~") and len(v) <= most
                and v.isprintable(),
                f"one path component of at most {most} printable characters: not empty, '.' "
                "or '..', no '/'")


def texts(what: str = "texts", *, empty: bool = False, unique: bool = False) -> Rule:
    """A list of non-empty texts (non-empty unless ``empty``; each once when ``unique``)."""
    def test(v):
        items = _items(v)
        return items is not None and (empty or len(items) >= 1) and all(
            isinstance(x, str) and x != "" for x in items) and (not unique or len(set(items)) == len(items))
    return Rule(test, f"a {'' if empty else 'non-empty '}list of {what}{', each once' if unique else ''}")


BOOLEAN = Rule(_boolean, "true or false")
POSITIVE = number(0.0, open_lo=True)
NON_NEGATIVE = number(0.0)
FRACTION = number(0.0, 1.0)


def samples_in(generator, spans, period: str, unit_s: float = 1.0) -> list[tuple[str, str]]:
    """Relations: each of the ``spans`` (hours) holds at least two samples of ``period`` (in
    ``unit_s`` seconds)."""
    step_s = float(getattr(generator, period)) * unit_s
    return [(key, f"must hold two samples of sim.generator.{period}={getattr(generator, period)}")
            for key in spans
            if 3600.0 * float(getattr(generator, key)) < 2 * step_s]


def check_values(values: Mapping, rules: Mapping[str, Rule], prefix: str,
                 error: type[ValueError] = ConfigError) -> None:
    """Raise ``error`` (:class:`ConfigError`) ``<prefix>.<key>=<value>: must be ...`` for the
    first entry of ``values`` outside its rule (a missing entry is ``None``)."""
    for key, rule in rules.items():
        value = _plain(values.get(key))
        if not rule(value):
            raise error(f"{prefix + '.' if prefix else ''}{key}={value!r}: must be {rule.says}")


def check_params(owner, prefix: str = "sim.generator", values: Mapping | None = None,
                 error: type[ValueError] = ConfigError) -> None:
    """:func:`check_values` of ``owner``'s ``param_rules`` over its attributes (or ``values``),
    then its first broken relation (``param_relations()``: ``(key, what it must be)``).

    An estimator checks itself in ``fit`` with ``prefix`` its class name and ``error``
    :class:`~thermocomp.base.errors.ParameterError`; the shell checks the same rules before any
    work with ``prefix`` the config key (``model.estimator``)."""
    rules = getattr(owner, "param_rules", {})
    if values is None:
        values = {key: getattr(owner, key) for key in rules}
    check_values(values, rules, prefix, error)
    relations = getattr(owner, "param_relations", None)
    broken = relations() if relations else []
    if broken:
        key, message = broken[0]
        value = _plain(values[key] if key in values else getattr(owner, key))
        raise error(f"{prefix}.{key}={value!r}: {message}")


def check_estimator(estimator) -> None:
    """An estimator's own check in ``fit``: :class:`~thermocomp.base.errors.ParameterError`
    ``ARX.max_inputs=0: must be an integer >= 1``."""
    check_params(estimator, type(estimator).__name__, error=ParameterError)


def _plain(value):
    """Hydra's ListConfig (and tuples) as lists, for the message and the tests."""
    if isinstance(value, Mapping):
        return {str(k): _plain(v) for k, v in value.items()}
    if isinstance(value, (str, bytes)) or not hasattr(value, "__iter__"):
        return value
    return [_plain(v) for v in value]
