"""Evaluation on the fixed shot suite: determinism and the statistics."""

from __future__ import annotations

import math

import numpy as np
import pytest

from agents.common.processes import stripes, unstripe
from agents.common.stats import mean_interval, sign_test, t975, wilson
from agents.runs.evaluation import evaluate


def test_wilson_interval():
    lo, hi = wilson(50, 100)
    assert lo == pytest.approx(0.4038, abs=1e-4) and hi == pytest.approx(0.5962, abs=1e-4)
    assert wilson(0, 10)[0] == 0.0 and wilson(10, 10)[1] == 1.0
    lo, hi = wilson(970, 1000)
    assert lo < 0.97 < hi and hi - lo < 0.025
    with pytest.raises(ValueError):
        wilson(3, 0)
    with pytest.raises(ValueError):
        wilson(5, 4)


def test_evaluation_is_deterministic_and_independent_of_workers():
    kwargs = {"obs_mode": "perceived", "perception": "ssl-2012"}
    a = evaluate("scripted", kwargs, episodes=12, workers=1)
    b = evaluate("scripted", kwargs, episodes=12, workers=2)
    assert a.saved == b.saved and a.outcomes == b.outcomes and a.steps == b.steps
    assert a.ball_rmse_m == pytest.approx(b.ball_rmse_m, rel=1e-12)
    assert a.episodes == 12 and a.saves == sum(a.saved)
    assert a.ci_low <= a.save_rate <= a.ci_high
    assert sum(a.outcomes.values()) == 12


def test_scripted_keeper_beats_standing_still_on_the_same_shots():
    scripted = evaluate("scripted", episodes=40)
    idle = evaluate("idle", episodes=40)
    assert scripted.save_rate >= 0.9
    assert scripted.save_rate - idle.save_rate >= 0.25
    assert scripted.ball_rmse_m == 0.0  # truth observations: no estimation error


def test_estimator_time_and_error_are_measured():
    res = evaluate("scripted", {"obs_mode": "perceived", "perception": "realistic"},
                   episodes=5, measure_estimator=True)
    assert res.estimator_us_per_step > 0
    assert 0 < res.ball_rmse_m < 0.5
    truth = evaluate("scripted", episodes=3, measure_estimator=True)
    assert truth.estimator_us_per_step == 0.0


def test_a_callable_policy_runs_in_process():
    res = evaluate(lambda obs: np.zeros(6, np.float32), episodes=3)
    assert res.episodes == 3 and res.policy == "<lambda>"


class _EpisodeCounter:
    """A policy with memory: it counts the steps since its last reset() and records, at
    each reset, how many steps the episode before had."""

    def __init__(self) -> None:
        self.steps, self.episodes = None, []

    def reset(self) -> None:
        if self.steps is not None:
            self.episodes.append(self.steps)
        self.steps = 0

    def __call__(self, obs):
        assert self.steps is not None, "called before reset()"
        self.steps += 1
        return np.zeros(6, np.float32)


def test_policies_with_memory_are_reset_at_every_episode_start(tmp_path):
    policy = _EpisodeCounter()
    res = evaluate(policy, episodes=3)
    policy.reset()
    assert len(policy.episodes) == 3 and sum(policy.episodes) == res.steps

    from agents.runs.evaluation import record_video

    video = _EpisodeCounter()
    record_video(video, tmp_path / "v.mp4", seeds=(0, 1), width=160)
    video.reset()
    assert len(video.episodes) == 2 and all(n > 0 for n in video.episodes)


def test_bad_arguments():
    with pytest.raises(ValueError, match="episodes"):
        evaluate("scripted", episodes=0)
    with pytest.raises(ValueError, match="workers"):
        evaluate("scripted", episodes=2, workers=0)
    with pytest.raises(TypeError, match="unknown"):
        evaluate("scripted", {"obs_mod": "raw"}, episodes=1)


def test_sign_test_is_the_exact_binomial_tail():
    # 2 * P(X <= 5) for X ~ Bin(23, 1/2): 2 * 44,552 / 2^23.
    assert sign_test(18, 5) == pytest.approx(2 * 44_552 / 2 ** 23)
    assert sign_test(5, 18) == sign_test(18, 5)
    assert sign_test(0, 0) == 1.0 and sign_test(7, 7) == 1.0
    assert 0.0 < sign_test(1200, 1000) < 1e-4  # large counts: exact integers, no overflow
    for bad in ((-1, 3), (2.5, 3), (True, 3)):
        with pytest.raises(ValueError, match="must be an integer >= 0"):
            sign_test(*bad)


def test_mean_interval_is_the_student_t_interval():
    m, lo, hi = mean_interval([1.0, 2.0, 3.0, 6.0])
    half = t975(3) * np.std([1.0, 2.0, 3.0, 6.0], ddof=1) / 2.0
    assert m == 3.0 and (lo, hi) == pytest.approx((3.0 - half, 3.0 + half))
    assert mean_interval([2.5]) == (2.5, -math.inf, math.inf)
    with pytest.raises(ValueError, match="at least one value"):
        mean_interval([])


def test_stripes_deal_items_round_robin_and_unstripe_restores_their_order():
    items = list(range(10, 17))
    parts = stripes(items, 3)
    assert parts == [[10, 13, 16], [11, 14], [12, 15]]
    assert unstripe([[2 * x for x in p] for p in parts]) == [2 * x for x in items]
    assert stripes(items[:2], 8) == [[10], [11]]  # no empty stripe
