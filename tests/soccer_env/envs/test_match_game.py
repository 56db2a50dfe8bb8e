"""The match with the game flow (game=...): what the environment does with the game
controller's decisions, the referee state in the observation and the info, the bad inputs,
and the scripted team keeping the rules at restarts. Each rule itself is tested on hand-made
frames in tests/soccer_env/sim/test_game.py and test_humanoid_game.py."""

import math

import numpy as np
import pytest
from pettingzoo.test import parallel_api_test

from agents.scripted import ScriptedTeam
from soccer_env import presets
from soccer_env.envs.batched import NotBatchable
from soccer_env.envs.batched_match import MatchBatch
from soccer_env.envs.match import GAME_FLOW_NAMES, GAME_NAMES, SoccerParallelEnv
from soccer_env.sim.game import COMMANDS

RULES = presets.rules("ssl-2025-div-b")


def match(**kw):
    kw.setdefault("blue", 2)
    kw.setdefault("yellow", 2)
    kw.setdefault("game", "ssl-2025-div-b")
    env = SoccerParallelEnv(**kw)
    env.reset(seed=0)
    return env


def idle(env):
    return {a: np.zeros(6, np.float32) for a in env.agents}


def step(env, actions=None):
    return env.step(idle(env) if actions is None else actions)


def game_entry(env, obs, agent, name):
    names = env.builder.names_for(0 if agent.startswith("blue") else 1)
    return float(obs[agent][list(names).index(name)])


def ball_out_over_touch_line(env, x=1.0):
    """Roll the ball over the touch line at y > 0 (nobody touched it) and step until the
    referee has seen it."""
    w = env.world
    w.set_ball(x, env.field.half_width - 0.1, 0.0, 2.0)
    for _ in range(30):
        obs, _, _, _, info = step(env)
        if info["blue_0"]["game"]["command"] != "normal_start":
            return obs, info
    raise AssertionError("the ball did not leave the field")


def play_in(env):
    """Let the kick-off run out (10 s) so that the ball is in play."""
    for _ in range(int(RULES.kickoff_time * 60) + 5):
        obs, _, _, _, info = step(env)
        if info["blue_0"]["game"]["in_play"]:
            return obs, info
    raise AssertionError("the kick-off never came into play")


# ------------------------------------------------------------------------------------------
# Construction and API


def test_without_the_game_flow_the_observation_keeps_its_four_game_entries():
    plain = SoccerParallelEnv(blue=2, yellow=2)
    flow = SoccerParallelEnv(blue=2, yellow=2, game=True)
    assert plain.game_rules is None and flow.game_rules.name == "ssl-2025-div-b"
    names = list(flow.builder.names_for(0))
    slots = ["game.mate0.on_field", "game.opp0.on_field", "game.opp1.on_field"]
    assert names[-len(GAME_FLOW_NAMES) - 3:] == list(GAME_FLOW_NAMES) + slots
    assert list(flow.builder.names_for(1))[-3:] == slots
    assert list(plain.builder.names_for(0))[-4:] == list(GAME_NAMES)
    size = plain.observation_space("blue_0").shape[0]
    assert flow.observation_space("blue_0").shape[0] == size + len(GAME_FLOW_NAMES) + 3


def test_the_match_with_the_game_flow_passes_the_parallel_api_test():
    parallel_api_test(SoccerParallelEnv(blue=2, yellow=2, game=True, max_cycles=60),
                      num_cycles=60)


@pytest.mark.parametrize("game, error, words", [
    ({"rules": "ssl-2025-div-b", "cards_off": True}, ValueError, "unknown key"),
    ("ssl-2030", ValueError, "unknown rules preset"),
    ({"placement": "teleport"}, ValueError, "placement must be one of"),
    ({"fouls": 1}, ValueError, "fouls must be True or False"),
    ("humanoid-2025-kid", ValueError, "for matches of humanoid robots"),
    (3.5, TypeError, "game must be None"),
])
def test_bad_game_arguments_are_refused_naming_what_is_allowed(game, error, words):
    with pytest.raises(error, match=words):
        SoccerParallelEnv(blue=2, yellow=2, game=game)


def test_mixed_and_batched_matches_refuse_the_game_flow():
    with pytest.raises(ValueError, match="both teams of one robot kind"):
        SoccerParallelEnv(blue=2, yellow=2, robot={"blue": "ssl", "yellow": "humanoid"},
                          game=True)
    with pytest.raises(NotBatchable, match="game flow"):
        MatchBatch(n_matches=2, blue=1, yellow=1, game=True)


def test_humanoid_options_are_refused_and_ssl_options_reach_the_controller():
    with pytest.raises(ValueError, match="apply to SSL rules only"):
        SoccerParallelEnv(blue=1, yellow=1, robot="humanoid",
                          game={"rules": "humanoid-2025-kid", "fouls": False})
    env = match(game={"placement": "referee", "half_time": False, "free_kicks": "2019"})
    assert env.game.options.placement == "referee" and not env.game.options.half_time
    assert env.game.options.free_kicks == "2019"


# ------------------------------------------------------------------------------------------
# What the environment does with the decisions


def test_the_match_starts_with_a_kick_off_whose_team_the_observation_shows():
    env = SoccerParallelEnv(blue=2, yellow=2, game=True)
    obs, info = env.reset(seed=3)
    g = info["blue_0"]["game"]
    assert g["command"] == "prepare_kickoff" and g["situation"] == "kickoff"
    kicker = g["command_team"]
    other = "yellow" if kicker == "blue" else "blue"
    assert game_entry(env, obs, f"{kicker}_0", "game.kickoff_ours") == 1.0
    assert game_entry(env, obs, f"{other}_0", "game.kickoff_theirs") == 1.0
    assert game_entry(env, obs, f"{kicker}_1", "game.restart") == 1.0
    assert game_entry(env, obs, f"{other}_1", "game.restart") == -1.0
    obs, _, _, _, info = step(env)
    assert info["blue_0"]["game"]["command"] == "normal_start"


def test_with_referee_placement_the_ball_goes_to_the_throw_in_spot_and_play_resumes():
    env = match(game={"placement": "referee"})
    play_in(env)
    obs, info = ball_out_over_touch_line(env, x=1.0)
    g = info["blue_0"]["game"]
    assert info["blue_0"]["event"] == "touch"
    assert g["command"] == "stop" and g["next_command"][0] == "direct_free"
    hy = env.field.half_width - RULES.line_margin
    assert g["designated"] == pytest.approx((1.0, hy), abs=0.05)
    assert env.world.ball_array()[0:2] == pytest.approx(g["designated"])
    # Yellow sees the designated position in its own frame (a half turn).
    assert game_entry(env, obs, "yellow_0", "game.target_x") == pytest.approx(-1.0, abs=0.05)
    assert game_entry(env, obs, "yellow_0", "game.target_y") == pytest.approx(-hy, abs=1e-4)
    assert game_entry(env, obs, "blue_0", "game.stop") == 1.0
    # Robots far from the ball: the free kick follows after the placement's minimum time.
    commands = []
    for _ in range(int(RULES.placement_min_time * 60) + 5):
        _, _, _, _, info = step(env)
        commands.append(info["blue_0"]["game"]["command"])
    assert commands[-1] == "direct_free"


def test_with_robot_placement_the_team_receiving_the_free_kick_is_asked_to_place():
    env = match()
    play_in(env)
    obs, info = ball_out_over_touch_line(env, x=1.0)
    g = info["blue_0"]["game"]
    # Nobody touched it, over the touch line in the half yellow defends: yellow's free kick.
    assert g["command"] == "ball_placement" and g["command_team"] == "yellow"
    assert game_entry(env, obs, "yellow_0", "game.placement_ours") == 1.0
    assert game_entry(env, obs, "blue_1", "game.placement_theirs") == 1.0
    assert game_entry(env, obs, "yellow_1", "game.next_team") == 1.0


def test_a_goal_scores_and_lines_the_teams_up_for_the_other_teams_kick_off():
    env = match()
    play_in(env)
    w = env.world
    w.set_ball(env.field.half_length - 0.2, 0.0, 4.0, 0.0)
    for _ in range(30):
        _, rewards, _, _, info = step(env)
        if info["blue_0"]["event"]:
            break
    assert info["blue_0"]["event"] == "goal" and env.score == [1, 0]
    assert rewards["blue_0"] == 1.0 and rewards["yellow_0"] == -1.0
    g = info["blue_0"]["game"]
    assert [e["kind"] for e in g["events"]] == ["goal"]
    assert g["command"] == "stop" and g["next_command"] == ("prepare_kickoff", "yellow")
    for _ in range(int(RULES.stage_pause * 60) + 5):
        _, _, _, _, info = step(env)
        if info["blue_0"]["game"]["command"] == "prepare_kickoff":
            break
    assert w.ball_array()[0:2] == pytest.approx((0.0, 0.0))
    robots = w.robot_array()
    assert np.all(robots[w.teams == 0, 0] < 0.0) and np.all(robots[w.teams == 1, 0] > 0.0)


def test_a_defender_touching_the_ball_in_its_defense_area_gives_a_penalty_kick_formation():
    env = match(blue=3, yellow=3)
    play_in(env)
    w = env.world
    # Blue robot 1 entirely inside blue's defense area, the ball rolling into it.
    x = -env.field.half_length + 0.5 * env.field.defense_depth
    w.set_robot(1, x, 0.3, math.pi)
    w.set_ball(x - 0.4, 0.3, 1.5, 0.0)
    for _ in range(40):
        _, _, _, _, info = step(env)
        if info["blue_0"]["game"]["events"]:
            break
    assert [e["kind"] for e in info["blue_0"]["game"]["events"]] == ["defender_in_defense_area"]
    for _ in range(int(RULES.stage_pause * 60) + 5):
        _, _, _, _, info = step(env)
        if info["blue_0"]["game"]["situation"] == "penalty":
            break
    g = info["blue_0"]["game"]
    assert g["situation_team"] == "yellow"
    mark = (-env.field.half_length + RULES.penalty_mark_distance, 0.0)
    assert w.ball_array()[0:2] == pytest.approx(mark)
    keeper = w.robot_array()[0]
    assert keeper[0] == pytest.approx(-env.field.half_length + w.radii[0])


def test_a_yellow_card_takes_a_robot_to_the_bench_where_its_actions_are_ignored():
    env = match(blue=3, yellow=3, game={"placement": "referee"})
    play_in(env)
    ball_out_over_touch_line(env)  # stop, then the free kick
    info = env.game.team_info[0]
    info.fouls = RULES.fouls_per_card - 1
    # Blue robot 2 (far from the ball) drives at full speed during stop: too fast (8.4.3).
    w = env.world
    w.set_robot(2, -2.0, -2.0, 0.0)
    w.set_ball(*env.game.designated)
    env.game._set_command("stop", -1)  # a fresh stop, to test the card alone
    env.game.next_command = ("direct_free", 1)
    fast = idle(env)
    fast["blue_2"] = np.array([1.0, 0.0, 0.0, 0.0, 0.0, 0.0], np.float32)
    for _ in range(int(RULES.grace_period * 60) + 30):
        obs, _, _, _, info = env.step(fast)
        kinds = [e["kind"] for e in info["blue_0"]["game"]["events"]]
        if "yellow_card" in kinds:
            break
    assert "bot_too_fast_in_stop" in kinds and "yellow_card" in kinds
    assert env.off_field == [2]
    assert info["blue_0"]["game"]["blue"]["off_field"] == ["blue_2"]
    assert info["blue_0"]["game"]["blue"]["robots_allowed"] == 2
    assert game_entry(env, obs, "blue_2", "game.on_field") == 0.0
    assert game_entry(env, obs, "blue_1", "game.on_field") == 1.0
    # Every other robot's slot of blue_2 flags it off the field; the others stay on.
    assert game_entry(env, obs, "blue_0", "game.mate1.on_field") == 0.0
    assert game_entry(env, obs, "blue_1", "game.mate1.on_field") == 0.0
    assert game_entry(env, obs, "blue_1", "game.mate0.on_field") == 1.0
    assert game_entry(env, obs, "yellow_0", "game.opp2.on_field") == 0.0
    assert [game_entry(env, obs, "yellow_0", f"game.opp{j}.on_field") for j in (0, 1)] \
        == [1.0, 1.0]
    assert game_entry(env, obs, "yellow_1", "game.allowed_theirs") == 2.0
    bench = w.robot_array()[2, 0:2].copy()
    assert bench[1] < -env.field.half_width  # beyond the touch line
    for _ in range(30):
        env.step(fast)  # its full-speed action is ignored
    assert w.robot_array()[2, 0:2] == pytest.approx(bench, abs=0.02)


def test_the_match_ends_when_the_controller_ends_it_and_time_left_counts_playing_time():
    env = match(match_duration=2.0, game={"half_time": False})
    done = False
    for _ in range(2000):
        obs, _, terms, _, info = step(env)
        if all(terms.values()):
            done = True
            break
    assert done and info["blue_0"]["game"]["stage"] == "post_game"
    assert env.world.time >= 2.0 and not env.agents


def test_flat_infos_carry_the_referee_state_under_fixed_keys():
    env = match(info_mode="flat")
    _, infos = env.reset(seed=1)
    keys = env.flat_info_keys
    assert tuple(infos["blue_0"]) == keys and "game_command" in keys
    _, _, _, _, infos = step(env)
    assert tuple(infos["yellow_1"]) == keys
    assert COMMANDS[int(infos["blue_0"]["game_command"])] == "normal_start"


def test_same_seed_same_match_with_scripted_teams():
    def run():
        env = SoccerParallelEnv(blue=2, yellow=2, game=True, match_duration=20.0)
        obs, _ = env.reset(seed=5)
        teams = [ScriptedTeam.for_env(env, t) for t in ("blue", "yellow")]
        trace = []
        while env.agents and len(trace) < 900:
            act = {}
            for t in teams:
                act.update(t(obs))
            obs, _, _, _, info = env.step(act)
            trace.append((info["blue_0"]["game"]["command"], env.world.ball_array().tobytes()))
        return trace
    assert run() == run()


# ------------------------------------------------------------------------------------------
# Humanoid laws


def test_a_humanoid_match_plays_the_kick_off_and_the_drop_ball():
    rules = presets.rules("humanoid-2025-kid", dropped_ball_time=3.0)
    env = SoccerParallelEnv(blue=2, yellow=2, robot="humanoid", game=rules,
                            match_duration=600.0)
    obs, info = env.reset(seed=0)
    assert info["blue_0"]["game"]["situation"] == "kickoff"
    play_in(env)
    # Nobody plays the ball: after 3 s a drop ball on the centre mark, robots out of the
    # circle.
    env.world.set_ball(1.0, 1.0)
    kinds = []
    for _ in range(4 * 60):
        _, _, _, _, info = step(env)
        kinds += [e["kind"] for e in info["blue_0"]["game"]["events"]]
        if "drop_ball" in kinds:
            break
    assert "drop_ball" in kinds
    w = env.world
    assert w.ball_array()[0:2] == pytest.approx((0.0, 0.0))
    gaps = np.hypot(*w.robot_array()[:, 0:2].T)
    assert np.all(gaps >= env.field.center_circle_radius - 1e-6)


# ------------------------------------------------------------------------------------------
# The scripted team keeps the rules


def scripted_match(seconds, seed=0, size=3):
    env = SoccerParallelEnv(blue=size, yellow=size, game=True, match_duration=600.0)
    obs, _ = env.reset(seed=seed)
    teams = [ScriptedTeam.for_env(env, t) for t in ("blue", "yellow")]
    events, steps = [], []
    while env.agents and env.world.time < seconds:
        act = {}
        for t in teams:
            act.update(t(obs))
        obs, _, _, _, info = env.step(act)
        g = info["blue_0"]["game"]
        events += [e["kind"] for e in g["events"]]
        steps.append((g["command"], env.world.robot_array().copy(),
                      env.world.ball_array().copy()))
    return env, events, steps


def test_scripted_teams_keep_distance_and_speed_at_stop_and_place_the_ball():
    env, events, steps = scripted_match(120.0)
    for kind in ("bot_too_fast_in_stop", "defender_too_close_to_kick_point",
                 "attacker_too_close_to_defense_area", "attacker_double_touched_ball"):
        assert kind not in events, events
    assert events.count("placement_succeeded") >= 3
    assert events.count("placement_failed") <= events.count("placement_succeeded") // 3
    # Two seconds into every stop, every robot is slower than the limit.
    run = 0
    for command, robots, _ in steps:
        run = run + 1 if command == "stop" else 0
        if run > RULES.grace_period * 60:
            assert np.all(np.hypot(robots[:, 3], robots[:, 4]) <= RULES.stop_speed)


def test_scripted_robots_leave_the_ball_to_the_placing_opponents():
    env = match(blue=3, yellow=3)
    teams = [ScriptedTeam.for_env(env, t) for t in ("blue", "yellow")]
    obs, _ = env.reset(seed=0)
    play_in(env)
    obs, info = ball_out_over_touch_line(env, x=1.0)
    assert info["blue_0"]["game"]["command_team"] == "yellow"
    closest = math.inf
    for k in range(int(RULES.placement_time * 60)):
        act = {}
        for t in teams:
            act.update(t(obs))
        obs, _, _, _, info = env.step(act)
        g = info["blue_0"]["game"]
        if g["command"] != "ball_placement":
            break
        if k > RULES.grace_period * 60:
            w = env.world
            blue = w.robot_array()[w.teams == 0, 0:2]
            closest = min(closest, float(np.min(np.hypot(*(blue - w.ball_array()[0:2]).T))))
    assert g["command"] == "direct_free" and g["command_team"] == "yellow"
    assert closest >= RULES.stop_distance


def test_scripted_humanoids_keep_away_from_the_opponents_throw_in():
    from agents.scripted import HumanoidTeam

    env = SoccerParallelEnv(blue=2, yellow=2, robot="humanoid", game=True)
    obs, _ = env.reset(seed=0)
    teams = [HumanoidTeam.for_env(env, t) for t in ("blue", "yellow")]
    play_in(env)
    w = env.world
    # A throw-in at (1, hy), robots of both teams walking there.
    w.set_ball(1.0, env.field.half_width - 0.3, 0.0, 2.0)
    w.set_robot(1, 1.0, env.field.half_width - 1.2, 0.0)
    w.set_robot(3, 1.6, env.field.half_width - 1.2, math.pi)
    for _ in range(60):
        act = {}
        for t in teams:
            act.update(t(obs))
        obs, _, _, _, info = env.step(act)
        if info["blue_0"]["game"]["situation"] == "free_kick":
            break
    g = info["blue_0"]["game"]
    assert g["situation"] == "free_kick"
    kicker = g["situation_team"]
    other = 1 if kicker == "blue" else 0
    # The other team's field player 0.9 m from the ball, facing it: it must not come nearer.
    bx, by = w.ball_array()[0:2]
    w.set_robot(3 if other else 1, bx, by - 0.9, math.pi / 2)
    events = []
    for _ in range(int(5 * 60)):
        act = {}
        for t in teams:
            act.update(t(obs))
        for a in act:
            if a.startswith(kicker):
                act[a] = np.zeros(6, np.float32)  # nobody takes it
        obs, _, _, _, info = env.step(act)
        events += [e["kind"] for e in info["blue_0"]["game"]["events"]]
    assert "defender_too_close_to_kick_point" not in events
    robots = w.robot_array()[w.teams == other, 0:2]
    assert np.all(np.hypot(*(robots - w.ball_array()[0:2]).T) >= 0.75)


def test_every_referee_gives_an_untouched_ball_to_the_team_defending_where_it_went_out():
    """One convention for the simple referee, the SSL game flow and the humanoid game flow:
    a ball nobody touched since the last restart goes to the team defending the half (touch
    line) or the end (goal line) it left by."""
    from soccer_env.sim.ball import BallExit
    from soccer_env.sim.referee import classify_exit, restart_team

    env = match()
    f = env.field
    cases = [((1.0, f.half_width + 0.1), 1), ((-1.0, -f.half_width - 0.1), 0),
             ((f.half_length + 0.1, 1.0), 1), ((-f.half_length - 0.1, -1.0), 0)]
    for (x, y), team in cases:
        ex = BallExit(x, y, 0.0, 0.0)
        assert restart_team(-1, ex, classify_exit(ex, f, env.ball_spec)) == team, (x, y)
        assert restart_team(team, ex, classify_exit(ex, f, env.ball_spec)) == 1 - team
    for x, team in ((1.0, "yellow"), (-1.0, "blue")):
        env = match()
        play_in(env)
        _, info = ball_out_over_touch_line(env, x=x)
        assert info["blue_0"]["game"]["command_team"] == team, x
