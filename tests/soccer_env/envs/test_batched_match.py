"""The batched match (:class:`soccer_env.envs.batched_match.MatchBatch`): the same matches as
single :class:`~soccer_env.envs.match.SoccerParallelEnv` seeded ``seed + k`` (kick-offs,
goals, free kicks, scores, rewards, ends and the next match), determinism, bad input."""

from __future__ import annotations

import numpy as np
import pytest

import soccer_env
from agents.scripted import ScriptedTeam
from soccer_env.envs.batched import NotBatchable
from soccer_env.envs.batched_match import MatchBatch


def _compare(kwargs: dict, n: int, steps: int, seed: int) -> dict[str, int]:
    """Step a batch and ``n`` single matches with the same actions (each match's scripted
    teams, computed from the single match's observations, with random noise and random
    kicks so that the ball goes out and into the goals); count the events. Events, scores,
    rewards, terminations and truncations must agree exactly (rewards to 1e-9),
    observations to 1e-4: the batch's worlds lie on patches of one space, whose offset
    coordinates round differently (about 1e-12 m), and its observations are computed in
    float64 where a single match's team builder works in single precision."""
    batch = MatchBatch(n, **kwargs)
    singles = [soccer_env.parallel_env(**kwargs) for _ in range(n)]
    agents = singles[0].possible_agents
    teams = [ScriptedTeam.for_env(singles[0], t) for t in ("blue", "yellow")]
    sizes = (singles[0].world.n_blue, singles[0].world.n_yellow)
    obs = batch.reset(seed=seed)
    single_obs = [e.reset(seed=seed + k)[0] for k, e in enumerate(singles)]
    rng = np.random.default_rng(seed)
    counts = {"goal": 0, "touch": 0, "goal_line": 0, "over_bar": 0, "end": 0}
    for t in range(steps):
        act = np.empty((n, len(agents), 6), np.float32)
        for k, o in enumerate(single_obs):
            rows = np.stack([o[a] for a in agents])
            np.testing.assert_allclose(obs[k], rows, atol=1e-4, err_msg=f"step {t}, match {k}")
            act[k, :sizes[0]] = teams[0].act(rows[:sizes[0]])
            act[k, sizes[0]:] = teams[1].act(rows[sizes[0]:])
        act[..., :3] += rng.normal(0.0, 0.3, act[..., :3].shape)
        act[..., 3] = np.where(rng.random(act.shape[:2]) < 0.05, 1.0, act[..., 3])
        act = np.clip(act, -1.0, 1.0)
        result = batch.step(act)
        obs = result.obs
        for k, e in enumerate(singles):
            o, r, te, tr, info = e.step(dict(zip(agents, act[k])))
            a0 = agents[0]
            event = info[a0]["event"]
            assert result.events[k] == event, (t, k)
            assert result.scores[k].tolist() == e.score, (t, k)
            np.testing.assert_allclose(result.rewards[k], [r[a] for a in agents], atol=1e-9)
            assert (result.terminated[k], result.truncated[k]) == (te[a0], tr[a0]), (t, k)
            if event:
                counts[event] += 1
            if te[a0] or tr[a0]:
                counts["end"] += 1
                assert result.lengths[k] == e.cycles
                np.testing.assert_allclose(result.final_obs[k], np.stack([o[a] for a in agents]),
                                           atol=1e-4)
                o, _ = e.reset()
            else:
                assert k not in result.final_obs
            single_obs[k] = o
    return counts


@pytest.mark.parametrize("kwargs", [
    {"blue": 2, "yellow": 2, "match_duration": 3.0, "field": "ssl-2012",
     "shaping": {"ball_progress": 1.0, "ball_distance": 0.5}},
    {"blue": 3, "yellow": 1, "max_cycles": 150, "field": "ssl-2012"},
    # The batched perception and command channels (latency; losses under "realistic").
    {"blue": 2, "yellow": 2, "match_duration": 3.0, "field": "ssl-2012",
     "obs_mode": "perceived", "perception": "ssl-2012"},
    {"blue": 2, "yellow": 2, "match_duration": 3.0, "field": "ssl-div-b",
     "obs_mode": "perceived", "perception": "realistic"},
    # Each match's own perception (the teams perceive differently), fed from the batch.
    {"blue": 2, "yellow": 2, "match_duration": 3.0, "field": "ssl-2012",
     "obs_mode": "perceived", "perception": {"blue": "ssl-2012", "yellow": "realistic"}},
    # Each team predicts its robots through its own commands (its own filters).
    {"blue": 2, "yellow": 2, "match_duration": 3.0, "field": "ssl-2012",
     "obs_mode": "perceived",
     "perception": {"vision": "ssl-2012", "robot_prediction": "commands"}},
    {"blue": 2, "yellow": 1, "max_cycles": 150, "field": "ssl-2012", "obs_mode": "raw",
     "perception": {"blue": "realistic", "yellow": "ssl-2012"}, "belief_features": True},
])
def test_the_batch_plays_the_single_matches(kwargs, monkeypatch):
    import soccer_env.perception.batched as perception_batch

    monkeypatch.setattr(perception_batch, "MIN_BATCH", 1)  # (batched at any size)
    batch = MatchBatch(2, **kwargs)
    shared = kwargs.get("obs_mode") == "perceived" and isinstance(kwargs["perception"], str)
    assert (batch._senses.vision is not None) == shared  # one batched perception where it can
    # (Contacts amplify the shared spaces' rounding; under noisy raw detections the scripted
    # teams' choices make that visible after about 350 steps.)
    counts = _compare(kwargs, n=4, steps=300 if "obs_mode" in kwargs else 400, seed=3)
    # Goals with their kick-offs or outs with their free kicks, and new matches (goals and
    # outs both happen in the truth cases).
    restarts = counts["goal"] + counts["touch"] + counts["goal_line"] + counts["over_bar"]
    assert restarts >= 1 and counts["end"] >= 4, counts
    if "obs_mode" not in kwargs:
        assert counts["goal"] >= 1 and counts["touch"] + counts["goal_line"] >= 1, counts


@pytest.mark.parametrize("kwargs", [
    {"blue": 2, "yellow": 2, "robot": "humanoid", "match_duration": 2.0},
    {"blue": 2, "yellow": 1, "robot": {"blue": "ssl", "yellow": "humanoid"},
     "field": "ssl-2012", "max_cycles": 100},
    {"blue": 1, "yellow": 1, "robot": "humanoid-2012", "obs_mode": "perceived",
     "match_duration": 2.0},
])
def test_humanoid_matches_in_the_batch(kwargs):
    """Humanoid and mixed matches: each match's walk engines, heads (turned by the head
    control from the robots' attention) and perception beside the batched physics; random
    actions (walks, kicks, dives), through match ends."""
    n = 3
    batch = MatchBatch(n, **kwargs)
    singles = [soccer_env.parallel_env(**kwargs) for _ in range(n)]
    agents = singles[0].possible_agents
    obs = batch.reset(seed=2)
    single_obs = [e.reset(seed=2 + k)[0] for k, e in enumerate(singles)]
    rng = np.random.default_rng(2)
    ends = 0
    for t in range(250):
        for k, o in enumerate(single_obs):
            np.testing.assert_allclose(obs[k], np.stack([o[a] for a in agents]), atol=1e-4,
                                       err_msg=f"step {t}, match {k}")
        act = rng.uniform(-1, 1, (n, len(agents), 6)).astype(np.float32)
        result = batch.step(act)
        obs = result.obs
        for k, e in enumerate(singles):
            o, r, te, tr, info = e.step(dict(zip(agents, act[k])))
            a0 = agents[0]
            assert result.events[k] == info[a0]["event"], (t, k)
            assert (result.terminated[k], result.truncated[k]) == (te[a0], tr[a0]), (t, k)
            np.testing.assert_allclose(result.rewards[k], [r[a] for a in agents], atol=1e-9)
            if te[a0] or tr[a0]:
                ends += 1
                o, _ = e.reset()
            single_obs[k] = o
    assert ends >= 3


def test_same_seed_same_matches_and_seed_lists():
    def run(seed):
        b = MatchBatch(3, blue=2, yellow=2, match_duration=1.0)
        out = [b.reset(seed=seed)]
        rng = np.random.default_rng(0)
        for _ in range(80):
            out.append(b.step(rng.uniform(-1, 1, (3, 4, 6))).obs)
        return np.stack(out), b

    first, b = run(7)
    again, _ = run(7)
    np.testing.assert_array_equal(first, again)
    np.testing.assert_array_equal(b.reset(seed=[7, 8, None])[:2], first[0][:2])
    assert b.times.tolist() == [0.0, 0.0, 0.0]


def test_bad_input_names_the_argument():
    b = MatchBatch(2, blue=1, yellow=1)
    with pytest.raises(RuntimeError, match="reset"):
        b.step(np.zeros((2, 2, 6)))
    b.reset(seed=0)
    with pytest.raises(ValueError, match=r"shape \(2, 2, 6\)"):
        b.step(np.zeros((2, 6)))
    bad = np.zeros((2, 2, 6))
    bad[1, 1, 2] = np.nan
    with pytest.raises(ValueError, match="yellow_0 of match 1"):
        b.step(bad)
    with pytest.raises(ValueError, match="n_matches"):
        MatchBatch(0)
    with pytest.raises(ValueError, match="seed"):
        b.reset(seed=[1])
    with pytest.raises(TypeError, match="colour"):
        MatchBatch(2, blue=1, yellow=1, colour="red")


@pytest.mark.parametrize("kwargs,why", [
    ({"obs_mode": "perceived", "field": "ssl-2012",
      "perception": {"vision": "ssl-2012", "detector": "pixels"}}, "pixels"),
    ({"render_mode": "rgb_array"}, "render"),
])
def test_what_the_batch_does_not_run_is_refused(kwargs, why):
    with pytest.raises(NotBatchable, match=why):
        MatchBatch(2, blue=1, yellow=1, **kwargs)
