"""The shipped baselines: they load with one call, act on the plain environment, match the
stable-baselines3 models they were copied from, and evaluate reproducibly."""

from __future__ import annotations

import numpy as np
import pytest

from agents.baselines import (
    BASELINES,
    NUMPY_ONLY,
    baseline_env_kwargs,
    baseline_path,
    load_baseline,
    make_baseline_env,
)
from agents.policies.action_maps import ACTION_MAPS
from agents.runs.evaluation import evaluate


@pytest.mark.parametrize("name", sorted(BASELINES))
def test_baseline_loads_with_one_call_and_acts_on_the_plain_env(name):
    keeper = load_baseline(name)
    assert baseline_path(name).stat().st_size < 300_000  # small enough to ship
    algorithm, command = (("DAgger", "soccer-env imitate") if name in NUMPY_ONLY else
                          ("PPO", "soccer-env train"))
    assert keeper.meta["algorithm"] == algorithm
    assert keeper.meta["command"].startswith(command)
    assert keeper.action_map["kind"] in ACTION_MAPS
    assert keeper.normalize is not None
    kwargs = baseline_env_kwargs(name)
    assert "shaping" not in kwargs
    expected = ({"camera": "kidsize-2012", "ball_tracker": "kick"} if name in NUMPY_ONLY else
                "realistic" if name.endswith("realistic") else "ssl-2012")
    assert kwargs["perception"] == expected
    env = make_baseline_env(name)
    obs, _ = env.reset(seed=0)
    action = keeper(obs)
    assert action.shape == (6,) and action.dtype == np.float32
    assert np.all(np.abs(action) <= np.sqrt(2) + 1e-6)
    batch = np.stack([env.reset(seed=s)[0] for s in range(4)])
    keeper.reset()  # a frame-stacked keeper starts each episode afresh
    first = keeper(batch)[2]
    keeper.reset()
    np.testing.assert_allclose(first, keeper(batch[2]), atol=1e-6)


@pytest.mark.parametrize("name", sorted(set(BASELINES) - NUMPY_ONLY))
def test_shipped_model_is_the_numpy_policy(name):
    """The stable-baselines3 model behind the numpy copy, with its normalisation statistics
    and the action map, gives the same commands."""
    pytest.importorskip("stable_baselines3")
    from agents.policies.action_maps import action_to_command
    from agents.runs.resolve import learner_spaces, load_sb3
    from agents.sb3.model_files import serialized_entries
    from agents.sb3.normalization import read_vecnormalize

    keeper = load_baseline(name)
    env = make_baseline_env(name)
    # Loaded without unpickling: the spaces are the environment's behind the action map.
    assert "observation_space" in serialized_entries(baseline_path(name, "zip"))
    obs_space, act_space = learner_spaces(env, {"action_map": keeper.action_map})
    model = load_sb3(baseline_path(name, "zip"), "PPO", observation_space=obs_space,
                     action_space=act_space)
    norm = read_vecnormalize(baseline_path(name, "stats"))
    obs = np.stack([env.reset(seed=s)[0] for s in range(8)])
    act, _ = model.predict(norm.normalize_obs(obs), deterministic=True)
    np.testing.assert_allclose(keeper.network_action(obs), act, atol=1e-5)
    expected = action_to_command(keeper.action_map["kind"], obs, act,
                                 keeper.action_map["params"])
    # The braking profile's square root amplifies float32 rounding near the target.
    np.testing.assert_allclose(keeper(obs), expected, atol=1e-3)


def test_baseline_evaluation_is_deterministic():
    name = "keeper-ppo-ssl2012"
    kwargs = baseline_env_kwargs(name)
    first = evaluate(f"baseline:{name}", kwargs, episodes=6, workers=1)
    second = evaluate(f"baseline:{name}", kwargs, episodes=6, workers=1)
    assert first.saved == second.saved and first.steps == second.steps


def test_unknown_baseline_names_what_is_shipped():
    with pytest.raises(ValueError, match="keeper-ppo-ssl2012"):
        load_baseline("keeper-dqn")
    with pytest.raises(ValueError, match="kind must be"):
        baseline_path("keeper-ppo-ssl2012", "onnx")
    for name in NUMPY_ONLY:
        with pytest.raises(ValueError, match="ships as a numpy policy only"):
            baseline_path(name, "zip")


def test_the_shipped_team_plays_a_match_from_its_own_files():
    import soccer_env
    from agents.baselines import SSL_TEAM_2V2, SSL_TEAM_CHECKPOINTS, load_team
    from agents.studies.matches import team_policy

    team = load_team()
    assert SSL_TEAM_2V2.stat().st_size < 200_000
    assert team.action_map["kind"] == "team-residual" and team.normalize is not None
    meta = team.meta
    assert meta["command"].startswith("python examples/train_ssl_team.py")
    assert meta["steps"] > 0 and meta["minutes"] > 0
    copies = sorted(SSL_TEAM_CHECKPOINTS.glob("team_*.npz"))
    assert copies and all(p.stat().st_size < 200_000 for p in copies)
    env = soccer_env.parallel_env(**{**meta["eval_kwargs"], "match_duration": 1.0})
    obs, _ = env.reset(seed=0)
    play = team_policy(str(SSL_TEAM_2V2), env, "yellow")
    steps = 0
    while env.agents:
        actions = play(obs)
        assert sorted(actions) == ["yellow_0", "yellow_1"]
        assert all(a.shape == (6,) and np.all(np.abs(a) <= 1.0) for a in actions.values())
        actions.update({a: np.zeros(6, np.float32) for a in ("blue_0", "blue_1")})
        obs, *_ = env.step(actions)
        steps += 1
    assert steps == 30
    env.close()
