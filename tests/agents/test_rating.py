"""Elo-style ratings (agents.studies.rating): the fitted difference is Elo's for a known score, the
fit is the likelihood's maximum (scipy as the oracle), ratings chain through sides that never
met, the anchor holds, a clean sweep stays finite under the prior, the bootstrap interval is
reproducible and brackets the estimate, and a real round robin orders scripted above idle."""

import math

import numpy as np
import pytest
from scipy.optimize import minimize

from agents.studies.matches import HeadToHead, MatchRecord, Side
from agents.studies.rating import (
    expected_score,
    fit_ratings,
    rate,
    rating_table,
)


def _h2h(a: str, b: str, outcomes: list[int], first_seed: int = 0) -> HeadToHead:
    """A head-to-head of sides labelled ``a`` and ``b`` with ``a``'s outcomes (+1 win, 0 draw,
    -1 loss), two matches per seed."""
    recs = [MatchRecord(first_seed + k // 2, k % 2 == 0, max(o, 0), max(-o, 0), 1,
                        (0.0, 0.0), (0.0, 0.0), (1, 1), 0.0) for k, o in enumerate(outcomes)]
    return HeadToHead(Side("scripted", label=a), Side("idle", label=b), recs)


def _outcomes(wins: int, draws: int, losses: int) -> list[int]:
    return [1] * wins + [0] * draws + [-1] * losses


def test_elo_expected_score():
    assert expected_score(0.0) == 0.5
    assert expected_score(400.0) == pytest.approx(10 / 11)
    assert expected_score(-200.0) == pytest.approx(1 - expected_score(200.0))


def test_a_known_score_gives_elo_difference():
    # 64 wins, 24 draws, 12 losses: a score of 0.76, which Elo puts 200.2 points up.
    h = _h2h("A", "B", _outcomes(64, 24, 12))
    ratings = {r.label: r for r in fit_ratings([h], anchor="B", prior_draws=0.0, bootstrap=0)}
    want = 400 * math.log10(0.76 / 0.24)
    assert ratings["A"].rating - ratings["B"].rating == pytest.approx(want, abs=1e-6)
    assert ratings["B"].rating == 1000.0
    assert ratings["A"].score == pytest.approx(0.76) and ratings["A"].matches == 100


def test_fit_is_the_maximum_likelihood():
    results = [_h2h("A", "B", _outcomes(30, 10, 20)), _h2h("B", "C", _outcomes(25, 15, 20)),
               _h2h("A", "C", _outcomes(28, 6, 6)), _h2h("C", "D", _outcomes(10, 5, 25))]
    prior = 1.0
    got = {r.label: r.rating for r in fit_ratings(results, anchor="A", prior_draws=prior,
                                                  bootstrap=0)}
    labels = ["A", "B", "C", "D"]
    data = []
    for h in results:
        s = sum(1.0 if r.goals_a > r.goals_b else 0.5 if r.goals_a == r.goals_b else 0.0
                for r in h.records)
        data.append((labels.index(h.a.label), labels.index(h.b.label), s + 0.5 * prior,
                     len(h.records) + prior))

    def nll(free):
        r = np.concatenate([[0.0], free])
        total = 0.0
        for i, j, s, n in data:
            e = 1 / (1 + 10 ** ((r[j] - r[i]) / 400))
            total -= s * math.log(e) + (n - s) * math.log(1 - e)
        return total

    best = minimize(nll, np.zeros(3), method="BFGS", options={"gtol": 1e-9})
    for k, label in enumerate(labels[1:]):
        assert got[label] - got["A"] == pytest.approx(best.x[k], abs=0.01)


def test_ratings_chain_through_sides_that_never_met():
    # A scores 0.76 against B, B 0.76 against C; A and C never met: about 400 apart.
    results = [_h2h("A", "B", _outcomes(64, 24, 12)),
               _h2h("B", "C", _outcomes(64, 24, 12), first_seed=100)]
    r = {x.label: x.rating for x in fit_ratings(results, anchor="C", anchor_rating=1500.0,
                                                prior_draws=0.0, bootstrap=0)}
    assert r["C"] == 1500.0
    assert r["A"] - r["C"] == pytest.approx(2 * 400 * math.log10(0.76 / 0.24), abs=1e-6)


def test_a_clean_sweep_is_finite_only_with_the_prior():
    h = _h2h("A", "B", _outcomes(100, 0, 0))
    with pytest.raises(ValueError, match="prior_draws > 0"):
        fit_ratings([h], prior_draws=0.0)
    r = {x.label: x.rating for x in fit_ratings([h], anchor="B", bootstrap=0)}
    # One virtual draw: a score of 100.5 / 101.
    assert r["A"] - r["B"] == pytest.approx(400 * math.log10(100.5 / 0.5), abs=1e-6)


def test_bootstrap_interval_is_reproducible_and_brackets_the_estimate():
    results = [_h2h("A", "B", _outcomes(40, 30, 30)), _h2h("B", "C", _outcomes(45, 20, 35))]
    one = fit_ratings(results, anchor="B", bootstrap=300, seed=3)
    two = fit_ratings(results, anchor="B", bootstrap=300, seed=3)
    assert one == two
    for r in one:
        assert r.low <= r.rating <= r.high
        if r.label == "B":
            assert r.low == r.high == 1000.0
        else:
            assert 30 < r.high - r.low < 300  # 100 matches: an interval of about +-70 points
    assert [r.label for r in one] == sorted([r.label for r in one],
                                            key=lambda x: -{q.label: q.rating for q in one}[x])
    table = rating_table(one)
    assert table.splitlines()[0].startswith("| side | Elo |") and "| B | 1000 |" in table


@pytest.mark.parametrize("results, kwargs, match", [
    ([], {}, "at least one head-to-head"),
    ([_h2h("A", "A", [1, 0])], {}, "against itself"),
    ([_h2h("A", "B", [1, 0]), _h2h("C", "D", [1, 0])], {}, "do not connect"),
    ([_h2h("A", "B", [1, 0])], {"anchor": "Z"}, "anchor must be one of"),
    ([_h2h("A", "B", [1, 0])], {"prior_draws": -1.0}, "prior_draws must be >= 0"),
    ([_h2h("A", "B", [1, 0])], {"bootstrap": 1.5}, "bootstrap must be an integer"),
])
def test_bad_input_is_refused(results, kwargs, match):
    with pytest.raises(ValueError, match=match):
        fit_ratings(results, **kwargs)


def test_a_round_robin_rates_a_team_that_plays_above_one_that_does_not():
    sides = [Side("scripted", "truth", label="scripted"), Side("idle", "truth", label="idle")]
    ratings, results = rate(sides, matches=2, env_kwargs={"blue": 1, "yellow": 1,
                                                          "match_duration": 6.0}, workers=1)
    assert len(results) == 1 and results[0].wins == 2
    r = {x.label: x for x in ratings}
    assert r["scripted"].rating == 1000.0 and r["idle"].rating < 1000.0
    assert r["scripted"].score == 1.0 and r["idle"].matches == 2
    with pytest.raises(ValueError, match="different labels"):
        rate([sides[0], sides[0]], matches=2)


def test_a_round_robin_plays_only_the_pairs_given():
    sides = [Side("scripted", "truth", label="scripted"), Side("idle", "truth", label="idle"),
             Side("idle", "truth", label="idle too")]
    results = rate(sides, matches=2, env_kwargs={"blue": 1, "yellow": 1, "match_duration": 1.0},
                   workers=1, pairs=[(sides[0], sides[1]), (sides[0], sides[2])])[1]
    assert [(h.a.label, h.b.label) for h in results] == [("scripted", "idle"),
                                                         ("scripted", "idle too")]
    with pytest.raises(ValueError, match=r"pairs must be made of the sides .* got \['other'\]"):
        rate(sides, matches=2, pairs=[(sides[0], Side("idle", label="other"))])
