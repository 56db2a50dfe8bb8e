"""API contracts: Gymnasium, PettingZoo and stable-baselines3 checkers, seeding, rendering."""

import warnings

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env
from pettingzoo.test import api_test, parallel_api_test, parallel_seed_test

import soccer_env


def test_goalkeeper_passes_check_env_without_warnings():
    env = gym.make("soccer_env/Goalkeeper-v0")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        check_env(env.unwrapped)
        check_env(gym.make("soccer_env/Goalkeeper-v0", render_mode="rgb_array").unwrapped)


@pytest.mark.parametrize("field", list(soccer_env.presets.FIELDS))
@pytest.mark.parametrize("robot", list(soccer_env.presets.ROBOTS))
def test_goalkeeper_on_every_preset(field, robot):
    env = gym.make("soccer_env/Goalkeeper-v0", field=field, robot=robot)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        check_env(env.unwrapped, skip_render_check=True)
    obs, info = env.reset(seed=0)
    for _ in range(30):
        obs, r, term, trunc, info = env.step(env.action_space.sample())
        assert env.observation_space.contains(obs)
        if term:
            break


@pytest.mark.parametrize("obs_mode,perception", [("raw", "realistic"), ("perceived", "realistic"),
                                                 ("perceived", "harsh"), ("raw", "ssl-2012")])
def test_goalkeeper_check_env_in_every_mode(obs_mode, perception):
    env = gym.make("soccer_env/Goalkeeper-v0", obs_mode=obs_mode, perception=perception)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        check_env(env.unwrapped, skip_render_check=True)


@pytest.mark.parametrize("obs_mode", ["raw", "perceived"])
def test_match_api_in_every_mode(obs_mode):
    env = soccer_env.parallel_env(blue=2, yellow=2, obs_mode=obs_mode, perception="harsh",
                                  match_duration=5.0)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        parallel_api_test(env, num_cycles=200)
    parallel_seed_test(lambda: soccer_env.parallel_env(blue=2, yellow=2, obs_mode=obs_mode),
                       num_cycles=100)


def test_same_shots_in_every_observation_mode():
    """Sensor noise has its own random stream: the seeded shots do not depend on the mode."""
    shots = []
    for mode, per in (("truth", None), ("raw", "harsh"), ("perceived", "realistic")):
        env = gym.make("soccer_env/Goalkeeper-v0", obs_mode=mode, perception=per)
        shots.append([env.reset(seed=s)[1]["shot"] for s in range(5)])
    assert shots[0] == shots[1] == shots[2]


def test_goalkeeper_passes_sb3_check_env():
    pytest.importorskip("stable_baselines3")
    from stable_baselines3.common.env_checker import check_env as sb3_check_env

    with warnings.catch_warnings():
        warnings.simplefilter("error")
        sb3_check_env(gym.make("soccer_env/Goalkeeper-v0").unwrapped)


def test_goalkeeper_registration():
    env = gym.make("soccer_env/Goalkeeper-v0")
    assert env.spec.max_episode_steps == 480
    assert env.observation_space.shape == (19,) and env.action_space.shape == (6,)


@pytest.mark.parametrize("blue,yellow", [(1, 1), (3, 2), (6, 6)])
def test_parallel_api(blue, yellow):
    env = soccer_env.parallel_env(blue=blue, yellow=yellow, match_duration=10.0)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        parallel_api_test(env, num_cycles=400)


def test_parallel_seed_test():
    parallel_seed_test(lambda: soccer_env.parallel_env(blue=2, yellow=2), num_cycles=200)


def test_aec_api():
    env = soccer_env.env(blue=2, yellow=2, match_duration=5.0)
    api_test(env, num_cycles=200)


def test_spaces_are_memoised():
    env = soccer_env.parallel_env(blue=2, yellow=1)
    assert list(env.observation_spaces) == list(env.action_spaces) == env.possible_agents
    for a in env.possible_agents:
        assert env.observation_space(a) is env.observation_space(a)
        assert env.action_space(a) is env.action_space(a)
        assert env.observation_spaces[a] is env.observation_space(a)
        assert env.action_spaces[a] is env.action_space(a)
    obs, _ = env.reset(seed=0)
    for a in env.agents:
        assert env.observation_space(a).contains(obs[a])


def test_match_info_keys_stable_from_reset():
    env = soccer_env.parallel_env(blue=1, yellow=1, shaping={"ball_distance": 0.1})
    _, infos = env.reset(seed=0)
    _, rewards, _, _, step_infos = env.step({a: np.zeros(6) for a in env.agents})
    for a in env.agents:
        assert set(infos[a]) == set(step_infos[a]) == {"truth", "estimate", "reward_terms",
                                                        "score", "event"}
        assert set(infos[a]["reward_terms"]) == set(step_infos[a]["reward_terms"])
        assert rewards[a] == pytest.approx(sum(step_infos[a]["reward_terms"].values()))
        assert step_infos[a]["reward_terms"]["ball_distance"] < 0


@pytest.mark.parametrize("robot", ["ssl", "humanoid"])
def test_state_space_is_finite_and_holds_every_state(robot):
    """The global state's Box has finite bounds (libraries size their networks' inputs from
    it) and holds the state all through random play, kicks, chips and collisions."""
    env = soccer_env.parallel_env(blue=3, yellow=3, robot=robot)
    assert np.all(np.isfinite(env.state_space.low)) and np.all(np.isfinite(env.state_space.high))
    rng = np.random.default_rng(0)
    env.reset(seed=0)
    assert env.state().shape == env.state_space.shape
    for _ in range(600):
        env.step({a: rng.uniform(-1, 1, 6) for a in env.agents})
        assert env.state_space.contains(env.state())


def rollout_goalkeeper(env, seed, steps=200):
    obs, info = env.reset(seed=seed)
    env.action_space.seed(seed)
    out = [obs]
    for _ in range(steps):
        obs, r, term, trunc, info = env.step(env.action_space.sample())
        out.append(np.append(obs, r))
        if term or trunc:
            obs, info = env.reset()
            out.append(obs)
    return np.concatenate(out)


@pytest.mark.parametrize("obs_mode", ["truth", "raw", "perceived"])
def test_goalkeeper_same_seed_same_episode(obs_mode):
    per = None if obs_mode == "truth" else "harsh"
    a = gym.make("soccer_env/Goalkeeper-v0", obs_mode=obs_mode, perception=per)
    b = gym.make("soccer_env/Goalkeeper-v0", obs_mode=obs_mode, perception=per)
    first = rollout_goalkeeper(a, 7)
    np.testing.assert_array_equal(first, rollout_goalkeeper(b, 7))
    rollout_goalkeeper(a, 3, steps=57)  # other history
    np.testing.assert_array_equal(first, rollout_goalkeeper(a, 7))
    assert not np.array_equal(first, rollout_goalkeeper(a, 8))


def rollout_match(env, seed, steps=150):
    obs, _ = env.reset(seed=seed)
    rng = np.random.default_rng(seed)
    out = []
    for _ in range(steps):
        obs, rew, *_ = env.step({a: rng.uniform(-1, 1, 6) for a in env.agents})
        out.append(np.concatenate([obs[a] for a in env.possible_agents]))
    return np.array(out)


def test_match_same_seed_same_episode():
    env = soccer_env.parallel_env(blue=3, yellow=3)
    first = rollout_match(env, 11)
    rollout_match(env, 5, steps=40)
    np.testing.assert_array_equal(first, rollout_match(env, 11))
    np.testing.assert_array_equal(first, rollout_match(soccer_env.parallel_env(blue=3, yellow=3),
                                                       11))


def test_no_global_random_state_used():
    state = np.random.get_state()[1].copy()  # noqa: NPY002 (checking the legacy global)
    env = gym.make("soccer_env/Goalkeeper-v0")
    rollout_goalkeeper(env, 1, steps=50)
    rollout_match(soccer_env.parallel_env(blue=1, yellow=1), 1, steps=20)
    np.testing.assert_array_equal(state, np.random.get_state()[1])  # noqa: NPY002


def test_info_truth_and_reward_terms():
    env = gym.make("soccer_env/Goalkeeper-v0", shaping={"ball_distance": 1.0})
    obs, info = env.reset(seed=0)
    truth = info["truth"]
    assert set(truth) == {"time", "ball_position", "ball_velocity", "ball_height", "robot_pose",
                          "robot_velocity"}
    assert set(truth["robot_pose"]) == {"blue_0"}
    obs, r, term, trunc, info = env.step(np.zeros(6, np.float32))
    terms = info["reward_terms"]
    assert set(terms) == {"outcome", "intercept", "ball_distance", "action_cost", "outside_area"}
    assert terms["ball_distance"] < 0.0 and terms["intercept"] == 0.0
    assert r == pytest.approx(sum(terms.values()))
    # The observation agrees with the truth (obs_mode="truth").
    kx, ky = truth["robot_pose"]["blue_0"][:2]
    names = env.unwrapped.builder.names
    assert obs[names.index("self.x")] == pytest.approx(info["truth"]["robot_pose"]["blue_0"][0],
                                                       abs=1e-5)
    assert kx < 0


def test_intercept_shaping_points_at_the_goal_mouth():
    """The intercept term is the keeper's distance from where the ball's line meets the goal
    line, limited to the mouth: a ball crawling sideways towards the goal does not put that
    point kilometres away."""
    env = gym.make("soccer_env/Goalkeeper-v0", shaping={"intercept": 1.0},
                   shots={"delay": (5.0, 5.0)})
    env.reset(seed=0)
    u = env.unwrapped
    f, dt = u.field, u.world.control_dt
    ky = float(u.world.snapshot().robots[0, 1])
    # Straight at the keeper: no penalty (to within the step's motion).
    u.world.set_ball(-2.0, ky, -3.0, 0.0)
    *_, info = env.step(np.zeros(6, np.float32))
    assert info["reward_terms"]["intercept"] == pytest.approx(0.0, abs=1e-3)
    # Barely towards the goal, fast sideways: the crossing point is held at the post.
    u.world.set_ball(-2.0, 0.0, -0.06, 2.0)
    *_, info = env.step(np.zeros(6, np.float32))
    mouth = 0.5 * f.goal_width + u.ball_spec.radius
    assert info["reward_terms"]["intercept"] == pytest.approx(
        -abs(ky - mouth) / f.goal_width * dt, rel=0.05)


def test_rgb_array_rendering():
    env = gym.make("soccer_env/Goalkeeper-v0", render_mode="rgb_array", render_width=480)
    env.reset(seed=0)
    frame = env.render()
    assert frame.dtype == np.uint8 and frame.ndim == 3 and frame.shape[1] == 480
    assert frame.shape[2] == 3 and frame.std() > 0
    match = soccer_env.parallel_env(blue=2, yellow=2, render_mode="rgb_array")
    match.reset(seed=0)
    assert match.render().shape[2] == 3


def test_human_rendering_with_dummy_video_driver():
    env = gym.make("soccer_env/Goalkeeper-v0", render_mode="human")
    env.reset(seed=0)
    env.step(np.zeros(6, np.float32))
    env.close()


def test_match_metadata_names_its_registered_id():
    assert soccer_env.parallel_env().metadata["name"] == "soccer_env/Match-v0"
    assert soccer_env.env().metadata["name"] == "soccer_env/Match-v0"


def test_pettingzoo_registry():
    import pettingzoo

    env = pettingzoo.make("parallel", "soccer_env/Match-v0", blue=1, yellow=1)
    assert env.possible_agents == ["blue_0", "yellow_0"]
    aec = pettingzoo.make("aec", "soccer_env/Match-v0", blue=1, yellow=1)
    aec.reset(seed=0)
    assert aec.agent_selection == "blue_0"


def test_readme_training_snippet_runs():
    """The README's stable-baselines3 quick start, shortened."""
    sb3 = pytest.importorskip("stable_baselines3")
    env = gym.make("soccer_env/Goalkeeper-v0")
    model = sb3.PPO("MlpPolicy", env, n_steps=128, batch_size=64, seed=0, device="cpu")
    model.learn(total_timesteps=256)
    obs, _ = env.reset(seed=0)
    action, _ = model.predict(obs, deterministic=True)
    assert env.action_space.contains(action)


def test_gymnasium_record_video_writes_the_episode(tmp_path):
    """Gymnasium's RecordVideo (moviepy, in the render extra) records a Goalkeeper episode."""
    pytest.importorskip("moviepy")
    from gymnasium.wrappers import RecordVideo

    env = RecordVideo(gym.make("soccer_env/Goalkeeper-v0", render_mode="rgb_array",
                               render_width=320), str(tmp_path / "videos"),
                      episode_trigger=lambda e: True, disable_logger=True)
    env.reset(seed=0)
    while True:
        _, _, term, trunc, _ = env.step(np.zeros(6, np.float32))
        if term or trunc:
            break
    env.close()
    videos = list((tmp_path / "videos").glob("*.mp4"))
    assert len(videos) == 1 and videos[0].stat().st_size > 1000
