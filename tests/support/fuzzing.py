"""What the fuzz tests share (``tests/test_fuzz.py``, ``tests/test_fuzz_objects.py``): the
strategies of what a caller might pass by mistake, the settings, and the checks of an outcome:
a result whose numbers are finite, or a refusal whose message names the argument (each
counted in hypothesis' statistics: ``pytest tests/test_fuzz*.py
--hypothesis-show-statistics``)."""

from __future__ import annotations

from typing import Any

import numpy as np
from hypothesis import HealthCheck, event, settings
from hypothesis import strategies as st

__all__ = ["NUMBERS", "ANYTHING", "FAST", "finite", "named", "accepted"]

NUMBERS = st.one_of(st.integers(-10**12, 10**12),
                    st.floats(allow_nan=True, allow_infinity=True))
#: Anything a caller might pass by mistake.
ANYTHING = st.one_of(
    st.none(), st.booleans(), NUMBERS, st.text(max_size=6),
    st.lists(NUMBERS, max_size=4).map(tuple), st.lists(NUMBERS, max_size=7),
    st.dictionaries(st.text(max_size=8), NUMBERS, max_size=2))
FAST = settings(max_examples=120, deadline=5000,
                suppress_health_check=[HealthCheck.too_slow,
                                       HealthCheck.function_scoped_fixture])


def finite(value: Any) -> bool:
    """Whether every number in ``value`` (arrays, dicts and sequences searched) is finite."""
    if value is None or isinstance(value, (str, bool)):
        return True
    if isinstance(value, dict):
        return all(finite(v) for v in value.values())
    if isinstance(value, (list, tuple)):
        return all(finite(v) for v in value)
    if isinstance(value, (int, float, np.number, np.ndarray)):
        arr = np.asarray(value)
        return not np.issubdtype(arr.dtype, np.number) or bool(np.all(np.isfinite(arr)))
    return True


def named(err: Exception, *names: str) -> bool:
    """Whether the message of ``err`` names one of ``names`` (and count the refusal in
    hypothesis' statistics: ``pytest tests/test_fuzz.py --hypothesis-show-statistics``)."""
    text = str(err)
    found = any(n in text for n in names)
    event("refused, naming the argument" if found else "refused, NOT naming the argument")
    return found


def accepted(ok: bool) -> bool:
    """Count an accepted input in hypothesis' statistics; ``ok``: its results are finite."""
    event("accepted, finite results" if ok else "accepted, NON-FINITE results")
    return ok
