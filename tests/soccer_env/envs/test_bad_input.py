"""Bad input gets a clear error naming the argument and what is allowed, and never corrupts the
world."""

import math

import gymnasium as gym
import numpy as np
import pytest
from worlds import make_world

import soccer_env
from soccer_env import presets


def keeper(**kw):
    env = gym.make("soccer_env/Goalkeeper-v0", **kw)
    env.reset(seed=0)
    return env


@pytest.mark.parametrize("bad", [np.nan, np.inf, -np.inf])
def test_goalkeeper_nonfinite_action_raises_and_leaves_world_intact(bad):
    env, ref = keeper(), keeper()
    action = np.zeros(6, np.float32)
    action[2] = bad
    before = env.unwrapped.world.snapshot()
    with pytest.raises(ValueError, match="blue_0.*non-finite"):
        env.step(action)
    after = env.unwrapped.world.snapshot()
    np.testing.assert_array_equal(before.robots, after.robots)
    assert before.time == after.time
    # The episode continues exactly as if the bad call never happened.
    rng = np.random.default_rng(0)
    for _ in range(50):
        a = rng.uniform(-1, 1, 6).astype(np.float32)
        o1, r1, t1, tr1, _ = env.step(a)
        o2, r2, t2, tr2, _ = ref.step(a)
        np.testing.assert_array_equal(o1, o2)
        if t1 or tr1:
            break


def test_out_of_range_actions_are_clipped_by_default():
    env, ref = keeper(), keeper()
    o1, *_ = env.step(np.array([5.0, -7.0, 2.0, 3.0, 1.0, 1.0], np.float32))
    o2, *_ = ref.step(np.array([1.0, -1.0, 1.0, 1.0, 1.0, 1.0], np.float32))
    np.testing.assert_array_equal(o1, o2)


def test_out_of_range_actions_rejected_on_request():
    env = keeper(out_of_range_actions="raise")
    with pytest.raises(ValueError, match=r"blue_0.*outside the allowed range \[-1, 1\]"):
        env.step(np.array([0, 0, 0, 1.5, 0, 0], np.float32))
    env.step(np.array([0, 0, 0, 1.0, 0, 0], np.float32))  # the boundary is allowed


@pytest.mark.parametrize("shape", [(5,), (7,), (1, 6), (2, 3)])
def test_wrong_action_shape(shape):
    env = keeper()
    with pytest.raises(ValueError, match=r"shape \(6,\)"):
        env.step(np.zeros(shape, np.float32))


def test_step_before_reset():
    env = gym.make("soccer_env/Goalkeeper-v0").unwrapped
    with pytest.raises(RuntimeError, match="reset"):
        env.step(np.zeros(6, np.float32))


def test_unknown_keyword_lists_allowed():
    with pytest.raises(TypeError, match=r"\['colour'\].*allowed: .*'field'"):
        gym.make("soccer_env/Goalkeeper-v0", colour="red")
    # Python's own wording, which TorchRL's GymEnv looks for before dropping "frameskip".
    with pytest.raises(TypeError, match=r"GoalkeeperEnv\(\) got an unexpected keyword "
                                        r"argument 'frameskip'"):
        gym.make("soccer_env/Goalkeeper-v0", frameskip=4)
    with pytest.raises(TypeError, match=r"\['team_size'\].*allowed: .*'blue'"):
        soccer_env.parallel_env(team_size=3)


@pytest.mark.parametrize("kwargs,match", [
    ({"field": "ssl-div-c"}, r"unknown field preset 'ssl-div-c'; known: \['humanoid-2012'"),
    ({"robot": "nao"}, r"unknown robot preset 'nao'; known: \['humanoid', 'humanoid-2012', "
                       r"'ssl', 'ssl-2012'\]"),
    ({"ball": "tennis"}, r"unknown ball preset 'tennis'; known"),
    ({"obs_mode": "filtered"}, r"obs_mode must be one of \['truth', 'raw', 'perceived'\]"),
    ({"perception": "foggy"}, r"unknown vision preset 'foggy'; known: \['harsh', 'ideal'"),
    ({"perception": {"ball_filter": "ukf"}}, r"ball_filter must be one of \['kf', 'kf-comp'"),
    ({"perception": {"colour": 2}}, r"unknown perception key\(s\) \['colour'\]"),
    ({"perception": {"camera": 2}}, r"perception \['camera'\]: these are humanoids' "
                                    r"head-camera options; SSL robots see through the overhead"),
    ({"perception": {"camera": "kidsize", "radio": "zigbee"}}, r"\['camera', 'radio'\]"),
    ({"head": "scan"}, r"head aims humanoids' head cameras; these robots are SSL robots"),
    ({"control_dt": "0.02"}, r"control_dt must be a number in \[0.001, 0.5\], got '0.02'"),
    ({"physics_dt": True}, r"physics_dt must be a number"),
    ({"robot": "humanoid", "perception": "realistic"}, r"unknown head-camera preset "
                                                       r"'realistic' for humanoid perception"),
    ({"robot": "humanoid", "perception": {"fusion": "median"}}, r"fusion must be one of"),
    ({"robot": "humanoid", "mates": 4}, r"mates must be an integer in 0..3, got 4"),
    ({"mates": 1}, r"mates \(team-mates watch only for humanoid keepers"),
    ({"robot": "humanoid", "head": "wobble"}, r"head must be one of \['auto', 'scan', "
                                               r"'action'\]"),
    ({"perception": 3}, r"perception must be a preset name"),
    ({"render_mode": "ansi"}, r"render_mode must be one of \[None, 'human', 'rgb_array'\]"),
    ({"out_of_range_actions": "ignore"}, r"out_of_range_actions must be one of"),
    ({"shaping": {"speed": 1.0}}, r"unknown shaping term\(s\) \['speed'\]; known"),
    ({"shaping": {"intercept": float("nan")}}, r"shaping\['intercept'\] must be in"),
    ({"shots": {"speed": (5.0, 2.0)}}, r"shots.speed must be \(low, high\)"),
    ({"shots": {"power": 3}}, r"unknown shots key\(s\) \['power'\]"),
    ({"shots": {"x_range": (-9.0, 0.0)}}, r"inside the field of play"),
    ({"control_dt": 0.0}, r"control_dt must be in \[0.001, 0.5\]"),
    ({"control_dt": "fast"}, r"control_dt must be a number in \[0.001, 0.5\]"),
    ({"physics_dt": 1.0}, r"physics_dt must be in"),
    ({"render_width": 0}, r"render_width must be an integer in \[64, 3840\] pixels, got 0"),
    ({"render_width": 10**6}, r"render_width must be an integer in \[64, 3840\]"),
    ({"render_width": 640.5}, r"render_width must be an integer"),
])
def test_goalkeeper_bad_arguments(kwargs, match):
    with pytest.raises((ValueError, TypeError), match=match):
        gym.make("soccer_env/Goalkeeper-v0", **kwargs)


@pytest.mark.parametrize("kwargs,match", [
    ({"blue": 12}, r"blue must be an integer in 0..11, got 12"),
    ({"yellow": -1}, r"yellow must be an integer in 0..11, got -1"),
    ({"blue": 2.5}, r"blue must be an integer"),
    ({"blue": True}, r"blue must be an integer"),
    ({"blue": 0, "yellow": 0}, r"blue \+ yellow must be >= 1"),
    ({"match_duration": -3}, r"match_duration must be in"),
    ({"max_cycles": 0}, r"max_cycles \(a positive integer or None\) must be an integer"),
    ({"formation_jitter": 2.0}, r"formation_jitter must be in \[0.0, 1.0\]"),
])
def test_match_bad_arguments(kwargs, match):
    with pytest.raises((ValueError, TypeError), match=match):
        soccer_env.parallel_env(**kwargs)


def test_preset_overrides_validated():
    with pytest.raises(TypeError, match=r"unknown robot parameter\(s\) \['wheels'\]; allowed"):
        presets.robot("ssl", wheels=4)
    with pytest.raises(ValueError, match=r"max_speed must be in \(0.0, 20.0\], got -1"):
        presets.robot("ssl", max_speed=-1)
    with pytest.raises(ValueError, match=r"kick_speed_cap must be in"):
        presets.robot("ssl", kick_speed_cap=math.nan)
    with pytest.raises(ValueError, match=r"goal_depth must be in"):
        presets.field("ssl-div-b", goal_depth=0.5)
    with pytest.raises(TypeError, match="field must be a preset name"):
        presets.field(42)
    assert presets.ball("ssl", rolling_deceleration=0.26).rolling_deceleration == 0.26


def test_match_action_dict_errors_leave_world_intact():
    env = soccer_env.parallel_env(blue=2, yellow=1)
    env.reset(seed=0)
    good = {a: np.zeros(6) for a in env.agents}
    before = env.world.snapshot()
    with pytest.raises(ValueError, match=r"missing actions for agent\(s\) \['yellow_0'\]"):
        env.step({a: v for a, v in good.items() if a != "yellow_0"})
    with pytest.raises(ValueError, match=r"unknown or finished agent\(s\) \['red_0'\]"):
        env.step({**good, "red_0": np.zeros(6)})
    with pytest.raises(ValueError, match=r"agent 'blue_1' must have shape \(6,\)"):
        env.step({**good, "blue_1": np.zeros(4)})
    with pytest.raises(ValueError, match=r"agent 'blue_0' contains a non-finite value"):
        env.step({**good, "blue_0": np.array([0, 0, np.nan, 0, 0, 0])})
    with pytest.raises(TypeError, match="actions must be a dict"):
        env.step([np.zeros(6)] * 3)
    after = env.world.snapshot()
    np.testing.assert_array_equal(before.robots, after.robots)
    assert before.time == after.time and env.cycles == 0
    env.step(good)


def test_match_messages_name_the_argument():
    env = soccer_env.parallel_env(blue=1, yellow=1)
    with pytest.raises(ValueError, match=r"seed must be None or an integer >= 0, got -1"):
        env.reset(seed=-1)
    env.reset(seed=0)
    with pytest.raises(ValueError, match=r"unknown or finished agent\(s\) \['red_1', 0\]"):
        env.step({"blue_0": np.zeros(6), 0: np.zeros(6), "red_1": np.zeros(6)})


@pytest.mark.parametrize("shots,match", [
    ({"speed": [1, 2, 3]}, r"shots.speed must be \(low, high\), two finite numbers, got "
                           r"\(1, 2, 3\)"),
    ({"speed": "fast"}, r"shots.speed must be \(low, high\)"),
    ({"delay": (0.0, float("nan"))}, r"shots.delay must be \(low, high\)"),
    ({"chip_probability": "often"}, r"shots.chip_probability must be in \[0.0, 1.0\]"),
    ({"y_range": (1.0,)}, r"shots.y_range must be \(low, high\)"),
])
def test_shot_distribution_messages_name_the_entry(shots, match):
    with pytest.raises(ValueError, match=match):
        gym.make("soccer_env/Goalkeeper-v0", shots=shots)


def test_step_after_the_shot_ended_raises():
    """A finished Goalkeeper episode cannot be stepped on (it returned +1 for a save every
    further step): the error says how it ended and to reset; reset starts anew."""
    env = gym.make("soccer_env/Goalkeeper-v0").unwrapped
    env.reset(seed=0)
    while True:
        _, _, term, _, info = env.step(np.zeros(6, np.float32))
        if term:
            break
    with pytest.raises(RuntimeError, match=rf"ended \('{info['outcome']}'\).*reset"):
        env.step(np.zeros(6, np.float32))
    env.reset(seed=1)
    env.step(np.zeros(6, np.float32))


@pytest.mark.parametrize("bad,match", [
    (np.array([np.nan, 0, 0, 0, 0, 0]), r"agent 'blue_0' contains a non-finite value"),
    (np.zeros(5), r"agent 'blue_0' must have shape \(6,\)"),
    ("fast", r"agent 'blue_0' must have shape \(6,\)"),
])
def test_aec_refuses_a_bad_action_at_the_agent_that_acts(bad, match):
    """AEC: a bad action raises at its own agent's step, naming it, and leaves the cycle as
    it was (the same agent still to act); the cycle then goes on normally."""
    env = soccer_env.env(blue=1, yellow=1)
    env.reset(seed=0)
    assert env.agent_selection == "blue_0"
    with pytest.raises(ValueError, match=match):
        env.step(bad)
    assert env.agent_selection == "blue_0"
    env.step(np.zeros(6))
    assert env.agent_selection == "yellow_0"
    env.step(np.zeros(6))  # the physics steps: the cycle is complete
    assert env.agent_selection == "blue_0"
    env.step(np.zeros(6))


@pytest.mark.parametrize("action", [np.array([1j, 0, 0, 0, 0, 0]),
                                    np.array(["2020-01-01"] * 6, dtype="datetime64[D]"),
                                    np.array(["a"] * 6), [0, 0, 0, 0, 0, [1]]])
def test_actions_that_are_no_real_numbers_are_refused(action):
    env = gym.make("soccer_env/Goalkeeper-v0")
    env.reset(seed=0)
    with pytest.raises(ValueError, match="action must"):
        env.step(action)
    env.step(np.zeros(6))  # nothing was broken
    match = soccer_env.parallel_env(blue=1, yellow=1)
    match.reset(seed=0)
    with pytest.raises(ValueError, match="actions must be arrays of 6 real numbers|must have "
                                         "shape"):
        match.step({a: action for a in match.agents})
    match.step({a: np.zeros(6) for a in match.agents})


def test_reset_options_are_checked():
    """The tasks take no reset options; the match ignores the keys it does not know (as
    PettingZoo's API test expects) but takes a dict only."""
    env = gym.make("soccer_env/Goalkeeper-v0")
    with pytest.raises(ValueError, match=r"options: GoalkeeperEnv takes no options; got "
                                         r"\['foo'\]"):
        env.reset(options={"foo": 1})
    with pytest.raises(ValueError, match=r"options must be None or a dict, got str 'x'"):
        env.reset(options="x")
    env.reset(seed=0, options={})  # an empty dict is no option
    parallel = soccer_env.parallel_env(blue=1, yellow=1)
    with pytest.raises(ValueError, match=r"options must be None or a dict, got str 'x'"):
        parallel.reset(options="x")
    a, _ = parallel.reset(seed=3, options={"foo": 1})
    b, _ = parallel.reset(seed=3)
    assert all(np.array_equal(a[k], b[k]) for k in a)


def test_a_numpy_integer_seed_is_a_seed():
    env = gym.make("soccer_env/Goalkeeper-v0")
    a, _ = env.reset(seed=np.int64(7))
    b, _ = env.reset(seed=7)
    assert np.array_equal(a, b)


def test_a_shot_range_of_one_value_fixes_it():
    env = gym.make("soccer_env/Goalkeeper-v0", shots={"x_range": (-1.0, -1.0)})
    for seed in range(3):
        _, info = env.reset(seed=seed)
        assert info["shot"]["x"] == -1.0 if "x" in info["shot"] else True
        assert info["truth"]["ball_position"][0] == pytest.approx(-1.0)


def test_an_aec_step_after_the_match_is_over_raises():
    env = soccer_env.env(blue=1, yellow=1, max_cycles=1)
    env.reset(seed=0)
    for _agent in env.agent_iter():
        _, _, done, cut, _ = env.last()
        env.step(None if done or cut else np.zeros(6))
    with pytest.raises(RuntimeError, match="the match is over; call reset"):
        env.step(np.zeros(6))


def test_step_after_match_end():
    env = soccer_env.parallel_env(blue=1, yellow=1, max_cycles=1)
    env.reset(seed=0)
    env.step({a: np.zeros(6) for a in env.agents})
    with pytest.raises(RuntimeError, match="reset"):
        env.step({})


def test_world_placement_validated():
    w = make_world()
    w.reset(np.array([[0.0, 0.0, 0.0]]))
    with pytest.raises(ValueError, match=r"ball position must be finite and inside the walls"):
        w.set_ball(100.0, 0.0)
    with pytest.raises(ValueError, match=r"ball velocity and height must be finite"):
        w.set_ball(0.0, 0.5, math.nan, 0.0)
    with pytest.raises(ValueError, match=r"robot_poses must have shape \(1, 3\)"):
        w.reset(np.zeros((2, 3)))
    with pytest.raises(ValueError, match=r"commands must have shape \(1, 6\)"):
        w.step(np.zeros((1, 4)))


def test_a_step_after_time_limit_truncation_goes_on_by_design():
    """Gymnasium's TimeLimit truncates; the task has not ended, so a further step continues
    the shot (finite results) and TimeLimit reports the truncation again."""
    env = gym.make("soccer_env/Goalkeeper-v0", max_episode_steps=3)
    env.reset(seed=0)
    for _ in range(3):
        *_, terminated, truncated, _ = env.step(np.zeros(6, np.float32))
    assert truncated and not terminated
    obs, reward, terminated, truncated, _ = env.step(np.zeros(6, np.float32))
    assert truncated and np.all(np.isfinite(obs)) and np.isfinite(reward)
    env.reset(seed=0)
    assert not env.step(np.zeros(6, np.float32))[3]
