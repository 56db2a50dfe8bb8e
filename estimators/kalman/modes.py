"""The mode switching of the interacting multiple model ball tracker: a Markov chain between
rest, rolling and maneuver (:class:`ModeChain`).

A continuous-time Markov chain with rates ``lambda_ij`` [1/s] (``rates[i][j]``, ``i != j``) and
``lambda_i = sum_j lambda_ij``. Over a step ``T`` the transition probabilities are taken as
``Pi_ii = exp(-lambda_i T)`` and ``Pi_ij = (1 - exp(-lambda_i T)) lambda_ij / lambda_i``: the
exact probability of leaving mode ``i`` within ``T``, sent where the first jump goes (this
leaves out two or more jumps within one step, ``O((lambda T)^2)``, and costs three
exponentials instead of a matrix exponential). Each row sums to 1.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

from ..checks import check_real
from ..compiled import kernel

__all__ = ["ModeChain", "DEFAULT_RATES", "MIN_PROBABILITY", "check_rates", "mode_products"]

#: Default mode transition rates [1/s], ``DEFAULT_RATES[i][j]`` from mode ``i`` to mode ``j``
#: (rest, rolling, maneuver; the diagonal is unused): a resting ball is kicked about every two
#: seconds and pushed into a slow roll more rarely; a rolling ball comes to rest about every
#: two seconds and is hit about every five; a maneuver is over within about 0.1 s, mostly into
#: a roll. A kick shows in the likelihoods at once whatever its prior rate, while every
#: transition into the maneuver mode mixes its wide covariance into the others: rates into it
#: are kept low (chosen on simulated two-phase kicks at 25 and 60 Hz).
DEFAULT_RATES = ((0.0, 0.1, 0.5),
                 (0.5, 0.0, 0.2),
                 (1.0, 10.0, 0.0))

#: Floor of a mode probability after an update: no mode is ever ruled out for good, and the
#: mixing weights ``mu_i Pi_ij / c_j`` stay defined.
MIN_PROBABILITY = 1e-12


class ModeChain:
    """The Markov chain of mode switches between rest, rolling and maneuver (see the module
    docstring).

    Args:
        rates: ``3 x 3`` transition rates [1/s] (row: from, column: to; the diagonal is
            ignored), each in [0, 1000].

    Attributes:
        rates: the rates as a 3 x 3 tuple of floats (zero diagonal).
        leave: the leaving rates ``lambda_i`` [1/s] of rest, rolling and maneuver.
        jump: where the first jump goes, ``lambda_ij / lambda_i`` for ``ij`` = ``RF, RM, FR,
            FM, MR, MF`` (0 for a mode never left).
    """

    __slots__ = ("rates", "leave", "jump")

    def __init__(self, rates: Sequence[Sequence[float]] = DEFAULT_RATES) -> None:
        self.rates = check_rates(rates)
        # Leaving rates and where the first jump goes: lambda_i, lambda_ij / lambda_i.
        self.leave = tuple(sum(row[j] for j in range(3) if j != i)
                           for i, row in enumerate(self.rates))
        self.jump = tuple(0.0 if self.leave[i] == 0.0 else self.rates[i][j] / self.leave[i]
                          for i in range(3) for j in range(3) if j != i)

    def products(self, mu: Sequence[float], dt: float) -> tuple[float, ...]:
        """``mu_i Pi_ij(dt)`` for mode probabilities ``mu`` and a step of ``dt`` > 0 seconds,
        for the targets rest, rolling and maneuver in turn (9 floats: ``i`` = rest, rolling,
        maneuver within each target); their sums over ``i`` are the predicted mode
        probabilities ``c_j``."""
        return mode_products(mu, dt, self.leave, self.jump)


@kernel
def mode_products(mu: tuple[float, float, float], dt: float,
                  leave: tuple[float, float, float], jump: tuple[float, ...]
                  ) -> tuple[float, ...]:
    """:meth:`ModeChain.products` of a chain with leaving rates ``leave`` ``lambda_i`` [1/s]
    and first-jump fractions ``jump`` ``lambda_ij / lambda_i`` (``RF, RM, FR, FM, MR, MF``):
    ``mu_i Pi_ij(dt)`` for the targets rest, rolling and maneuver in turn."""
    mR, mF, mM = mu
    lR, lF, lM = leave
    jRF, jRM, jFR, jFM, jMR, jMF = jump
    sR, sF, sM = math.exp(-lR * dt), math.exp(-lF * dt), math.exp(-lM * dt)
    gR, gF, gM = mR - mR * sR, mF - mF * sF, mM - mM * sM  # mu_i (1 - Pi_ii)
    return (mR * sR, gF * jFR, gM * jMR,
            gR * jRF, mF * sF, gM * jMF,
            gR * jRM, gF * jFM, mM * sM)


def check_rates(rates: Any) -> tuple[tuple[float, float, float], ...]:
    """``rates`` as a 3 x 3 tuple of floats; ``ValueError`` naming the entry otherwise."""
    try:
        rows = [list(row) for row in rates]
    except TypeError:
        raise ValueError(f"rates must be a 3 x 3 matrix of transition rates [1/s], got "
                         f"{rates!r}") from None
    if len(rows) != 3 or any(len(row) != 3 for row in rows):
        raise ValueError(f"rates must be a 3 x 3 matrix of transition rates [1/s], got "
                         f"{rates!r}")
    return tuple(tuple(0.0 if i == j else check_real(f"rates[{i}][{j}]", rows[i][j], 0.0,
                                                     1000.0, unit=" 1/s")
                       for j in range(3)) for i in range(3))
