"""MatchVecEnv: stable-baselines3's VecEnv contract on the match, training and self-play."""

from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("stable_baselines3")

import torch  # noqa: E402
from stable_baselines3 import PPO  # noqa: E402
from stable_baselines3.common.monitor import Monitor  # noqa: E402
from stable_baselines3.common.utils import check_for_correct_spaces  # noqa: E402
from stable_baselines3.common.vec_env import VecCheckNan, VecMonitor, VecNormalize  # noqa: E402

import soccer_env  # noqa: E402
from agents.policies import NumpyPolicy  # noqa: E402
from agents.sb3.policies import numpy_copy  # noqa: E402
from agents.scripted import ScriptedTeam  # noqa: E402
from agents.vec.factories import make_match_vec_env  # noqa: E402
from agents.vec.match import MatchVecEnv  # noqa: E402
from agents.vec.self_play import SelfPlayCallback  # noqa: E402

#: A short 1 vs 1 match: 30 control steps.
SHORT = {"blue": 1, "yellow": 1, "match_duration": 0.5}


pytestmark = pytest.mark.usefixtures("one_torch_thread")


def zeros(venv):
    return np.zeros((venv.num_envs, 6), dtype=np.float32)


def shadow_matches(kwargs, seed, n):
    """Stand-alone matches reset as MatchVecEnv's after ``seed(seed)``."""
    out = []
    for k in range(n):
        m = soccer_env.parallel_env(**kwargs)
        obs, _ = m.reset(seed=seed + k)
        out.append((m, obs))
    return out


# ----------------------------------------------------------------------------------------
# Spaces and layout
# ----------------------------------------------------------------------------------------


@pytest.mark.parametrize("learner,per_match", [("blue", 2), ("yellow", 3), ("both", 4)])
def test_spaces_shapes_and_batch_layout(learner, per_match):
    kwargs = {"blue": 2, "yellow": 3 if learner == "yellow" else 2, "match_duration": 5.0}
    if learner == "both":
        kwargs["yellow"] = 2
    venv = MatchVecEnv(kwargs, n_matches=3, learner=learner, opponent=None)
    match = soccer_env.parallel_env(**kwargs)
    check_for_correct_spaces(venv, match.observation_space("blue_0"),
                             match.action_space("blue_0"))
    assert venv.num_envs == 3 * per_match
    assert venv.entry_agents[per_match] == (1, venv.learner_agents[0])
    venv.seed(7)
    obs = venv.reset()
    assert isinstance(obs, np.ndarray) and obs.dtype == np.float32
    assert obs.shape == (venv.num_envs, *venv.observation_space.shape)
    assert all(venv.observation_space.contains(o) for o in obs)
    # Entry k * L + j is learner j of match k, reset with seed 7 + k, in its team's frame.
    for k, (_, m_obs) in enumerate(shadow_matches(kwargs, 7, 3)):
        for j, agent in enumerate(venv.learner_agents):
            np.testing.assert_array_equal(obs[k * per_match + j], m_obs[agent])
    obs, rewards, dones, infos = venv.step(zeros(venv))
    assert obs.shape == (venv.num_envs, venv.observation_space.shape[0])
    assert rewards.shape == (venv.num_envs,) and rewards.dtype == np.float32
    assert dones.shape == (venv.num_envs,) and dones.dtype == bool
    assert len(infos) == venv.num_envs
    assert set(infos[0]) == {"score", "event", "TimeLimit.truncated"}
    assert "truth" not in infos[0]  # the match's large info is not forwarded


# ----------------------------------------------------------------------------------------
# VecEnv contract: auto-reset, terminal observation, truncation, episode statistics
# ----------------------------------------------------------------------------------------


def test_terminal_observation_auto_reset_and_episode_info_match_the_real_matches():
    """Stepped side by side with stand-alone matches fed the same actions: every observation
    and reward agrees, the finished match's last observation is the terminal observation,
    and the observation returned with done=True is the next match's first."""
    kwargs = {**SHORT, "shaping": {"ball_distance": 1.0}}
    venv = make_match_vec_env(kwargs, n_matches=2, learner="blue", opponent="idle", seed=11)
    venv.reset()
    shadows = shadow_matches(kwargs, 11, 2)
    last = [None, None]
    rng = np.random.default_rng(0)
    returns = np.zeros(2)
    for step in range(1, 31):
        actions = rng.uniform(-1, 1, (2, 6)).astype(np.float32)
        obs, rewards, dones, infos = venv.step(actions)
        for k, (m, _) in enumerate(shadows):
            m_obs, m_rew, *_ = m.step({"blue_0": actions[k], "yellow_0": np.zeros(6)})
            last[k] = m_obs["blue_0"]
            returns[k] += m_rew["blue_0"]
            assert rewards[k] == np.float32(m_rew["blue_0"])
            assert rewards[k] < 0.0  # the distance shaping is on
            if step < 30:
                assert not dones[k]
                np.testing.assert_array_equal(obs[k], m_obs["blue_0"])
                assert "terminal_observation" not in infos[k]
    assert dones.all()
    for k, (m, _) in enumerate(shadows):
        info = infos[k]
        np.testing.assert_array_equal(info["terminal_observation"], last[k])
        assert not np.array_equal(obs[k], info["terminal_observation"])
        np.testing.assert_array_equal(obs[k], m.reset()[0]["blue_0"])  # auto-reset
        assert info["TimeLimit.truncated"] is False  # the clock ran out: a termination
        assert info["episode"]["l"] == 30
        assert info["episode"]["r"] == pytest.approx(returns[k], rel=1e-5)
        assert info["episode"]["t"] >= 0.0
        assert info["is_success"] is False and info["goals_for"] == 0
    # The next match runs on: no stale done flags or statistics.
    obs, rewards, dones, infos = venv.step(zeros(venv))
    assert not dones.any() and "episode" not in infos[0]


def test_max_cycles_is_a_truncation():
    venv = make_match_vec_env({**SHORT, "match_duration": 100.0, "max_cycles": 10},
                              n_matches=2, learner="both", seed=0)
    venv.reset()
    for _ in range(9):
        _, _, dones, infos = venv.step(zeros(venv))
        assert not dones.any() and not any(i["TimeLimit.truncated"] for i in infos)
    _, _, dones, infos = venv.step(zeros(venv))
    assert dones.all()
    assert all(i["TimeLimit.truncated"] is True for i in infos)
    assert all(i["episode"]["l"] == 10 for i in infos)


def test_goal_rewards_are_zero_sum_and_reported_per_team():
    """'both' with the scripted team's actions fed in: at each goal the scorer's entries get
    +1, the other team's -1, and the final info holds each side's goals and success."""
    kwargs = {"blue": 1, "yellow": 1, "match_duration": 10.0}
    venv = make_match_vec_env(kwargs, n_matches=1, learner="both", seed=3)
    teams = [ScriptedTeam.for_env(venv.matches[0], c) for c in ("blue", "yellow")]
    obs = venv.reset()
    goals = 0
    while True:
        actions = np.concatenate([teams[0].act(obs[:1]), teams[1].act(obs[1:])])
        obs, rewards, dones, infos = venv.step(actions)
        if infos[0]["event"] == "goal":
            goals += 1
            assert abs(rewards[0]) == 1.0 and rewards.sum() == 0.0
            assert rewards[1] == -rewards[0]
        else:
            assert not rewards.any()
        if dones.any():
            break
    blue, yellow = infos[0]["score"]["blue"], infos[0]["score"]["yellow"]
    assert goals == blue + yellow > 0
    assert [i["goals_for"] for i in infos] == [blue, yellow]
    assert [i["goals_against"] for i in infos] == [yellow, blue]
    assert [i["is_success"] for i in infos] == [blue > yellow, yellow > blue]
    assert [i["episode"]["r"] for i in infos] == [blue - yellow, yellow - blue]


def test_step_async_then_step_wait_equals_step():
    a = make_match_vec_env(SHORT, n_matches=2, learner="blue", opponent="scripted", seed=1)
    b = make_match_vec_env(SHORT, n_matches=2, learner="blue", opponent="scripted", seed=1)
    np.testing.assert_array_equal(a.reset(), b.reset())
    act = np.full((2, 6), 0.3, dtype=np.float32)
    a.step_async(act)
    oa, ra, da, _ = a.step_wait()
    ob, rb, db, _ = b.step(act)
    np.testing.assert_array_equal(oa, ob)
    np.testing.assert_array_equal(ra, rb)


# ----------------------------------------------------------------------------------------
# Seeding
# ----------------------------------------------------------------------------------------


def run(venv, steps, seed=0):
    rng = np.random.default_rng(seed)
    out = [venv.reset()]
    for _ in range(steps):
        obs, rew, done, _ = venv.step(rng.uniform(-1, 1, (venv.num_envs, 6)))
        out += [obs, rew[:, None], done[:, None].astype(np.float32)]
    return np.concatenate(out, axis=1)


def test_same_seed_same_matches_other_seed_other_matches():
    kwargs = {"blue": 2, "yellow": 2, "match_duration": 1.0, "obs_mode": "perceived"}
    a = make_match_vec_env(kwargs, n_matches=2, learner="blue", seed=5)
    b = make_match_vec_env(kwargs, n_matches=2, learner="blue", seed=5)
    ra, rb = run(a, 80), run(b, 80)  # through an auto-reset
    np.testing.assert_array_equal(ra, rb)
    a.seed(5)
    np.testing.assert_array_equal(run(a, 80), ra)  # seed() again, then reset()
    b.seed(6)
    assert not np.array_equal(run(b, 80), ra)
    assert a.seed(9) == [9, 9, 10, 10]  # each entry gets its match's seed


# ----------------------------------------------------------------------------------------
# Wrappers and VecEnv methods
# ----------------------------------------------------------------------------------------


def test_vec_check_nan_vec_monitor_and_vec_normalize_on_top():
    venv = make_match_vec_env(SHORT, n_matches=2, learner="both", seed=0)
    wrapped = VecNormalize(VecMonitor(VecCheckNan(venv, raise_exception=True)), gamma=0.9)
    obs = wrapped.reset()
    assert obs.shape == (4, venv.observation_space.shape[0])
    episodes = []
    for _ in range(35):
        obs, rewards, dones, infos = wrapped.step(np.full((4, 6), 0.5, np.float32))
        assert np.isfinite(obs).all() and np.isfinite(rewards).all()
        if dones.any():
            episodes = [i["episode"] for i in infos]
            terminal = [i["terminal_observation"] for i in infos]
            assert all(np.abs(t).max() <= wrapped.clip_obs for t in terminal)
    assert [e["l"] for e in episodes] == [30] * 4
    # VecCheckNan catches a NaN action before the match sees it.
    bad = np.zeros((4, 6), np.float32)
    bad[1, 0] = np.nan
    with pytest.raises(ValueError, match="nan"):
        wrapped.step(bad)


def test_get_set_attr_env_method_env_is_wrapped_and_images():
    venv = make_match_vec_env({**SHORT, "render_mode": "rgb_array", "render_width": 160},
                              n_matches=2, learner="both", seed=0)
    venv.reset()
    assert venv.get_attr("render_mode") == ["rgb_array"] * 4
    assert venv.get_attr("score", indices=[3]) == [[0, 0]]
    venv.set_attr("formation_jitter", 0.0, indices=[2, 3])
    assert [m.formation_jitter for m in venv.matches] == [0.1, 0.0]
    states = venv.env_method("state", indices=[0, 1, 2])
    assert len(states) == 3 and states[0] is states[1]  # one call per match
    np.testing.assert_array_equal(states[2], venv.matches[1].state())
    assert venv.env_is_wrapped(Monitor) == [False] * 4
    assert venv.has_attr("world") and not venv.has_attr("no_such_attribute")
    images = venv.get_images()
    assert len(images) == 2 and images[0].ndim == 3 and images[0].shape[2] == 3
    tiled = venv.render(mode="rgb_array")
    assert tiled.ndim == 3 and tiled.shape[2] == 3
    with pytest.raises(IndexError, match="batch entry 4 out of range"):
        venv.get_attr("score", indices=[4])
    venv.close()


# ----------------------------------------------------------------------------------------
# Opponents
# ----------------------------------------------------------------------------------------


def test_a_team_without_opponents_needs_no_opponent():
    venv = make_match_vec_env({"blue": 2, "yellow": 0, "match_duration": 0.2}, n_matches=2,
                              learner="blue", seed=0)
    assert venv.opponents == [None, None] and venv.num_envs == 4
    venv.reset()
    for _ in range(12):
        _, _, dones, _ = venv.step(zeros(venv))
    assert dones.all()


def test_callable_opponent_sees_each_match_team_in_its_own_frame():
    calls = []

    def opponent(obs):
        calls.append(obs.copy())
        return np.tile([1.0, 0.0, 0.0, 0.0, 0.0, 0.0], (len(obs), 1))  # drive forward

    kwargs = {"blue": 1, "yellow": 2, "match_duration": 5.0, "formation_jitter": 0.0}
    venv = make_match_vec_env(kwargs, n_matches=3, learner="blue", opponent=opponent, seed=2)
    obs = venv.reset()
    before = [m.state()[6:].reshape(-1, 6)[1:, 0].copy() for m in venv.matches]
    for _ in range(30):
        venv.step(zeros(venv))
    assert len(calls) == 30 * 3 and all(c.shape == (2, obs.shape[1]) for c in calls)
    for k, m in enumerate(venv.matches):
        after = m.state()[6:].reshape(-1, 6)[1:, 0]
        assert np.all(after < before[k] - 0.3)  # yellow's forward is the field's -x


def test_opponent_policies_play_their_part():
    """A scripted opponent beats the idle learner; an idle one never scores."""
    kwargs = {"blue": 1, "yellow": 1, "match_duration": 15.0}
    for opponent, conceded in (("scripted", True), ("idle", False)):
        venv = make_match_vec_env(kwargs, n_matches=1, learner="blue", opponent=opponent,
                                  seed=0)
        venv.reset()
        while True:
            _, _, dones, infos = venv.step(zeros(venv))
            if dones[0]:
                break
        assert (infos[0]["goals_against"] > 0) == conceded


def test_sb3_model_opponent_is_a_frozen_numpy_copy():
    venv = make_match_vec_env(SHORT, n_matches=2, learner="blue", opponent="idle", seed=0)
    model = PPO("MlpPolicy", venv, n_steps=32, batch_size=64, n_epochs=1, seed=0)
    venv.set_opponent(model)
    copy = venv.opponents[0]
    assert isinstance(copy, NumpyPolicy) and venv.opponents[1] is copy
    obs = venv.reset()
    expected = model.predict(obs, deterministic=True)[0]
    np.testing.assert_allclose(copy(obs), expected, atol=1e-5)
    model.learn(64)
    assert venv.opponents[0] is copy  # learning replaces neither the copy...
    np.testing.assert_allclose(copy(obs), expected, atol=1e-5)  # ...nor its weights
    assert not np.allclose(copy(obs), model.predict(obs, deterministic=True)[0])


# ----------------------------------------------------------------------------------------
# Training and self-play
# ----------------------------------------------------------------------------------------


@pytest.mark.parametrize("opponent", ["scripted", "idle"])
def test_ppo_learns_against_a_fixed_opponent(opponent):
    venv = make_match_vec_env({"blue": 2, "yellow": 2, "match_duration": 1.0}, n_matches=2,
                              learner="blue", opponent=opponent, seed=0)
    model = PPO("MlpPolicy", venv, n_steps=64, batch_size=64, n_epochs=1, seed=0)
    before = [p.detach().clone() for p in model.policy.parameters()]
    model.learn(256)
    assert model.num_timesteps >= 256
    assert any(not torch.equal(a, b) for a, b in zip(before, model.policy.parameters()))
    # The logger's episode statistics come from our infos (no VecMonitor here).
    assert len(model.ep_info_buffer) >= 4
    assert all(e["l"] == 60 for e in model.ep_info_buffer)
    assert len(model.ep_success_buffer) >= 4


def test_self_play_with_both_teams_learning():
    venv = make_match_vec_env({"blue": 2, "yellow": 2, "match_duration": 1.0}, n_matches=2,
                              learner="both", seed=0)
    assert venv.num_envs == 8 and venv.opponents == [None, None]
    model = PPO("MlpPolicy", venv, n_steps=64, batch_size=128, n_epochs=1, seed=0)
    model.learn(1024)
    assert model.num_timesteps >= 1024
    # Both teams are learners: the two sides' episode returns cancel out (no shaping).
    rs = [e["r"] for e in model.ep_info_buffer]
    assert len(rs) >= 8 and sum(rs) == 0.0


@pytest.mark.parametrize("pool_size", [1, 3])
def test_self_play_callback_copies_the_learner_into_the_opponent(pool_size):
    venv = make_match_vec_env(SHORT, n_matches=2, learner="blue", opponent="idle", seed=0)
    model = PPO("MlpPolicy", venv, n_steps=32, batch_size=64, n_epochs=1, seed=0)
    callback = SelfPlayCallback(update_every=64, pool_size=pool_size)
    initial = numpy_copy(model)
    model.learn(320, callback=callback)
    assert callback.n_updates >= 5  # at the start, then every 64 timesteps
    pool = list(callback.pool)
    assert len(pool) == min(pool_size, callback.n_updates)

    def differ(p, q):
        return any(not np.array_equal(a[1], b[1]) for a, b in zip(p.layers, q.layers)
                   if a[0] == "linear")

    # The opponent's weights changed with the learner's, and each copy stayed as it was.
    last = pool[-1]
    assert differ(initial, last)
    if pool_size > 1:
        assert differ(pool[0], pool[-1])
    obs = venv.reset()
    if pool_size == 1:
        assert venv.opponents == [last, last]
    else:
        assert venv.opponent_pool == pool
        assert all(any(o is p for p in pool) for o in venv.opponents)
    for opp in venv.opponents:
        assert opp(obs).shape == (2, 6)


def test_self_play_callback_carries_frozen_vec_normalize_statistics():
    venv = make_match_vec_env(SHORT, n_matches=2, learner="blue", opponent="idle", seed=0)
    norm = VecNormalize(venv)
    model = PPO("MlpPolicy", norm, n_steps=32, batch_size=64, n_epochs=1, seed=0)
    model.learn(64, callback=SelfPlayCallback(update_every=32))
    opp = venv.opponents[0]
    obs = venv.reset()
    out = opp(obs)
    raw = numpy_copy(model)
    assert not np.allclose(out, raw(obs))  # it normalises before the network
    norm.obs_rms.mean += 1.0  # later statistics do not leak into the copy
    np.testing.assert_array_equal(opp(obs), out)


# ----------------------------------------------------------------------------------------
# Bad input
# ----------------------------------------------------------------------------------------


def test_bad_arguments_raise_value_errors_naming_what_is_allowed():
    with pytest.raises(ValueError, match=r"learner must be one of \['blue', 'yellow', 'both'\], "
                                         r"got 'red'"):
        MatchVecEnv(SHORT, learner="red")
    with pytest.raises(ValueError, match=r"opponent must be 'scripted', 'idle', a numpy policy"):
        MatchVecEnv(SHORT, opponent="champion")
    with pytest.raises(ValueError, match=r"opponent must be 'scripted', 'idle'.*got int"):
        MatchVecEnv(SHORT, opponent=42)
    with pytest.raises(ValueError, match="n_matches must be an integer >= 1"):
        MatchVecEnv(SHORT, n_matches=0)
    with pytest.raises(ValueError, match="equal size"):
        MatchVecEnv({"blue": 2, "yellow": 1}, learner="both")
    with pytest.raises(ValueError, match="opponent must be None with learner='both'"):
        MatchVecEnv(SHORT, learner="both", opponent="idle")
    with pytest.raises(ValueError, match="the yellow team has no robots"):
        MatchVecEnv({"blue": 2, "yellow": 0}, learner="yellow")
    with pytest.raises(TypeError, match="unknown keyword"):
        MatchVecEnv({**SHORT, "colour": "red"})
    small = NumpyPolicy([("linear", np.zeros((6, 3)), np.zeros(6))], "clip", -np.ones(6),
                        np.ones(6))
    with pytest.raises(ValueError, match="observations of size 3"):
        MatchVecEnv(SHORT, opponent=small)
    size = MatchVecEnv(SHORT).observation_space.shape[0]
    stacked = NumpyPolicy([("linear", np.zeros((6, 2 * size)), np.zeros(6))], "clip",
                          -np.ones(6), np.ones(6), frame_stack=2)
    with pytest.raises(ValueError, match="opponent policies with memory"):
        MatchVecEnv(SHORT, opponent=stacked)
    with pytest.raises(ValueError, match="update_every must be an integer >= 1"):
        SelfPlayCallback(update_every=0)


def test_recurrent_models_learn_on_matches_but_cannot_be_opponents():
    """RecurrentPPO trains on a MatchVecEnv (each robot its own LSTM state); as an
    opponent it would never have its memory reset, so it is refused."""
    contrib = pytest.importorskip("sb3_contrib")
    venv = make_match_vec_env(SHORT, n_matches=2, learner="blue", opponent="idle", seed=0)
    model = contrib.RecurrentPPO("MlpLstmPolicy", venv, n_steps=32, batch_size=64, seed=0,
                                 device="cpu", policy_kwargs={"lstm_hidden_size": 8})
    model.learn(64)
    assert model.num_timesteps == 64
    with pytest.raises(ValueError, match="opponent policies with memory"):
        venv.set_opponent(model)


def test_bad_steps_raise_clear_errors():
    venv = make_match_vec_env(SHORT, n_matches=2, learner="blue", opponent="idle", seed=0)
    with pytest.raises(RuntimeError, match=r"call reset\(\) before"):
        venv.step(zeros(venv))
    venv.reset()
    with pytest.raises(ValueError, match=r"actions must have shape \(2, 6\).*got \(2, 5\)"):
        venv.step(np.zeros((2, 5)))
    with pytest.raises(ValueError, match=r"actions must have shape \(2, 6\).*got \(6,\)"):
        venv.step(np.zeros(6))
    nan = zeros(venv)
    nan[1, 2] = np.nan
    before = [m.state() for m in venv.matches]
    with pytest.raises(ValueError, match=r"blue_0 of match 1 \(batch entry 1\).*non-finite"):
        venv.step(nan)
    for m, state in zip(venv.matches, before):  # no match moved
        np.testing.assert_array_equal(m.state(), state)
    strict = make_match_vec_env({**SHORT, "out_of_range_actions": "raise"}, n_matches=2,
                                opponent="idle")
    strict.reset()
    with pytest.raises(ValueError, match="outside the allowed range"):
        strict.step(np.full((2, 6), 1.5))
    venv.set_opponent(lambda obs: np.zeros((len(obs), 5)))
    with pytest.raises(ValueError, match=r"returned actions of shape \(1, 5\)"):
        venv.step(zeros(venv))
    both = make_match_vec_env(SHORT, learner="both")
    with pytest.raises(ValueError, match="learner='both' has no opponent"):
        both.set_opponent("idle")
    model = PPO("MlpPolicy", both, n_steps=16, batch_size=16, n_epochs=1)
    with pytest.raises(ValueError, match="SelfPlayCallback needs learner='blue' or 'yellow'"):
        model.learn(16, callback=SelfPlayCallback(update_every=8))
