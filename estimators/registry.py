"""Named option families: one registry per family maps a name to a value and a one-line
description.

The value is what the name stands for: a factory (a class or function that builds the option,
e.g. a particle-filter variant) or, for preset tables, the frozen spec itself. Every listing
of a family's names (error messages, ``soccer-env list``, the ablation's tables) reads the
registry, so an option added with :meth:`Registry.register` appears everywhere at once.

A registry is a read-only :class:`~collections.abc.Mapping` from name to value, in
registration order; registration is the only way to change it. It depends on nothing, so
every layer of the package (estimators, environment, agents) uses the same class.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Iterator, Mapping
from typing import Any, Generic, TypeVar

__all__ = ["Registry"]

T = TypeVar("T")


class Registry(Mapping[str, T], Generic[T]):
    """The options of one family (see the module docstring).

    Args:
        family: what the options are, as error messages name them (``"ball filter"``).
        entries: initial ``(name, value, description)`` triples, in order.
    """

    def __init__(self, family: str, entries: Iterable[tuple[str, T, str]] = ()) -> None:
        self.family = family
        self._values: dict[str, T] = {}
        self._descriptions: dict[str, str] = {}
        for name, value, description in entries:
            self.register(name, value, description)

    def register(self, name: str, value: T, description: str, *, replace: bool = False) -> T:
        """Add option ``name`` (after the existing ones) and return ``value``. A name already
        registered raises ``ValueError`` unless ``replace`` (which keeps its position)."""
        if not isinstance(name, str) or not name or name.strip() != name or "," in name:
            raise ValueError(f"{self.family} names must be non-empty strings without commas "
                             f"or surrounding spaces, got {name!r}")
        if not isinstance(description, str) or not description.strip():
            raise ValueError(f"{self.family} {name!r} needs a one-line description")
        if name in self._values and not replace:
            raise ValueError(f"{self.family} {name!r} is already registered (pass "
                             f"replace=True to replace it)")
        self._values[name] = value
        self._descriptions[name] = " ".join(description.split())
        return value

    def unregister(self, name: str) -> T:
        """Remove option ``name`` (unknown names raise ``ValueError`` listing the options) and
        return its value."""
        self.check(name)
        del self._descriptions[name]
        return self._values.pop(name)

    # Mapping ------------------------------------------------------------------------------

    def __getitem__(self, name: str) -> T:
        return self._values[name]

    def __iter__(self) -> Iterator[str]:
        return iter(self._values)

    def __len__(self) -> int:
        return len(self._values)

    def __repr__(self) -> str:
        return f"Registry({self.family!r}, {list(self._values)})"

    # Reading ------------------------------------------------------------------------------

    def description(self, name: str) -> str:
        """The one-line description of option ``name``."""
        return self._descriptions[self.check(name)]

    def descriptions(self) -> dict[str, str]:
        """``{name: description}`` of every option, in registration order."""
        return dict(self._descriptions)

    def check(self, name: Any, what: str | None = None) -> str:
        """Return ``name`` if it is a registered option, else raise ``ValueError`` that names
        ``what`` (default: the family) and lists the options."""
        if not isinstance(name, str) or name not in self._values:
            raise ValueError(f"{what or self.family} must be one of {list(self._values)}, "
                             f"got {name!r}")
        return name

    def create(self, name: str, *args: Any, **kwargs: Any) -> Any:
        """Call the factory registered as ``name`` with the given arguments (after checking
        the name)."""
        factory: Callable[..., Any] = self._values[self.check(name)]  # type: ignore[assignment]
        return factory(*args, **kwargs)
