"""The "team-residual" map (agents.scripted.residual): an action of 0 plays the scripted team
exactly, the map's bounds and switches, a numpy policy saved with the map acts alone on the
plain match, training through the VecEnv wrapper hands the map to self-play copies, and bad
input is refused with the argument named."""

import numpy as np
import pytest

import soccer_env
from agents.policies import NumpyPolicy
from agents.scripted import (
    HUMANOID_IDLE_MOTION,
    HumanoidTeam,
    ScriptedTeam,
    residual_command,
    scripted_team_from_params,
    team_residual_command,
    team_residual_params,
)
from agents.studies.matches import Side, head_to_head, team_policy
from agents.vec.factories import make_match_vec_env
from agents.vec.self_play import SelfPlayCallback
from agents.vec.team_residual import TeamResidualVecEnv

KWARGS = {"blue": 2, "yellow": 2, "match_duration": 6.0, "control_dt": 1.0 / 30.0}


def _play(blue_act, seed=3):
    """Ball positions of a match whose yellow team is scripted and blue plays ``blue_act``."""
    env = soccer_env.parallel_env(**KWARGS)
    yellow = ScriptedTeam.for_env(env, "yellow")
    obs, _ = env.reset(seed=seed)
    balls = []
    while env.agents:
        actions = blue_act(env, obs)
        actions.update(yellow(obs))
        obs, _, _, _, infos = env.step(actions)
        balls.append(infos["blue_0"]["truth"]["ball_position"][:2].copy())
    score = infos["blue_0"]["score"]
    env.close()
    return np.array(balls), score


def test_zero_correction_plays_the_scripted_team():
    def scripted(env, obs):
        return ScriptedTeam.for_env(env, "blue")(obs)

    def residual(env, obs):
        params = team_residual_params(env, "blue")
        rows = np.stack([obs["blue_0"], obs["blue_1"]])
        out = team_residual_command(rows, np.zeros((2, 6)), params)
        return {"blue_0": out[0], "blue_1": out[1]}

    want, want_score = _play(scripted)
    got, got_score = _play(residual)
    assert np.abs(np.diff(want, axis=0)).sum() > 0.5  # the ball moved
    np.testing.assert_array_equal(got, want)
    assert got_score == want_score


def test_switches_and_bounds():
    env = soccer_env.parallel_env(**KWARGS)
    obs, _ = env.reset(seed=0)
    params = team_residual_params(env, "blue")
    rows = np.stack([obs["blue_0"], obs["blue_1"]])
    base = ScriptedTeam.for_env(env, "blue").act(rows)
    env.close()
    zero = team_residual_command(rows, np.zeros((2, 6)), params)
    np.testing.assert_array_equal(zero[:, :3], base[:, :3])
    # A switch that is off (kick 0, chip and dribbler -1) reads -1: off either way.
    assert np.all(base[:, 4:] == -1.0) and np.all(zero[:, 3:][base[:, 3:] <= 0] == -1.0)
    # +1 on the switches turns them on at full power; the motion saturates at +-1.
    on = team_residual_command(rows, np.ones((2, 6)), params)
    assert np.all(on[:, 3:] == np.where(base[:, 3:] > 0, 1.0, 0.0))
    full = team_residual_command(rows, np.full((2, 6), 2.0), params)  # clipped to 1 first
    np.testing.assert_array_equal(full, on)
    down = team_residual_command(rows, -np.ones((2, 6)), params)
    assert np.all(down >= -1.0) and np.all(down[:, 3:] == -1.0)


def test_the_team_rebuilt_once_gives_the_map():
    """scripted_team_from_params rebuilds the scripted team from the params alone (the same
    team for the same params), and residual_command with it is team_residual_command."""
    env = soccer_env.parallel_env(**KWARGS)
    obs, _ = env.reset(seed=2)
    params = team_residual_params(env, "yellow", residual=0.5)
    team = scripted_team_from_params(params)
    assert isinstance(team, ScriptedTeam) and team.team_size == 2
    assert scripted_team_from_params(dict(params)) is team
    rows = np.stack([obs["yellow_0"], obs["yellow_1"]])
    np.testing.assert_array_equal(team.act(rows),
                                  ScriptedTeam.for_env(env, "yellow").act(rows))
    act = np.random.default_rng(1).uniform(-1.0, 1.0, (2, 6))
    np.testing.assert_array_equal(residual_command(team, 0.5, rows, act),
                                  team_residual_command(rows, act, params))
    env.close()
    with pytest.raises(ValueError, match=r"params lack \['team_size'\]"):
        scripted_team_from_params({k: v for k, v in params.items() if k != "team_size"})


def test_a_saved_team_acts_alone_on_the_plain_match(tmp_path):
    env = soccer_env.parallel_env(**KWARGS)
    obs, _ = env.reset(seed=1)
    params = team_residual_params(env, "yellow")
    n = env.observation_space("yellow_0").shape[0]
    rng = np.random.default_rng(0)
    w, b = rng.normal(0, 0.05, (6, n)), rng.normal(0, 0.3, 6)
    policy = NumpyPolicy([("linear", w, b)], "clip", -np.ones(6), np.ones(6),
                         action_map={"kind": "team-residual", "params": params})
    path = policy.save(tmp_path / "team.npz")
    loaded = NumpyPolicy.load(path)
    rows = np.stack([obs["yellow_0"], obs["yellow_1"]])
    want = team_residual_command(rows, np.clip(rows @ w.T + b, -1, 1), params)
    np.testing.assert_allclose(loaded(rows), want, atol=1e-6)
    acts = team_policy(str(path), env, "yellow")(obs)
    np.testing.assert_allclose(np.stack([acts["yellow_0"], acts["yellow_1"]]), want, atol=1e-6)
    env.close()
    h = head_to_head(Side(str(path), "truth"), Side("scripted", "truth"), 2,
                     env_kwargs={**KWARGS, "match_duration": 2.0}, workers=1)
    assert h.matches == 2  # plays from both sides
    with pytest.raises(ValueError, match="whole teams of 2 robots"):
        loaded(rows[:1])


def test_training_through_the_map_gives_self_play_copies_the_map():
    from stable_baselines3 import PPO

    train = {**KWARGS, "match_duration": 1.0}
    params = team_residual_params(soccer_env.parallel_env(**train), "blue")
    venv = TeamResidualVecEnv(make_match_vec_env(train, n_matches=2, opponent="scripted",
                                                 seed=0), params)
    assert venv.num_envs == 4 and venv.action_map == {"kind": "team-residual",
                                                      "params": params}
    model = PPO("MlpPolicy", venv, n_steps=8, batch_size=16, n_epochs=1, seed=0)
    callback = SelfPlayCallback(update_every=16)
    model.learn(32, callback=callback)
    copy = callback.pool[-1]
    assert copy.action_map["kind"] == "team-residual"
    obs = venv.reset()
    net = copy.network_action(obs)
    np.testing.assert_allclose(copy(obs), team_residual_command(obs, net, params), atol=1e-6)
    venv.close()


def test_under_the_game_flow_the_correction_applies_in_open_play_only():
    """A full correction changes the command in open play and leaves the scripted team's at
    restarts and for a robot off the field; the params rebuild a team with the match's
    rules."""
    env = soccer_env.parallel_env(blue=2, yellow=2, game=True, match_duration=30.0)
    obs, _ = env.reset(seed=1)
    params = team_residual_params(env, "blue")
    assert params["rules"]["name"] == env.game_rules.name
    team = ScriptedTeam.for_env(env, "blue")
    yellow = ScriptedTeam.for_env(env, "yellow")
    push = np.full((2, 6), 0.8)
    seen = {"restart": 0, "open": 0}
    while env.agents and env.world.time < 20.0:
        rows = np.stack([obs["blue_0"], obs["blue_1"]])
        scripted = team.act(rows)
        scripted[:, 3:] = np.where(scripted[:, 3:] > 0.0, scripted[:, 3:], -1.0)
        u = team_residual_command(rows, push, params)
        restart = np.asarray(team.restarts.needs_restart_play(rows), dtype=bool)
        np.testing.assert_allclose(u[restart], scripted[restart], atol=1e-6)
        assert np.all(np.abs(u[~restart] - scripted[~restart]).max(axis=1) > 0.1)
        seen["restart"] += int(restart.sum())
        seen["open"] += int((~restart).sum())
        obs, *_ = env.step({**dict(zip(("blue_0", "blue_1"), u)), **yellow(obs)})
    assert seen["restart"] > 50 and seen["open"] > 50
    # A robot off the field: its row plays the scripted team's command (standing still).
    rows = np.stack([obs["blue_0"], obs["blue_1"]])
    names = list(env.builder.names_for(0))
    rows[1, names.index("game.on_field")] = 0.0
    u = team_residual_command(rows, push, params)
    np.testing.assert_allclose(u[1, :3], team.act(rows)[1, :3], atol=1e-6)


HUMANOIDS = {"blue": 2, "yellow": 2, "robot": "humanoid-2012", "match_duration": 8.0,
             "control_dt": 1.0 / 30.0}


@pytest.mark.parametrize("game", [False, True])
def test_a_humanoid_team_through_the_map(game):
    """The map corrects the scripted humanoid team: a zero correction plays it exactly (the
    same match, its "neither kick nor dive" read as HUMANOID_IDLE_MOTION, which does
    nothing), the rebuilt team is the team, and under the laws' game flow a robot waiting
    out the opponents' restart or off the field plays the scripted command whatever the
    correction."""
    kwargs = {**HUMANOIDS, "game": game}
    runs = []
    for correct in (False, True):
        env = soccer_env.parallel_env(**kwargs)
        obs, _ = env.reset(seed=4)
        params = team_residual_params(env, "blue")
        team = scripted_team_from_params(params)
        blue, yellow = (HumanoidTeam.for_env(env, side) for side in ("blue", "yellow"))
        assert isinstance(team, HumanoidTeam) and params["kind"] == "humanoid"
        balls, waited = [], 0
        while env.agents:
            rows = np.stack([obs["blue_0"], obs["blue_1"]])
            base = np.stack(list(blue(obs).values()))
            np.testing.assert_array_equal(team.act_batch(rows[None])[0], base)
            act = (residual_command(team, 1.0, rows, np.zeros((2, 6))) if correct
                   else base)
            if correct:
                idle = base[:, 3] == 0.0
                assert np.all(act[idle, 3] == HUMANOID_IDLE_MOTION)
                waiting = team.waiting_rows(rows)
                waited += int(waiting.sum())
                pushed = residual_command(team, 1.0, rows, np.ones((2, 6)))
                np.testing.assert_array_equal(pushed[waiting], act[waiting])
            actions = {"blue_0": act[0], "blue_1": act[1], **yellow(obs)}
            obs, _, _, _, infos = env.step(actions)
            balls.append(infos["blue_0"]["truth"]["ball_position"][:2].copy())
        runs.append((np.array(balls), infos["blue_0"]["score"], waited))
        env.close()
    (want, want_score, _), (got, got_score, waited) = runs
    assert np.abs(np.diff(want, axis=0)).sum() > 0.2  # the ball moved
    np.testing.assert_array_equal(got, want)
    assert got_score == want_score
    assert (waited > 0) == game  # the kick-off's wait, under the game flow only


@pytest.mark.parametrize("make, match", [
    (lambda: team_residual_params(soccer_env.parallel_env(blue=2, yellow=2), "red"),
     "team must be one of"),
    (lambda: team_residual_params(soccer_env.parallel_env(blue=2, yellow=2), "blue",
                                  residual=0.0), r"residual must be in \(0, 2\]"),
    (lambda: team_residual_command(np.zeros((3, 41)), np.zeros((3, 6)), team_residual_params(
        soccer_env.parallel_env(blue=2, yellow=2), "blue")), "got 3 rows"),
    (lambda: team_residual_command(np.zeros((2, 41)), np.zeros((2, 3)), team_residual_params(
        soccer_env.parallel_env(blue=2, yellow=2), "blue")), r"actions \(n, 6\)"),
    (lambda: TeamResidualVecEnv(make_match_vec_env({"blue": 3, "yellow": 1}, n_matches=1),
                                team_residual_params(soccer_env.parallel_env(blue=2, yellow=2),
                                                     "blue")), "not whole teams of 2"),
])
def test_bad_input_is_refused(make, match):
    with pytest.raises(ValueError, match=match):
        make()
