"""Validation helpers of the whole package: clear errors that name the argument and say what
is allowed.

* arguments of the environments and tools: :func:`check_choice`, :func:`check_range` (returns
  the value as a float), :func:`check_int`, :func:`reject_unknown`, :func:`parse_scales`;
* fields of the presets' dataclasses: :func:`check_number`, :func:`check_integer`,
  :func:`check_flag`, :func:`check_rgb`;
* mappings of a dataclass's fields: :func:`check_fields`, :func:`from_mapping`,
  :func:`resolve_preset`.
"""

from __future__ import annotations

import dataclasses
import inspect
import math
from collections.abc import Callable, Iterable, Mapping, Sequence
from typing import Any, TypeVar

import numpy as np

from estimators.registry import Registry

__all__ = ["reject_unknown", "keyword_names", "check_choice", "check_range", "check_int",
           "parse_scales", "check_number", "check_integer", "check_flag", "check_rgb",
           "check_fields", "from_mapping", "resolve_preset", "preset_table", "check_options",
           "real_array"]


def keyword_names(func: Callable[..., Any]) -> list[str]:
    """Names of the keyword arguments that ``func`` accepts explicitly (not ``**kwargs``)."""
    kinds = (inspect.Parameter.POSITIONAL_OR_KEYWORD, inspect.Parameter.KEYWORD_ONLY)
    return [p.name for p in inspect.signature(func).parameters.values()
            if p.kind in kinds and p.name != "self"]


def reject_unknown(where: str, unknown: Mapping[str, Any], allowed: Iterable[str]) -> None:
    """Raise ``TypeError`` if ``unknown`` holds any keyword, in Python's own wording (``f()
    got an unexpected keyword argument 'name'``, which libraries such as TorchRL look for to
    drop an optional keyword they tried) followed by the list of the allowed ones."""
    if unknown:
        names = sorted(unknown)
        raise TypeError(
            f"{where}() got an unexpected keyword argument {names[0]!r} (unknown keyword "
            f"argument(s) {names}; allowed: {sorted(allowed)})"
        )


def check_choice(name: str, value: Any, allowed: Iterable[Any]) -> None:
    """Raise ``ValueError`` unless ``value`` is one of ``allowed``."""
    allowed = list(allowed)
    if value not in allowed:
        raise ValueError(f"{name} must be one of {allowed}, got {value!r}")


def check_range(name: str, value: float, low: float, high: float) -> float:
    """Return ``float(value)``; raise ``ValueError`` unless a finite real number (not a
    string, a bool or a complex number) in ``[low, high]``."""
    if isinstance(value, (str, bytes, bool, np.bool_, complex, np.complexfloating)):
        raise ValueError(f"{name} must be a number in [{low}, {high}], got {value!r}")
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a number in [{low}, {high}], got {value!r}") from None
    if not (math.isfinite(v) and low <= v <= high):
        raise ValueError(f"{name} must be in [{low}, {high}], got {value!r}")
    return v


def check_int(name: str, value: Any, low: int, high: int) -> int:
    """Return ``int(value)``; raise ``ValueError`` unless an integer (not a bool) in
    ``[low, high]``."""
    if not _is_integer_in(value, low, high):
        raise ValueError(f"{name} must be an integer in {low}..{high}, got {value!r}")
    return int(value)


def _is_integer_in(value: Any, low: int, high: int) -> bool:
    """Whether ``value`` is an integer (not a bool) in ``[low, high]``."""
    return (isinstance(value, (int, np.integer)) and not isinstance(value, bool)
            and low <= value <= high)


def check_number(name: str, value: Any, low: float, high: float, *, low_open: bool = False,
                 high_open: bool = False, unit: str = "") -> None:
    """Raise ``ValueError`` unless ``value`` is a finite number (not a bool) in the interval
    from ``low`` to ``high`` (open at an end where said): "``name`` must be in [low,
    high]``unit``, got ...". For the fields of a spec, which keep the value as given."""
    ok = (isinstance(value, (int, float, np.integer, np.floating)) and not isinstance(value, bool)
          and math.isfinite(value) and (value > low if low_open else value >= low)
          and (value < high if high_open else value <= high))
    if not ok:
        lo, hi = "(" if low_open else "[", ")" if high_open else "]"
        raise ValueError(f"{name} must be in {lo}{low}, {high}{hi}{unit}, got {value!r}")


def check_integer(name: str, value: Any, low: int, high: int, unit: str = "") -> None:
    """Raise ``ValueError`` unless ``value`` is an integer (not a bool) in ``[low, high]``."""
    if not _is_integer_in(value, low, high):
        raise ValueError(f"{name} must be an integer in [{low}, {high}]{unit}, got {value!r}")


def check_seed(seed: Any) -> None:
    """Raise ``ValueError`` unless ``seed`` is None or an integer >= 0 (not a bool): what
    ``reset(seed=...)`` takes (Gymnasium's own check raises its ``Error``, numpy's a
    ``TypeError`` without the argument's name)."""
    if seed is not None and not (isinstance(seed, (int, np.integer))
                                 and not isinstance(seed, (bool, np.bool_)) and seed >= 0):
        raise ValueError(f"seed must be None or an integer >= 0, got {seed!r}")


def check_options(options: Any, allowed: Sequence[str], who: str, strict: bool = True
                  ) -> dict[str, Any]:
    """``reset``'s ``options`` as a dict: ``ValueError`` naming ``who`` (the environment)
    unless None or a mapping whose keys are among ``allowed`` (with ``strict``; otherwise
    other keys are ignored)."""
    if options is None:
        return {}
    if not isinstance(options, Mapping):
        raise ValueError(f"options must be None or a dict, got {type(options).__name__} "
                         f"{options!r}")
    unknown = sorted(str(k) for k in options if k not in allowed)
    if unknown and strict:
        takes = f"takes the options {list(allowed)}" if allowed else "takes no options"
        raise ValueError(f"options: {who} {takes}; got {unknown}")
    return dict(options)


def real_array(name: str, value: Any) -> np.ndarray:
    """``value`` as a float64 array: ``ValueError`` naming ``name`` unless it holds real
    numbers (booleans, integers or floats: not complex numbers, dates, strings or objects)."""
    try:
        arr = np.asarray(value)
    except (TypeError, ValueError):  # ragged
        raise ValueError(f"{name} must be an array of real numbers, got {value!r}") from None
    if arr.dtype.kind not in "biuf":
        raise ValueError(f"{name} must hold real numbers, got an array of {arr.dtype}")
    return arr.astype(np.float64)


def check_pair(name: str, value: Any) -> tuple[float, float]:
    """``value`` as ``(low, high)``: raise ``ValueError`` naming ``name`` unless it is a
    sequence of exactly two finite real numbers (not bools), whatever else it must satisfy
    (checked by the caller)."""
    ok = (isinstance(value, (tuple, list, np.ndarray)) and len(value) == 2
          and all(isinstance(v, (int, float, np.integer, np.floating))
                  and not isinstance(v, (bool, np.bool_)) and math.isfinite(v)
                  for v in value))
    if not ok:
        raise ValueError(f"{name} must be (low, high), two finite numbers, got {value!r}")
    return float(value[0]), float(value[1])


def check_flag(name: str, value: Any) -> None:
    """Raise ``ValueError`` unless ``value`` is True or False."""
    if not isinstance(value, bool):
        raise ValueError(f"{name} must be True or False, got {value!r}")


def check_rgb(name: str, value: Any) -> None:
    """Raise ``ValueError`` unless ``value`` is an ``(r, g, b)`` tuple of integers in
    [0, 255]."""
    ok = (isinstance(value, tuple) and len(value) == 3
          and all(isinstance(c, int) and not isinstance(c, bool) and 0 <= c <= 255
                  for c in value))
    if not ok:
        raise ValueError(f"{name} must be an (r, g, b) tuple of integers in [0, 255], got "
                         f"{value!r}")


def parse_scales(name: str, given: Mapping[str, float] | None, known: Mapping[str, str]
                 ) -> dict[str, float]:
    """Validate a ``{term: scale}`` mapping against the ``known`` terms (name -> description).

    Missing terms get scale 0 (off). Unknown names raise ``ValueError`` listing the known
    ones; scales must be finite numbers.
    """
    scales = dict.fromkeys(known, 0.0)
    if given is None:
        return scales
    if not isinstance(given, Mapping):
        raise TypeError(f"{name} must be a mapping of term name to scale, got "
                        f"{type(given).__name__}")
    unknown = sorted(set(given) - set(known))
    if unknown:
        raise ValueError(f"unknown {name} term(s) {unknown}; known: {sorted(known)}")
    for key, value in given.items():
        scales[key] = check_range(f"{name}[{key!r}]", value, -1e6, 1e6)
    return scales


_S = TypeVar("_S")


def check_fields(cls: Any, keys: Iterable[str], what: str, *, exclude: Iterable[str] = (),
                 error: type[Exception] = ValueError, noun: str = "key", where: str = ""
                 ) -> None:
    """Raise ``error`` unless every one of ``keys`` names a field of the dataclass ``cls``
    (or of an instance), ``exclude`` left out: "unknown {what} {noun}(s) [...]{where};
    allowed: [...]". The one check behind every mapping of a dataclass's fields the package
    accepts (:func:`from_mapping`, :func:`resolve_preset`, the agents' configurations)."""
    allowed = {f.name for f in dataclasses.fields(cls)} - set(exclude)
    unknown = sorted(set(keys) - allowed)
    if unknown:
        raise error(f"unknown {what} {noun}(s) {unknown}{where}; allowed: {sorted(allowed)}")


def from_mapping(cls: type[_S], value: _S | Mapping[str, Any] | None, what: str,
                 defaults: Mapping[str, Any] | None = None) -> _S:
    """An instance of the dataclass ``cls`` from an argument ``what``: an instance (returned
    as it is), None (``cls(**defaults)``) or a mapping of its fields over ``defaults``
    (unknown keys raise ``ValueError``; lists become tuples, as JSON gives them). Anything else
    raises ``TypeError``."""
    if value is None:
        return cls(**dict(defaults or {}))
    if isinstance(value, cls):
        return value
    if isinstance(value, Mapping):
        check_fields(cls, value, what)
        given = {k: tuple(v) if isinstance(v, list) else v for k, v in value.items()}
        return cls(**{**dict(defaults or {}), **given})
    raise TypeError(f"{what} must be a {cls.__name__} or a mapping of its fields, got "
                    f"{type(value).__name__}")


def resolve_preset(kind: str, table: Mapping[str, _S], value: str | _S,
                   overrides: dict[str, Any]) -> _S:
    """The preset ``value`` of ``table`` (a name, or a spec of the table's type) with the
    ``overrides`` of its fields applied (``dataclasses.replace``; the spec validates the new
    values). Unknown names raise ``ValueError``, unknown fields and other types ``TypeError``,
    each listing what is allowed."""
    if isinstance(value, str):
        if value not in table:
            raise ValueError(f"unknown {kind} preset {value!r}; known: {sorted(table)}")
        spec = table[value]
    elif any(isinstance(value, type(s)) for s in table.values()):
        spec = value
    else:
        raise TypeError(
            f"{kind} must be a preset name ({sorted(table)}) or a "
            f"{type(next(iter(table.values()))).__name__}, got {type(value).__name__}"
        )
    if overrides:
        check_fields(spec, overrides, kind, exclude=("name", "source"), error=TypeError,
                     noun="parameter")
        spec = dataclasses.replace(spec, **overrides)
    return spec


def preset_table(family: str, specs: Mapping[str, _S]) -> Registry[_S]:
    """A registry of the frozen ``specs`` of one preset family (``"field"``, ``"vision"``,
    ...), each described by its ``source``; the table :func:`resolve_preset` reads. Register
    more with ``table.register(name, spec, spec.source)``."""
    return Registry(f"{family} preset", [(name, spec, getattr(spec, "source", "") or name)
                                         for name, spec in specs.items()])
