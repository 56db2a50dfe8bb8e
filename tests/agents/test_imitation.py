"""DAgger with a privileged teacher: the teacher's labels against known truth, the frame
stack the numpy policy reads, a tiny run's folder, determinism and bad configurations."""

from __future__ import annotations

import json
import math

import gymnasium as gym
import numpy as np
import pytest

import soccer_env  # noqa: F401
from agents.policies import NumpyPolicy
from agents.policies.action_maps import action_to_command, ball_residual_params
from agents.runs.imitation import ImitationConfig, imitate, stack_history, teacher_action
from soccer_env.envs.registration import GOALKEEPER_ID

#: A humanoid keeper on its own head camera and the kick tracker: cheap and perceived.
KW = {"robot": "humanoid-2012", "obs_mode": "perceived", "belief_features": True,
      "perception": {"camera": "kidsize-2012", "ball_tracker": "kick"}}


def _obs(heading: float, body_velocity: tuple[float, float]) -> np.ndarray:
    """An observation of the Goalkeeper's layout with the pose's heading axis and the
    ball's body-frame velocity set (the rest zero)."""
    obs = np.zeros(32, np.float32)
    obs[2], obs[3] = math.cos(heading), -math.sin(heading)
    obs[9], obs[10] = body_velocity
    return obs


def test_teacher_action_is_the_scaled_team_frame_velocity_error():
    # Heading +90 degrees: a ball moving along the body's +x moves along the team's +y.
    obs = _obs(math.pi / 2, (1.0, 0.0))
    np.testing.assert_allclose(teacher_action(obs, (0.0, 1.0)), [0.0, 0.0], atol=1e-6)
    np.testing.assert_allclose(teacher_action(obs, (-1.5, 1.0), residual=3.0), [-0.5, 0.0],
                               atol=1e-6)
    # Beyond the largest correction: clipped into [-1, 1].
    np.testing.assert_allclose(teacher_action(obs, (9.0, -9.0)), [1.0, -1.0])


def test_the_teacher_action_gives_the_keeper_the_true_velocity():
    env = gym.make(GOALKEEPER_ID, **KW)
    params = ball_residual_params(env)
    obs_true = _obs(0.4, (0.0, 0.0))
    obs_true[7:9] = (1.5, 0.3)
    c, s = math.cos(0.4), math.sin(0.4)
    true_v = np.array([-2.0, 0.5])
    obs_true[9], obs_true[10] = c * true_v[0] + s * true_v[1], -s * true_v[0] + c * true_v[1]
    believed = obs_true.copy()
    believed[9:11] = (0.0, 0.0)  # the belief has not seen the kick
    a = teacher_action(believed, true_v, params["residual"])
    np.testing.assert_allclose(action_to_command("ball-residual", believed, a, params),
                               action_to_command("ball-residual", obs_true, np.zeros(2),
                                                 params), atol=1e-5)


def test_stack_history_matches_the_numpy_policy_stack():
    rng = np.random.default_rng(0)
    obs = rng.normal(size=(5, 3)).astype(np.float32)
    x = stack_history(obs, 3)
    assert x.shape == (5, 9)
    np.testing.assert_array_equal(x[0], np.concatenate([obs[0]] * 3))
    np.testing.assert_array_equal(x[4], obs[2:5].ravel())
    layers = [("linear", np.eye(9, dtype=np.float32), np.zeros(9, np.float32))]
    policy = NumpyPolicy(layers, "clip", -np.full(9, 1e6), np.full(9, 1e6), frame_stack=3)
    for t in range(5):
        np.testing.assert_allclose(policy(obs[t]), x[t], rtol=1e-5)


def test_bad_configurations_are_refused():
    with pytest.raises(ValueError, match="obs_mode='truth'"):
        ImitationConfig(env_kwargs={"robot": "humanoid-2012"})
    with pytest.raises(ValueError, match="info_mode must be 'full'"):
        ImitationConfig(env_kwargs={**KW, "info_mode": "flat"})
    for name, value in (("rounds", 0), ("episodes", 1.5), ("frame_stack", True),
                        ("eval_episodes", -1), ("workers", 0)):
        with pytest.raises(ValueError, match=f"{name} must be an integer >= "):
            ImitationConfig(env_kwargs=KW, **{name: value})
    with pytest.raises(ValueError, match="hidden must be one or more integers"):
        ImitationConfig(env_kwargs=KW, hidden=(8, 0))
    with pytest.raises(ValueError, match="learning_rate must be a finite number > 0"):
        ImitationConfig(env_kwargs=KW, learning_rate=float("nan"))


def test_a_tiny_run_writes_a_policy_the_evaluation_reads(tmp_path, one_torch_thread):
    from agents.runs.evaluation import evaluate

    cfg = ImitationConfig(env_kwargs=KW, rounds=2, episodes=3, frame_stack=2, hidden=(8,),
                          epochs=2, eval_episodes=2, workers=1)
    summary = imitate(cfg, tmp_path / "run", command=["soccer-env", "imitate"])
    run = tmp_path / "run"
    assert {p.name for p in run.iterdir()} >= {"config.json", "round_0_policy.npz",
                                               "round_1_policy.npz", "final_policy.npz",
                                               "evaluations.json", "summary.json"}
    rows = json.loads((run / "evaluations.json").read_text())
    assert [r["round"] for r in rows] == [0, 1]
    assert rows[1]["samples"] > rows[0]["samples"] > 0 and summary["steps"] == rows[1]["steps"]
    policy = NumpyPolicy.load(run / "final_policy.npz")
    assert policy.frame_stack == 2 and policy.action_map["kind"] == "ball-residual"
    assert policy.meta["algorithm"] == "DAgger"
    assert policy.meta["command"] == "soccer-env imitate"
    assert evaluate(run, KW, episodes=2, start_seed=rows[0]["round"]).episodes == 2
    # Same configuration, same network; another folder refuses nothing, the same refuses.
    imitate(cfg, tmp_path / "again")
    again = NumpyPolicy.load(tmp_path / "again" / "final_policy.npz")
    for a, b in zip(policy.layers, again.layers):
        for u, v in zip(a[1:], b[1:]):
            np.testing.assert_array_equal(u, v)
    with pytest.raises(FileExistsError, match="already holds a run"):
        imitate(cfg, run)
