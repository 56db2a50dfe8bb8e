"""Learner action spaces: the field-frame velocity and target maps, as wrappers and as the
function numpy policies apply; stacked observations, in the environment and in the numpy
policy."""

from __future__ import annotations

import math

import gymnasium as gym
import numpy as np
import pytest

import soccer_env  # noqa: F401
from agents.policies import NumpyPolicy
from agents.policies.action_maps import ACTION_MAPS, action_to_command, target_params
from agents.policies.wrappers import (
    FieldVelocityActions,
    TargetActions,
    stack_frames,
    wrap_actions,
)
from soccer_env.envs.keeper import drive_command

ID = "soccer_env/Goalkeeper-v0"


def _obs_with_heading(theta: float, x: float = -4.0, y: float = 0.2) -> np.ndarray:
    obs = np.zeros(19, np.float32)
    obs[0], obs[1] = x, y
    obs[2], obs[3] = math.cos(theta), -math.sin(theta)  # the observation's convention
    return obs


@pytest.mark.parametrize("theta", [0.0, 0.7, -2.0, math.pi])
def test_velocity_map_rotates_the_field_frame_command_into_the_body(theta):
    cmd = action_to_command("velocity", _obs_with_heading(theta), np.array([0.6, -0.3, 0.2]))
    # Rotating the body-frame command back by the heading gives the field-frame one.
    c, s = math.cos(theta), math.sin(theta)
    assert c * cmd[0] - s * cmd[1] == pytest.approx(0.6, abs=1e-6)
    assert s * cmd[0] + c * cmd[1] == pytest.approx(-0.3, abs=1e-6)
    assert cmd[2] == pytest.approx(0.2)
    assert list(cmd[3:]) == [0.0, -1.0, -1.0]  # kicker off


def test_target_map_is_the_braking_profile_controller():
    env = gym.make(ID)
    params = target_params(env)
    theta = 0.4
    obs = _obs_with_heading(theta, x=-4.3, y=-0.1)
    action = np.array([-0.5, 0.8])
    cmd = action_to_command("target", obs, action, params)
    tx = params["x_min"] + 0.25 * (params["x_max"] - params["x_min"])
    ty = 0.8 * params["y_max"]
    vx, vy = drive_command(-4.3, -0.1, math.cos(theta), math.sin(theta), tx, ty,
                           params["max_speed"], params["max_acceleration"])
    assert cmd[0] * params["max_speed"] == pytest.approx(vx, abs=1e-5)
    assert cmd[1] * params["max_speed"] == pytest.approx(vy, abs=1e-5)
    assert cmd[2] < 0  # turns back towards heading 0
    # The target box: in front of the goal line, covering the goal mouth.
    u = env.unwrapped
    assert params["x_min"] > -u.field.half_length
    assert params["y_max"] >= 0.5 * u.field.goal_width


def test_guard_map_is_the_target_map_on_the_guard_line():
    env = gym.make(ID)
    params = target_params(env)
    obs = _obs_with_heading(0.3, x=-4.2, y=0.1)
    for y in (-1.0, -0.2, 0.7):
        np.testing.assert_allclose(action_to_command("guard", obs, np.array([y]), params),
                                   action_to_command("target", obs, np.array([-1.0, y]), params))
    # The guard line is the scripted keeper's.
    from agents import ScriptedGoalkeeper

    assert params["x_min"] == pytest.approx(ScriptedGoalkeeper.for_env(env).guard_x)


def test_target_keeper_reaches_its_target_and_stops():
    env = TargetActions(gym.make(ID, shots={"delay": (10.0, 10.0)}))
    obs, _ = env.reset(seed=3)
    for _ in range(120):  # 2 s
        obs, *_ = env.step(np.array([0.0, 1.0], np.float32))
    p = env.params
    assert obs[0] == pytest.approx(0.5 * (p["x_min"] + p["x_max"]), abs=0.02)
    assert obs[1] == pytest.approx(p["y_max"], abs=0.02)
    assert math.hypot(obs[4], obs[5]) < 0.05  # stopped there
    assert abs(obs[6]) < 0.1  # not spinning


def test_batches_match_single_calls():
    rng = np.random.default_rng(0)
    obs = rng.normal(0, 1, (8, 19)).astype(np.float32)
    env = gym.make(ID)
    params = target_params(env)
    for kind in ("velocity", "target", "guard"):
        act = rng.uniform(-1, 1, (8, ACTION_MAPS[kind]))
        batch = action_to_command(kind, obs, act, params)
        for i in range(8):
            np.testing.assert_allclose(batch[i], action_to_command(kind, obs[i], act[i], params),
                                       atol=1e-6)


@pytest.mark.parametrize("kind", ["velocity", "target", "guard"])
def test_wrapped_env_passes_check_env_and_is_deterministic(kind):
    from gymnasium.utils.env_checker import check_env

    env = wrap_actions(gym.make(ID), kind)
    assert env.action_space.shape == (ACTION_MAPS[kind],)
    check_env(env.unwrapped)  # the wrapper's own contract is checked below
    runs = []
    for _ in range(2):
        obs, _ = env.reset(seed=11)
        rng = np.random.default_rng(1)
        trace = [obs]
        for _ in range(40):
            obs, *_ = env.step(rng.uniform(-1, 1, ACTION_MAPS[kind]).astype(np.float32))
            trace.append(obs)
        runs.append(np.array(trace))
    np.testing.assert_array_equal(runs[0], runs[1])


def test_numpy_policy_with_a_map_acts_on_the_plain_env(tmp_path):
    """A policy trained through a wrapper, saved and loaded, gives the wrapper's commands."""
    env = gym.make(ID)
    params = target_params(env)
    rng = np.random.default_rng(2)
    layers = [("linear", rng.normal(0, 0.3, (2, 19)), rng.normal(0, 0.1, 2))]
    policy = NumpyPolicy(layers, "clip", -np.ones(2), np.ones(2),
                         action_map={"kind": "target", "params": params})
    loaded = NumpyPolicy.load(policy.save(tmp_path / "t.npz"))
    obs, _ = env.reset(seed=0)
    expected = action_to_command("target", obs, np.clip(layers[0][1] @ obs + layers[0][2],
                                                        -1, 1), params)
    np.testing.assert_allclose(loaded(obs), expected, atol=1e-5)
    assert loaded(obs).shape == (6,)
    with pytest.raises(ValueError, match="outputs"):
        NumpyPolicy(layers, "clip", -np.ones(2), np.ones(2), action_map={"kind": "velocity"})


def test_bad_input():
    env = gym.make(ID)
    with pytest.raises(ValueError, match="kind"):
        action_to_command("wheels", np.zeros(19), np.zeros(3))
    with pytest.raises(ValueError, match="shape"):
        action_to_command("velocity", np.zeros(19), np.zeros(2))
    with pytest.raises(ValueError, match="params"):
        action_to_command("target", np.zeros(19), np.zeros(2))
    with pytest.raises(ValueError, match="actions must be one of"):
        wrap_actions(env, "wheels")
    with pytest.raises(ValueError, match="depth"):
        TargetActions(env, depth=-1.0)
    wrapped = FieldVelocityActions(env)
    with pytest.raises(RuntimeError, match="reset"):
        wrapped.step(np.zeros(3, np.float32))
    wrapped.reset(seed=0)
    with pytest.raises(ValueError, match="shape"):
        wrapped.step(np.zeros(6, np.float32))
    with pytest.raises(ValueError, match="finite"):
        wrapped.step(np.array([np.nan, 0, 0], np.float32))


@pytest.mark.parametrize("n", [2, 4])
def test_stacked_observation_is_the_last_n_plain_ones(n):
    """Oldest first, the episode's first observation repeated to fill; a reset starts over."""
    plain, stacked = gym.make(ID, obs_mode="perceived"), stack_frames(
        gym.make(ID, obs_mode="perceived"), n)
    assert stacked.observation_space.shape == (19 * n,)
    assert stacked.observation_space.dtype == np.float32
    rng = np.random.default_rng(0)
    for seed in (3, 4):  # the second episode must not see the first one's observations
        history = [plain.reset(seed=seed)[0]]
        obs, _ = stacked.reset(seed=seed)
        for step in range(12):
            window = ([history[0]] * n + history)[-n:]
            np.testing.assert_array_equal(obs, np.concatenate(window), err_msg=f"step {step}")
            assert stacked.observation_space.contains(obs)
            action = rng.uniform(-1, 1, 6).astype(np.float32)
            history.append(plain.step(action)[0])
            obs, *_ = stacked.step(action)
    assert stack_frames(plain, 1) is plain


def test_frame_stack_outside_an_action_map():
    """The map reads the pose from the plain observation under the stack: the stacked,
    mapped environment steps as the mapped one does."""
    mapped = wrap_actions(gym.make(ID), "guard")
    both = stack_frames(wrap_actions(gym.make(ID), "guard"), 3)
    obs_m, _ = mapped.reset(seed=5)
    obs_b, _ = both.reset(seed=5)
    for a in (0.5, -0.8, 0.1, 1.0):
        action = np.array([a], np.float32)
        obs_m, *_ = mapped.step(action)
        obs_b, *_ = both.step(action)
        np.testing.assert_array_equal(obs_b[-19:], obs_m)
    with pytest.raises(ValueError, match="n must be an integer >= 1"):
        stack_frames(mapped, 0)


def test_numpy_policy_keeps_the_stack_itself(tmp_path):
    """A frame-stacked NumpyPolicy called with single observations gives what its network
    gives on the stacked ones, round-trips with its stack size, and restarts at reset()."""
    n = 3
    rng = np.random.default_rng(7)
    layers = [("linear", rng.normal(0, 0.3, (8, 19 * n)), rng.normal(0, 0.1, 8)), ("tanh",),
              ("linear", rng.normal(0, 0.3, (6, 8)), rng.normal(0, 0.1, 6))]
    policy = NumpyPolicy.load(NumpyPolicy(layers, "clip", -np.ones(6), np.ones(6),
                                          frame_stack=n).save(tmp_path / "s.npz"))
    assert policy.frame_stack == n and policy.obs_size == 19 and policy.stateful
    plain, stacked = gym.make(ID), stack_frames(gym.make(ID), n)
    for seed in (0, 1):
        obs, _ = plain.reset(seed=seed)
        sobs, _ = stacked.reset(seed=seed)
        policy.reset()
        for _ in range(10):
            action = policy(obs)
            np.testing.assert_allclose(action, policy.network_action(sobs), atol=1e-6)
            obs, *_ = plain.step(action)
            sobs, *_ = stacked.step(action)
    with pytest.raises(ValueError, match="reset"):
        policy(np.zeros((2, 19), np.float32))  # another batch shape mid-episode
    policy.reset()
    assert policy(np.zeros((2, 19), np.float32)).shape == (2, 6)
    with pytest.raises(ValueError, match="multiple of frame_stack"):
        NumpyPolicy(layers, "clip", -np.ones(6), np.ones(6), frame_stack=2)


def test_guard_residual_starts_from_the_scripted_keeper():
    """The ``guard-residual`` map's target with a zero action is the scripted keeper's point
    on the guard line (computed from the same perceived observation), and a full action moves
    it by the residual."""
    import gymnasium as gym

    from agents.policies.action_maps import RESIDUAL, residual_params, scripted_guard_y
    from soccer_env.envs.keeper import ScriptedGoalkeeper

    env = wrap_actions(gym.make("soccer_env/Goalkeeper-v0", obs_mode="perceived",
                                perception="ssl-2012"), "guard-residual")
    keeper = ScriptedGoalkeeper.for_env(env)
    params = residual_params(env)
    assert params["residual"] == RESIDUAL
    observations = []
    for seed in range(5):
        obs, _ = env.reset(seed=seed)
        for _ in range(60):
            observations.append(obs)
            obs, _, term, trunc, _ = env.step(np.zeros(1, np.float32))
            if term or trunc:
                break
    batch = np.array(observations)
    expected = np.array([keeper.guard_y(o) for o in batch])
    # (to float rounding: the map normalises the heading vector, the keeper does not)
    np.testing.assert_allclose(scripted_guard_y(batch, params), expected, atol=1e-6)
    assert np.ptp(expected) > 0.1  # the shots moved it
    # A zero action drives to that point like the guard map aimed there.
    for o, y in zip(batch[:20], expected[:20]):
        guard = action_to_command("guard", o, np.array([y / params["y_max"]]), params)
        np.testing.assert_allclose(
            action_to_command("guard-residual", o, np.zeros(1), params), guard, atol=1e-6)


@pytest.mark.parametrize("robot,preset", [("ssl-2012", "ssl-2012"),
                                          ("humanoid-2012", "kidsize-2012")])
def test_ball_residual_starts_from_the_scripted_keeper(robot, preset, tmp_path):
    """``ball-residual`` with a zero action is the scripted keeper (SSL or humanoid, walking and
    diving) on the same perceived observation, step for step; a correction is the scripted
    keeper on the observation whose ball velocity is corrected (team frame, rotated into the
    body frame); a saved numpy policy rebuilds the keeper from its params alone."""
    from agents.policies.action_maps import BALL_RESIDUAL, ball_residual_params
    from soccer_env.envs.keeper import ScriptedGoalkeeper

    env = wrap_actions(gym.make(ID, robot=robot, obs_mode="perceived", perception=preset,
                                belief_features=True), "ball-residual")
    assert env.action_space.shape == (2,)
    keeper = ScriptedGoalkeeper.for_env(env)
    params = ball_residual_params(env)
    assert params["residual"] == BALL_RESIDUAL and params["humanoid"] == (robot != "ssl-2012")
    obs, _ = env.reset(seed=1)
    seen, dived = [], False
    for _ in range(200):
        np.testing.assert_array_equal(
            action_to_command("ball-residual", obs, np.zeros(2), params), keeper(obs))
        dived |= keeper(obs)[3] < -0.5
        seen.append(obs)
        obs, _, term, trunc, _ = env.step(np.zeros(2, np.float32))
        if term or trunc:
            break
    assert robot == "ssl-2012" or dived  # the humanoid keeper's dive went through the map
    act = np.array([-0.5, 0.25])
    names = env.unwrapped.builder.names
    for o in seen[::10]:
        c, s = o[2], -o[3]
        vx, vy = act * BALL_RESIDUAL
        moved = o.astype(np.float64)
        moved[names.index("ball.vx")] += c * vx + s * vy
        moved[names.index("ball.vy")] += -s * vx + c * vy
        np.testing.assert_allclose(action_to_command("ball-residual", o, act, params),
                                   keeper(moved), atol=1e-5)
    # A numpy policy with the map acts on the plain environment from its saved params.
    layers = [("linear", np.zeros((2, len(names))), np.array([0.3, -0.2]))]
    policy = NumpyPolicy.load(NumpyPolicy(
        layers, "clip", -np.ones(2), np.ones(2),
        action_map={"kind": "ball-residual", "params": params}).save(tmp_path / "p.npz"))
    batch = np.array(seen[:5])
    np.testing.assert_allclose(policy(batch), action_to_command(
        "ball-residual", batch, np.tile([0.3, -0.2], (5, 1)), params), atol=1e-6)


def test_humanoid_refuses_the_ssl_maps_and_incomplete_params():
    from agents.policies.action_maps import ball_residual_params

    env = gym.make(ID, robot="humanoid")
    for kind in ("velocity", "target", "guard", "guard-residual"):
        with pytest.raises(ValueError, match="humanoid keeper takes 'native' or 'ball-residual'"):
            wrap_actions(env, kind)
    params = ball_residual_params(env)
    del params["robot.fall_time"]
    with pytest.raises(ValueError, match="robot.fall_time"):
        action_to_command("ball-residual", np.zeros(19), np.zeros(2), params)
