"""The scripted team: it wins, plays both colours and every observation mode, keeps its roles;
its batched actions are its actions."""

from __future__ import annotations

import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import soccer_env
from agents.scripted import ScriptedTeam
from estimators.exact import hypots, wrap_angles
from soccer_env.envs.keeper import ScriptedGoalkeeper

FIELD = soccer_env.presets.field("ssl-div-b")
HX = FIELD.half_length
R = soccer_env.presets.robot("ssl").radius


def idle_team(agents):
    return lambda obs: {a: np.zeros(6, np.float32) for a in agents}


def random_team(agents, seed):
    rng = np.random.default_rng(seed)
    return lambda obs: {a: rng.uniform(-1.0, 1.0, 6).astype(np.float32) for a in agents}


def make_team(kind, env, colour, seed):
    agents = [a for a in env.possible_agents if a.startswith(colour)]
    if kind == "scripted":
        return ScriptedTeam.for_env(env, colour)
    if kind == "idle":
        return idle_team(agents)
    return random_team(agents, seed + 1000)


def play(blue, yellow, kinds, seed, duration=20.0, **kwargs):
    """Play a whole match; return the score (blue, yellow). ``kinds`` = (blue's, yellow's)."""
    env = soccer_env.parallel_env(blue=blue, yellow=yellow, match_duration=duration, **kwargs)
    obs, _ = env.reset(seed=seed)
    teams = [make_team(k, env, c, seed) for k, c in zip(kinds, ("blue", "yellow"))]
    while env.agents:
        actions = {}
        for team in teams:
            actions.update(team(obs))
        obs, *_ = env.step(actions)
    return tuple(env.score)


def in_defense_area(x, y, sign=1.0):
    """Whether a field-frame point lies in the defense area of the team defending -sign x."""
    return sign * x < -HX + FIELD.defense_depth and abs(y) < 0.5 * FIELD.defense_width


# ----------------------------------------------------------------------------------------
# It wins
# ----------------------------------------------------------------------------------------


@pytest.mark.parametrize("blue,yellow", [(1, 1), (3, 3),
                                         pytest.param(6, 6, marks=pytest.mark.slow)])
def test_scripted_team_beats_idle_and_random_teams_with_either_colour(blue, yellow):
    """Over 8 short matches (2 seeds x 2 colours x idle/random opponent) the scripted team
    wins every match, scores at least 1.5 goals per 20 s match and concedes almost nothing."""
    scored = conceded = 0
    for seed in (0, 1):
        for opponent in ("idle", "random"):
            for colour in ("blue", "yellow"):
                kinds = ("scripted", opponent) if colour == "blue" else (opponent, "scripted")
                b, y = play(blue, yellow, kinds, seed)
                gf, ga = (b, y) if colour == "blue" else (y, b)
                assert gf > ga, (opponent, colour, seed, (b, y))
                scored += gf
                conceded += ga
    assert scored >= 12
    assert conceded <= 2


def test_scripted_team_scores_on_perceived_observations():
    """The team reads only its observations: on the estimation stack's belief (noise,
    latency) it still beats idle and random teams."""
    b, y = play(3, 3, ("scripted", "idle"), seed=0, obs_mode="perceived")
    assert b >= 2 and y == 0
    b, y = play(3, 3, ("random", "scripted"), seed=1, obs_mode="perceived")
    assert y >= 2 and b == 0


def test_scripted_team_scores_on_raw_detections():
    """Raw detections (delayed, unfiltered, with very noisy ball velocities) make it weaker,
    but it still scores against an idle team."""
    scores = [play(1, 1, ("scripted", "idle"), seed=s, obs_mode="raw") for s in (0, 1)]
    assert sum(b for b, _ in scores) >= 2 and all(y == 0 for _, y in scores)


def test_same_seed_same_match_and_another_seed_another():
    def trajectory(seed):
        env = soccer_env.parallel_env(blue=2, yellow=2, match_duration=4.0,
                                      obs_mode="perceived")
        obs, _ = env.reset(seed=seed)
        blue, yellow = ScriptedTeam.for_env(env, "blue"), ScriptedTeam.for_env(env, "yellow")
        states, actions = [], []
        while env.agents:
            act = {**blue(obs), **yellow(obs)}
            actions.append(np.stack([act[a] for a in env.possible_agents]))
            obs, *_ = env.step(act)
            states.append(env.state())
        return np.array(states), np.array(actions)

    s1, a1 = trajectory(3)
    s2, a2 = trajectory(3)
    np.testing.assert_array_equal(s1, s2)
    np.testing.assert_array_equal(a1, a2)
    s3, _ = trajectory(4)
    assert not np.array_equal(s1, s3)


# ----------------------------------------------------------------------------------------
# Both colours: yellow reads its own team frame
# ----------------------------------------------------------------------------------------


def staged(blue, yellow, poses, ball, **kwargs):
    """A match reset, then every robot and the ball teleported (at rest); returns the env and
    fresh observations (after one idle step)."""
    env = soccer_env.parallel_env(blue=blue, yellow=yellow, match_duration=60.0,
                                  formation_jitter=0.0, **kwargs)
    env.reset(seed=0)
    env.world.place_all(np.array(poses, dtype=float), ball)
    env.restart_team = -1  # open play, not the kick-off drawn at reset
    obs, *_ = env.step({a: np.zeros(6, np.float32) for a in env.agents})
    return env, obs


def test_yellow_plays_the_mirror_image_of_blue():
    """In a point-symmetric position each yellow robot sees what its blue counterpart sees,
    and the yellow team does what the blue team does."""
    blue = [(-4.0, 0.3, 0.2), (-1.0, -0.8, 1.0), (-2.0, 1.5, -2.5)]
    yellow = [(-x, -y, math.remainder(h + math.pi, 2 * math.pi)) for x, y, h in blue]
    env, obs = staged(3, 3, blue + yellow, (0.0, 0.0))
    blue_team, yellow_team = ScriptedTeam.for_env(env, "blue"), ScriptedTeam.for_env(env, "yellow")
    ab, ay = blue_team(obs), yellow_team(obs)
    assert sorted(ab) == ["blue_0", "blue_1", "blue_2"]
    assert sorted(ay) == ["yellow_0", "yellow_1", "yellow_2"]
    for i in range(3):
        np.testing.assert_allclose(obs[f"yellow_{i}"], obs[f"blue_{i}"], atol=1e-4)
        np.testing.assert_allclose(ay[f"yellow_{i}"], ab[f"blue_{i}"], atol=1e-3)
    # Not trivially idle: someone drives and turns.
    assert np.abs(np.stack(list(ab.values()))[:, :3]).max() > 0.1


# ----------------------------------------------------------------------------------------
# Roles
# ----------------------------------------------------------------------------------------


def test_keeper_is_the_scripted_goalkeeper_outside_its_defense_area():
    """Robot 0 plays ScriptedGoalkeeper's action, bit for bit, whenever the ball is away
    from the defense area (blue and yellow)."""
    env = soccer_env.parallel_env(blue=3, yellow=3, match_duration=10.0)
    obs, _ = env.reset(seed=2)
    teams = {c: ScriptedTeam.for_env(env, c) for c in ("blue", "yellow")}
    keepers = {c: ScriptedGoalkeeper(env.field, env.ball_spec, env.robot_spec,
                                     env.builder.names_for(t))
               for t, c in enumerate(("blue", "yellow"))}
    compared = 0
    while env.agents:
        act = {**teams["blue"](obs), **teams["yellow"](obs)}
        bx = float(env.state()[0])
        for sign, colour in ((1.0, "blue"), (-1.0, "yellow")):
            if sign * bx > -HX + FIELD.defense_depth + 0.2:
                np.testing.assert_array_equal(act[f"{colour}_0"],
                                              keepers[colour](obs[f"{colour}_0"]))
                compared += 1
        obs, *_ = env.step(act)
    assert compared > 500


def test_formation_around_a_fixed_ball():
    """With the ball held in place (and kickers off), the keeper stands on its guard line on
    the ball's side, the nearest field player goes to the ball, and the four defenders walk
    round the ball to stand spread out between it and their goal, outside the defense
    area."""
    poses = [(-3.0, 1.0, 0.0), (1.0, 2.5, 0.0), (-1.0, 0.0, 0.0), (0.5, -2.0, 0.0),
             (-3.0, -2.5, 0.0), (0.0, 1.0, 0.0), (4.0, -2.8, math.pi)]
    ball = (-1.2, 0.8)
    env, obs = staged(6, 1, poses, ball)
    team = ScriptedTeam.for_env(env, "blue")
    idle = {"yellow_0": np.zeros(6, np.float32)}
    closest = np.full(6, np.inf)
    for _ in range(150):  # 2.5 s
        act = team(obs)
        for a in act.values():
            a[3] = 0.0
        obs, *_ = env.step({**act, **idle})
        robots = env.state()[6:].reshape(-1, 6)[:6]
        closest = np.minimum(closest, np.hypot(*(robots[:, :2] - ball).T))
        env.world.set_ball(*ball)
    guard_x = -HX + R + 0.05
    assert abs(robots[0, 0] - guard_x) < 0.05
    assert 0.0 < robots[0, 1] < 0.5 * FIELD.goal_width
    attacker = 2  # the nearest field player at the start
    assert closest[attacker] < 0.15
    defenders = [1, 3, 4, 5]
    assert closest[defenders].min() > 0.2  # they went round the ball, not through it
    d_ball = np.hypot(*(robots[:, :2] - ball).T)
    goal = np.array([-HX, 0.0])
    ball_to_goal = np.hypot(*(np.array(ball) - goal))
    for i in defenders:
        x, y = robots[i, :2]
        assert np.hypot(x - goal[0], y - goal[1]) < ball_to_goal - 0.3, i
        assert not in_defense_area(x, y), i
        assert d_ball[i] > 0.4, i
    gaps = [np.hypot(*(robots[i, :2] - robots[j, :2]))
            for i in defenders for j in defenders if i < j]
    assert min(gaps) > 0.3


def test_attacker_is_the_nearest_field_player_and_scores_past_an_idle_keeper():
    """The field player nearest the ball takes it and shoots past the keeper standing in the
    middle of the goal; its team-mates never touch the ball."""
    poses = [(-4.3, 0.0, 0.0), (-1.0, 2.0, 0.0), (1.0, -0.8, 0.0), (-2.0, -2.0, 0.0),
             (4.3, 0.0, math.pi), (3.5, 2.5, math.pi)]
    env, obs = staged(4, 2, poses, (1.6, -0.5))
    team = ScriptedTeam.for_env(env, "blue")
    idle = {a: np.zeros(6, np.float32) for a in ("yellow_0", "yellow_1")}
    touched = np.zeros(6, dtype=bool)
    for _ in range(240):
        obs, _, _, _, info = env.step({**team(obs), **idle})
        if info["blue_0"]["event"]:
            break
        touched |= env.world.touched
    assert info["blue_0"]["event"] == "goal" and env.score == [1, 0]
    assert touched[2] and not touched[[0, 1, 3]].any()


def test_keeper_alone_clears_a_ball_resting_in_its_defense_area():
    poses = [(-4.3, 0.0, 0.0), (-2.5, 1.0, 0.0), (-2.0, -1.0, 0.0), (3.0, 2.5, math.pi)]
    env, obs = staged(3, 1, poses, (-4.0, 0.5))
    team = ScriptedTeam.for_env(env, "blue")
    idle = {"yellow_0": np.zeros(6, np.float32)}
    cleared = False
    for _ in range(240):
        obs, *_ = env.step({**team(obs), **idle})
        state = env.state()
        robots = state[6:].reshape(-1, 6)
        for i in (1, 2):
            assert not in_defense_area(*robots[i, :2]), (i, robots[i, :2])
        if not in_defense_area(*state[:2]):
            cleared = True
            break
    assert cleared
    assert env.world.last_touch == 0


# ----------------------------------------------------------------------------------------
# API
# ----------------------------------------------------------------------------------------


def test_call_and_batched_act_agree_and_stay_in_the_action_box():
    env = soccer_env.parallel_env(blue=3, yellow=2, match_duration=5.0)
    obs, _ = env.reset(seed=0)
    team = ScriptedTeam.for_env(env, "yellow")
    for _ in range(60):
        act = team(obs)
        assert sorted(act) == ["yellow_0", "yellow_1"]
        batch = team.act(np.stack([obs["yellow_0"], obs["yellow_1"]]))
        assert batch.dtype == np.float32 and batch.shape == (2, 6)
        np.testing.assert_array_equal(batch, np.stack([act["yellow_0"], act["yellow_1"]]))
        assert np.all(np.abs(batch) <= 1.0)
        obs, *_ = env.step({**act, **{f"blue_{i}": np.zeros(6, np.float32) for i in range(3)}})


def test_bad_input_raises_clear_errors():
    env = soccer_env.parallel_env(blue=2, yellow=0, match_duration=5.0)
    with pytest.raises(ValueError, match=r"team must be one of \['blue', 'yellow'\], got 'red'"):
        ScriptedTeam.for_env(env, "red")
    with pytest.raises(ValueError, match="yellow team of this match has no robots"):
        ScriptedTeam.for_env(env, "yellow")
    team = ScriptedTeam.for_env(env, "blue")
    obs, _ = env.reset(seed=0)
    with pytest.raises(ValueError, match=r"obs_batch must have shape \(2, "):
        team.act(obs["blue_0"][None])
    with pytest.raises(ValueError, match="team_size must be 1..11"):
        ScriptedTeam(env.field, env.ball_spec, env.robot_spec, env.builder.names, 0)


# ----------------------------------------------------------------------------------------
# Batched actions: act_batch is act, match by match
# ----------------------------------------------------------------------------------------
#
# act_batch calls open_play_rows, which runs the compiled rules act_one calls (field_player,
# attacker_act) on each row's floats: the same arithmetic, so the actions are equal bit for
# bit. The guarding keeper's rows go through ScriptedGoalkeeper.act_batch, which runs the
# keeper's compiled rule (ssl_keeper) on each row as its single path does. These tests ask for
# exact equality.


def match_observations(n, seed, steps=600):
    """Observations ``(steps, n, obs_dim)`` of both teams of an n-a-side match played by two
    scripted teams, with bursts of random actions (so that the ball is kicked, roles change and
    robots stand anywhere), and the actions ``act`` gave: ``{colour: (obs, actions)}``."""
    env = soccer_env.parallel_env(blue=n, yellow=n, match_duration=60.0)
    obs, _ = env.reset(seed=seed)
    teams = {c: ScriptedTeam.for_env(env, c) for c in ("blue", "yellow")}
    rng = np.random.default_rng(seed)
    seen = {c: ([], []) for c in teams}
    for step in range(steps):
        actions = {}
        for c, team in teams.items():
            rows = np.stack([obs[f"{c}_{i}"] for i in range(n)])
            act = team.act(rows)
            seen[c][0].append(rows)
            seen[c][1].append(act)
            actions.update({f"{c}_{i}": act[i] for i in range(n)})
        if step % 60 >= 50:
            actions = {a: rng.uniform(-1.0, 1.0, 6).astype(np.float32) for a in env.agents}
        obs, *_ = env.step(actions)
    return env, {c: (np.array(o), np.array(a)) for c, (o, a) in seen.items()}


def world_rows(names, robots, headings, ball, ball_velocity, opponents, base):
    """Each robot's observation of a staged world (team frame, [m], [rad], [m/s]): ``base``
    (``(n, obs_dim)``) with the entries the team reads overwritten."""
    ix = {name: i for i, name in enumerate(names)}
    out = np.array(base, dtype=np.float64)
    for i, (pos, h) in enumerate(zip(robots, headings)):
        c, s = math.cos(h), math.sin(h)

        def body(v, c=c, s=s):
            return c * v[0] + s * v[1], -s * v[0] + c * v[1]

        row = out[i]
        row[ix["self.x"]], row[ix["self.y"]] = pos
        row[ix["self.ax"]], row[ix["self.ay"]] = c, -s
        row[ix["ball.dx"]], row[ix["ball.dy"]] = body(np.subtract(ball, pos))
        row[ix["ball.vx"]], row[ix["ball.vy"]] = body(ball_velocity)
        for j, k in enumerate(k for k in range(len(robots)) if k != i):
            row[ix[f"mate{j}.dx"]], row[ix[f"mate{j}.dy"]] = body(np.subtract(robots[k], pos))
        for j, opp in enumerate(opponents):
            row[ix[f"opp{j}.dx"]], row[ix[f"opp{j}.dy"]] = body(np.subtract(opp, pos))
    return out


def random_observations(env, colour, rng, count):
    """``(count, n, obs_dim)`` float32 observations within the observation space: a quarter
    drawn uniformly from it (any heading vector, ball, robots), the rest staged worlds with
    the ball in or at the edge of the own defense area, rolling slowly or fast, a robot just
    behind or in front of it, opponents on the lines from the ball to the goal mouth or close
    to the ball."""
    t = ("blue", "yellow").index(colour)
    names = env.builder.names_for(t)
    n, m = (env.world.n_blue, env.world.n_yellow)[::1 if t == 0 else -1]
    space = env.observation_space(f"{colour}_0")
    lo, hi = space.low.astype(np.float64), space.high.astype(np.float64)
    f = env.field
    hx, hy = f.half_length, f.half_width
    out = rng.uniform(lo, hi, (count, n, len(names)))
    for g in range(count // 4, count):
        if g % 3 == 0:
            ball = (-hx + rng.uniform(0.0, f.defense_depth + 0.1),
                    rng.uniform(-0.6, 0.6) * f.defense_width)
        else:
            ball = (rng.uniform(-hx, hx), rng.uniform(-hy, hy))
        speed = (0.0, rng.uniform(0.0, 0.4), rng.uniform(0.0, 6.0))[g % 3]
        a = rng.uniform(-math.pi, math.pi)
        robots = np.column_stack([rng.uniform(-hx, hx, n), rng.uniform(-hy, hy, n)])
        if n >= 2:
            robots[0] = (-hx + 0.14, rng.uniform(-0.5, 0.5))
        headings = rng.uniform(-math.pi, math.pi, n)
        if g % 2:  # one robot just behind (or in front of) the ball, about facing the goal
            k = rng.integers(n)
            u = np.array([hx, rng.uniform(-0.4, 0.4)]) - ball
            u /= np.linalg.norm(u)
            robots[k] = ball - rng.uniform(-0.3, 0.3) * u + rng.normal(0.0, 0.03, 2)
            headings[k] = math.atan2(u[1], u[0]) + rng.normal(0.0, 0.3)
        opponents = np.column_stack([rng.uniform(-hx, hx, m), rng.uniform(-hy, hy, m)])
        for j in range(m):
            r = rng.random()
            if r < 0.4:  # on the line from the ball to a point of the goal mouth
                goal = np.array([hx, rng.uniform(-0.5, 0.5)])
                opponents[j] = ball + rng.uniform(0.1, 1.0) * (goal - ball) \
                    + rng.normal(0.0, 0.05, 2)
            elif r < 0.6:
                opponents[j] = ball + rng.normal(0.0, 0.4, 2)
        out[g] = world_rows(names, robots, headings, ball,
                            (speed * math.cos(a), speed * math.sin(a)), opponents, out[g])
    return np.clip(out, lo, hi).astype(np.float32)


def assert_batch_is_act(team, obs, expected=None):
    """``team.act_batch(obs)`` (float32 and float64 input) is ``act`` match by match."""
    if expected is None:
        expected = np.stack([team.act(o) for o in obs])
    batch = team.act_batch(obs)
    assert batch.dtype == np.float32 and batch.shape == obs.shape[:2] + (6,)
    np.testing.assert_array_equal(batch, expected)
    np.testing.assert_array_equal(team.act_batch(obs.astype(np.float64)), expected)


@pytest.mark.parametrize("n", [1, 2, 3, 6])
def test_act_batch_is_act_on_match_observations(n):
    """Both teams' observations of a played match (every role, kicks, restarts, random
    bursts): act_batch over all steps at once gives act's actions, bit for bit; so does the
    keeper's act_batch on robot 0's rows."""
    env, seen = match_observations(n, seed=10 + n)
    for colour, (obs, actions) in seen.items():
        team = ScriptedTeam.for_env(env, colour)
        assert_batch_is_act(team, obs, actions)
        keeper = team.keeper
        np.testing.assert_array_equal(keeper.act_batch(obs[:, 0]),
                                      np.stack([keeper(o) for o in obs[:, 0]]))
    # The ball was played: kicked or pushed faster than 1 m/s.
    names = env.builder.names_for(0)
    obs = seen["blue"][0]
    speed = np.hypot(obs[..., names.index("ball.vx")], obs[..., names.index("ball.vy")])
    assert speed.max() > 1.0


@pytest.mark.parametrize("blue,yellow", [(1, 1), (2, 3), (3, 2), (6, 6)])
def test_act_batch_is_act_on_random_and_staged_observations(blue, yellow):
    """Observations drawn from the observation space and staged worlds (balls in the defense
    area, blocked shooting lines, balls behind robots), for both colours."""
    env = soccer_env.parallel_env(blue=blue, yellow=yellow)
    rng = np.random.default_rng(100 * blue + yellow)
    for colour in ("blue", "yellow"):
        team = ScriptedTeam.for_env(env, colour)
        assert_batch_is_act(team, random_observations(env, colour, rng, 600 // blue + 100))


def test_act_batch_breaks_ties_like_act():
    """Symmetric worlds, where act's strict comparisons and max() of tuples pick a side: two
    field players equally placed for the ball, equally good aim points, both escape sides
    equally good when a blocker stands right in front of the ball."""
    env = soccer_env.parallel_env(blue=3, yellow=2)
    names = env.builder.names_for(0)
    team = ScriptedTeam.for_env(env, "blue")
    base = np.zeros((3, len(names)))
    worlds = [
        # Mirrored field players behind the ball on its line to the goal.
        ([(-4.3, 0.0), (-1.0, 0.5), (-1.0, -0.5)], [0.0, 0.0, 0.0], (0.0, 0.0),
         [(3.0, 2.0), (3.0, -2.0)]),
        # A field player straight behind the ball, nobody in the way.
        ([(-4.3, 0.0), (-0.5, 0.0), (-2.0, 2.0)], [0.0, 0.0, 1.0], (0.0, 0.0),
         [(3.0, 2.5), (3.0, -2.5)]),
        # The same with a blocker straight ahead, close and far.
        ([(-4.3, 0.0), (-0.5, 0.0), (-2.0, 2.0)], [0.0, 0.0, 1.0], (0.0, 0.0),
         [(0.4, 0.0), (3.0, -2.5)]),
        ([(-4.3, 0.0), (-0.5, 0.0), (-2.0, 2.0)], [0.0, 0.0, 1.0], (0.0, 0.0),
         [(2.0, 0.0), (2.5, 0.0)]),
        # Beyond the goal line, blocked on the way back: equal escape sides, decided by y.
        ([(-4.3, 0.0), (4.78, 0.0), (-2.0, 2.0)], [0.0, 0.0, 1.0], (4.7, 0.0),
         [(4.65, 0.0), (3.0, -2.5)]),
        # Two defenders lined up behind the attacker.
        ([(-4.3, 0.0), (1.0, 0.0), (-2.0, 0.0)], [0.0, 0.5, -0.5], (0.5, 0.0),
         [(3.0, 0.0), (2.0, 1.0)]),
    ]
    obs = np.stack([world_rows(names, r, h, b, (0.0, 0.0), o, base)
                    for r, h, b, o in worlds]).astype(np.float32)
    assert_batch_is_act(team, obs)


def test_act_batch_rows_do_not_depend_on_the_batch():
    """A match's actions are the same alone (M = 1), in any slice of the batch, and for no
    match at all (M = 0) the answer is empty."""
    env = soccer_env.parallel_env(blue=3, yellow=3)
    team = ScriptedTeam.for_env(env, "yellow")
    obs = random_observations(env, "yellow", np.random.default_rng(7), 40)
    whole = team.act_batch(obs)
    for i in (0, 17, 39):
        np.testing.assert_array_equal(team.act_batch(obs[i:i + 1])[0], whole[i])
    np.testing.assert_array_equal(np.concatenate([team.act_batch(obs[a:b]) for a, b in
                                                  ((0, 5), (5, 23), (23, 40))]), whole)
    np.testing.assert_array_equal(team.act_batch(obs[::-1]), whole[::-1])
    empty = team.act_batch(obs[:0])
    assert empty.shape == (0, 3, 6) and empty.dtype == np.float32


def test_act_batch_rejects_bad_shapes():
    env = soccer_env.parallel_env(blue=2, yellow=1)
    team = ScriptedTeam.for_env(env, "blue")
    obs, _ = env.reset(seed=0)
    rows = np.stack([obs["blue_0"], obs["blue_1"]])
    assert rows.shape == (2, 35)
    for bad in (rows, rows[None, :1], rows[None, :, :-1], rows[None, None]):
        with pytest.raises(ValueError, match=r"obs must have shape \(M, 2, 35\) \(M matches"):
            team.act_batch(bad)
    with pytest.raises(ValueError, match=r"obs must have shape \(n, 35\)"):
        team.keeper.act_batch(rows[0])
    humanoid = ScriptedGoalkeeper(env.field, env.ball_spec, soccer_env.presets.robot("humanoid"),
                                  env.builder.names_for(0))
    with pytest.raises(ValueError, match="act_batch plays SSL keepers"):
        humanoid.act_batch(rows)


@pytest.mark.skipif(sys.version_info < (3, 11), reason="math.hypot's algorithm since 3.11")
def test_hypots_and_wrap_angles_are_math_hypot_and_remainder_bit_for_bit():
    rng = np.random.default_rng(3)
    scale = 10.0 ** rng.uniform(-6.0, 2.0, 200_000)
    x = rng.normal(size=scale.size) * scale
    y = rng.normal(size=scale.size) * scale * 10.0 ** rng.uniform(-8.0, 0.0, scale.size)
    special = [0.0, -0.0, 3.0, 1e-310, 5e-324, 1e300, math.inf, -math.inf]
    x = np.concatenate([x, np.repeat(special, len(special))])
    y = np.concatenate([y, np.tile(special, len(special))])
    np.testing.assert_array_equal(hypots(x, y), [math.hypot(a, b) for a, b in zip(x, y)])
    np.testing.assert_array_equal(hypots(y, x), [math.hypot(b, a) for a, b in zip(x, y)])
    # Angles up to a few turns, and every double next to the half-turn ties.
    angles = [rng.uniform(-4.0 * math.pi, 4.0 * math.pi, 100_000)]
    for tie in (math.pi, 3.0 * math.pi, 2.0 * math.pi):
        for sign in (1.0, -1.0):
            a = np.full(41, sign * tie)
            steps = np.arange(-20, 21)
            angles.append(np.array([math.nextafter(v, math.inf) if k > 0 else v
                                    for v, k in zip(a, steps)]))
            angles.append(a + steps * math.ulp(tie))
    angles = np.concatenate(angles)
    np.testing.assert_array_equal(wrap_angles(angles),
                                  [math.remainder(a, 2.0 * math.pi) for a in angles])


def test_exact_has_no_effect():
    """``exact=False`` (kept for compatibility): the same actions as the exact team, bit for
    bit, on real match observations (every rule is a compiled kernel)."""
    env = soccer_env.parallel_env(blue=2, yellow=2)
    exact = ScriptedTeam.for_env(env, "yellow")
    fast = ScriptedTeam.for_env(env, "yellow", exact=False)
    rng = np.random.default_rng(5)
    obs, _ = env.reset(seed=5)
    rows = []
    for _ in range(300):
        rows.append(np.stack([obs["yellow_0"], obs["yellow_1"]]))
        obs, *_ = env.step({a: rng.uniform(-1, 1, 6) for a in env.possible_agents})
    batch = np.stack(rows)
    np.testing.assert_array_equal(fast.act_batch(batch), exact.act_batch(batch))


def test_the_scripted_package_imports_without_the_learning_libraries():
    """agents.scripted is the numpy-only layer of agents: in a fresh interpreter where
    stable-baselines3, torch and Ray cannot be imported, it imports and plays."""
    code = ("import sys\n"
            "class Block:\n"
            "    def find_spec(self, name, path=None, target=None):\n"
            "        if name.split('.')[0] in ('stable_baselines3', 'torch', 'ray'):\n"
            "            raise ModuleNotFoundError(name)\n"
            "sys.meta_path.insert(0, Block())\n"
            "import soccer_env\n"
            "from agents.scripted import HumanoidTeam, ScriptedTeam, team_residual_params\n"
            "env = soccer_env.parallel_env(blue=2, yellow=2)\n"
            "obs, _ = env.reset(seed=0)\n"
            "print(sorted(ScriptedTeam.for_env(env, 'blue')(obs)))\n")
    res = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         cwd=Path(__file__).resolve().parents[2], timeout=120)
    assert res.returncode == 0, res.stderr
    assert res.stdout == "['blue_0', 'blue_1']\n"
