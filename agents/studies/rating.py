"""Elo-style playing-strength ratings from seeded matches.

:func:`round_robin` plays :func:`~agents.studies.matches.head_to_head` between every pair of a
list of sides (each pair on the same seeds, colours swapped every other match), and
:func:`fit_ratings` fits one rating per side to all those matches at once, so a side that met
only some of the others is still placed on the common scale.

The model is Elo's: side ``i`` scores ``E_ij = 1 / (1 + 10^((R_j - R_i) / 400))`` on average
against side ``j`` (a win scores 1, a draw 1/2, a loss 0), so 400 points of difference mean
an expected score of 10/11 (91 %), 200 points 76 %, 100 points 64 %. The ratings maximise the
likelihood ``sum_m [s_m log E_m + (1 - s_m) log(1 - E_m)]`` over the matches ``m`` (Elo's
logistic model fitted in one pass instead of updated match by match, as BayesElo and
Ordo do: the order of the matches does not matter), plus ``prior_draws`` virtual draws for
every pair that played, which keep a side that won every match at a finite rating (Coulom's
BayesElo uses the same prior). The anchor side is held at ``anchor_rating``; the problem is
solved by Newton's method on the others (the log-likelihood is concave).

The 95 % intervals come from the bootstrap over seeds: every pair's seeds (each played from
both sides, the paired unit of :mod:`agents.studies.matches`) are drawn with replacement, the
ratings refitted, and the 2.5 and 97.5 percentiles of each rating taken (the anchor's interval
is a point; the others' widths include the anchor's own uncertainty).
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from agents.studies.matches import HeadToHead, Side, head_to_head

__all__ = ["Rating", "fit_ratings", "rate", "round_robin", "rating_table", "expected_score",
           "ELO_SCALE"]

#: Points per factor of 10 in the odds of winning (Elo's 400).
ELO_SCALE = 400.0
_LN10 = math.log(10.0)


def expected_score(difference: float) -> float:
    """Elo's expected score of a side rated ``difference`` points above its opponent:
    ``1 / (1 + 10^(-difference / 400))``."""
    return 1.0 / (1.0 + 10.0 ** (-difference / ELO_SCALE))


@dataclass(frozen=True)
class Rating:
    """One side's rating.

    Attributes:
        label: the side's label.
        rating: Elo points (the anchor's is ``anchor_rating``).
        low, high: the bootstrap 95 % interval.
        matches: matches the side played.
        score: its mean score (win 1, draw 1/2, loss 0) over them.
    """

    label: str
    rating: float
    low: float
    high: float
    matches: int
    score: float


def _pairs(results: Sequence[HeadToHead]) -> tuple[list[str], list[tuple[int, int, np.ndarray,
                                                                         np.ndarray]]]:
    """The side labels and, per head-to-head, ``(i, j, seeds, scores)``: the seed of each match
    and ``i``'s score in it."""
    labels: list[str] = []
    out = []
    for h in results:
        for side in (h.a, h.b):
            if side.label not in labels:
                labels.append(side.label)
        i, j = labels.index(h.a.label), labels.index(h.b.label)
        if i == j:
            raise ValueError(f"a head-to-head of {h.a.label!r} against itself cannot rate it")
        seeds = np.array([r.seed for r in h.records], dtype=np.int64)
        scores = np.array([1.0 if r.goals_a > r.goals_b else 0.5 if r.goals_a == r.goals_b
                           else 0.0 for r in h.records])
        out.append((i, j, seeds, scores))
    return labels, out


def _connected(n: int, pairs: Sequence[tuple[int, int]]) -> bool:
    parent = list(range(n))

    def find(x: int) -> int:
        while parent[x] != x:
            parent[x] = parent[parent[x]]
            x = parent[x]
        return x

    for i, j in pairs:
        parent[find(i)] = find(j)
    return len({find(x) for x in range(n)}) == 1


def _fit(n: int, games: Sequence[tuple[int, int, float, float]], anchor: int) -> np.ndarray:
    """Maximum-likelihood ratings in natural units (``theta = R ln 10 / 400``) of ``n`` sides
    from ``games`` ``(i, j, total score of i, count)``, ``theta[anchor] = 0``: Newton's method
    on the concave log-likelihood (a few iterations; step halving keeps it monotone)."""
    theta = np.zeros(n)
    free = [k for k in range(n) if k != anchor]
    ii = np.array([g[0] for g in games])
    jj = np.array([g[1] for g in games])
    s = np.array([g[2] for g in games])
    c = np.array([g[3] for g in games])

    def loglik(t: np.ndarray) -> float:
        d = t[ii] - t[jj]
        # s log sigma(d) + (c - s) log sigma(-d), computed stably.
        return float(np.sum(-s * np.logaddexp(0.0, -d) - (c - s) * np.logaddexp(0.0, d)))

    value = loglik(theta)
    for _ in range(100):
        d = theta[ii] - theta[jj]
        e = 1.0 / (1.0 + np.exp(-d))
        r = s - c * e
        w = c * e * (1.0 - e)
        grad = np.zeros(n)
        np.add.at(grad, ii, r)
        np.add.at(grad, jj, -r)
        hess = np.zeros((n, n))
        np.add.at(hess, (ii, ii), w)
        np.add.at(hess, (jj, jj), w)
        np.add.at(hess, (ii, jj), -w)
        np.add.at(hess, (jj, ii), -w)
        step = np.zeros(n)
        step[free] = np.linalg.solve(hess[np.ix_(free, free)], grad[free])
        scale = 1.0
        while True:
            trial = theta + scale * step
            new = loglik(trial)
            if new >= value - 1e-12 or scale < 1e-6:
                break
            scale *= 0.5
        theta, gain, value = trial, new - value, new
        if np.max(np.abs(scale * step)) < 1e-10 or abs(gain) < 1e-13:
            break
    return theta


def _games(pairs: Sequence[tuple[int, int, np.ndarray, np.ndarray]], prior_draws: float,
           picks: Sequence[np.ndarray] | None = None) -> list[tuple[int, int, float, float]]:
    games = []
    for k, (i, j, _seeds, scores) in enumerate(pairs):
        if picks is not None:
            scores = scores[picks[k]]
        games.append((i, j, float(scores.sum()) + 0.5 * prior_draws,
                      float(len(scores)) + prior_draws))
    return games


def fit_ratings(results: Sequence[HeadToHead], anchor: str | None = None,
                anchor_rating: float = 1000.0, prior_draws: float = 1.0,
                bootstrap: int = 1000, seed: int = 0) -> list[Rating]:
    """One Elo rating per side of ``results`` (see the module docstring), best first.

    Args:
        results: head-to-heads; together they must connect every side.
        anchor: the label of the side held at ``anchor_rating`` (default: the first side of
            the first head-to-head).
        anchor_rating: its rating.
        prior_draws: virtual draws added to every pair that played (> 0 keeps the ratings
            finite when a side won every match).
        bootstrap: resamples for the intervals (0: no intervals, ``low = high = rating``).
        seed: the resampling's seed.
    """
    if not results:
        raise ValueError("results must hold at least one head-to-head")
    if not (math.isfinite(prior_draws) and prior_draws >= 0.0):
        raise ValueError(f"prior_draws must be >= 0, got {prior_draws!r}")
    if isinstance(bootstrap, bool) or not isinstance(bootstrap, (int, np.integer)) \
            or bootstrap < 0:
        raise ValueError(f"bootstrap must be an integer >= 0, got {bootstrap!r}")
    labels, pairs = _pairs(results)
    if anchor is None:
        anchor = labels[0]
    if anchor not in labels:
        raise ValueError(f"anchor must be one of the sides {labels}, got {anchor!r}")
    if not _connected(len(labels), [(i, j) for i, j, _, _ in pairs]):
        raise ValueError("the head-to-heads do not connect every side: ratings on one scale "
                         "need every side linked to the others by matches")
    a = labels.index(anchor)
    if prior_draws == 0.0:
        for i, j, _, scores in pairs:
            if scores.min() == scores.max() and scores[0] != 0.5:
                raise ValueError(f"{labels[i]!r} against {labels[j]!r}: every match has the "
                                 "same winner, whose rating is infinite without a prior; "
                                 "use prior_draws > 0")
    to_elo = ELO_SCALE / _LN10
    best = _fit(len(labels), _games(pairs, prior_draws), a) * to_elo + anchor_rating
    low, high = best.copy(), best.copy()
    if bootstrap:
        rng = np.random.default_rng(seed)
        units = [[np.flatnonzero(seeds == u) for u in np.unique(seeds)]
                 for _, _, seeds, _ in pairs]
        draws = np.empty((bootstrap, len(labels)))
        for b in range(bootstrap):
            picks = [np.concatenate([u[k] for k in rng.integers(len(u), size=len(u))])
                     for u in units]
            draws[b] = _fit(len(labels), _games(pairs, prior_draws, picks), a)
        draws = draws * to_elo + anchor_rating
        low, high = np.percentile(draws, [2.5, 97.5], axis=0)
    played = np.zeros(len(labels))
    total = np.zeros(len(labels))
    for i, j, _, scores in pairs:
        played[i] += len(scores)
        played[j] += len(scores)
        total[i] += scores.sum()
        total[j] += len(scores) - scores.sum()
    out = [Rating(labels[k], float(best[k]), float(low[k]), float(high[k]), int(played[k]),
                  float(total[k] / played[k])) for k in range(len(labels))]
    return sorted(out, key=lambda r: -r.rating)


def round_robin(sides: Sequence[Side], matches: int = 100, start_seed: int = 0,
                env_kwargs: Mapping[str, Any] | None = None, workers: int | None = None,
                progress: Callable[[str], None] | None = None,
                pairs: Sequence[tuple[Side, Side]] | None = None) -> list[HeadToHead]:
    """:func:`~agents.studies.matches.head_to_head` between every pair of ``sides`` (labels must
    differ), or only between the ``pairs`` given (sides of ``sides``), ``matches`` seeded
    matches each, every pair on the same seeds; ``progress`` is called with each pair's
    summary line."""
    labels = [s.label for s in sides]
    if len(sides) < 2 or len(set(labels)) != len(labels):
        raise ValueError(f"a round robin needs two or more sides with different labels, got "
                         f"{labels}")
    if pairs is None:
        pairs = list(itertools.combinations(sides, 2))
    strangers = sorted({s.label for pair in pairs for s in pair if s not in sides})
    if strangers:
        raise ValueError(f"pairs must be made of the sides {labels}; got {strangers}")
    out = []
    for a, b in pairs:
        h = head_to_head(a, b, matches, start_seed, env_kwargs, workers)
        if progress is not None:
            progress(h.summary())
        out.append(h)
    return out


def rate(sides: Sequence[Side], matches: int = 100, anchor: str | None = None, **kwargs: Any
         ) -> tuple[list[Rating], list[HeadToHead]]:
    """:func:`round_robin` then :func:`fit_ratings` (``anchor`` default: the first side);
    ``kwargs`` go to :func:`round_robin`."""
    results = round_robin(sides, matches, **kwargs)
    return fit_ratings(results, anchor=anchor or sides[0].label), results


def rating_table(ratings: Sequence[Rating]) -> str:
    """The ratings as a Markdown table, best first."""
    lines = ["| side | Elo | 95 % interval | matches | score |", "|---|---|---|---|---|"]
    for r in ratings:
        lines.append(f"| {r.label} | {r.rating:.0f} | {r.low:.0f} to {r.high:.0f} | "
                     f"{r.matches} | {100 * r.score:.1f} % |")
    return "\n".join(lines)
