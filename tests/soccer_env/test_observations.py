"""The vectorised observation builder against a direct, per-agent reading of its documentation."""

import math

import numpy as np
import pytest

from soccer_env import presets
from soccer_env.observations import ObservationBuilder
from soccer_env.state import WorldState


def body(vec, theta):
    """Rotate a field-frame vector into a body frame with heading theta."""
    c, s = math.cos(theta), math.sin(theta)
    return [c * vec[0] + s * vec[1], -s * vec[0] + c * vec[1]]


def reference(field, team, own_i, mates, opponents, robots, ball):
    sign = 1.0 if team == 0 else -1.0
    x, y, th, vx, vy, om = robots[own_i]
    th_team = th + (0.0 if team == 0 else math.pi)
    out = [sign * x, sign * y, math.cos(th_team), -math.sin(th_team), *body((vx, vy), th), om]
    out += body((ball[0] - x, ball[1] - y), th) + body(ball[3:5], th)
    for j in [m for m in mates if m != own_i] + list(opponents):
        xj, yj, thj, vxj, vyj, _ = robots[j]
        out += body((xj - x, yj - y), th) + [math.cos(thj - th), math.sin(thj - th)]
        out += body((vxj, vyj), th)
    hx, gw = field.half_length, field.goal_width / 2
    for px, py in ((-hx, gw), (-hx, -gw), (hx, gw), (hx, -gw)):
        out += body((sign * px - x, sign * py - y), th)
    return np.array(out)


@pytest.mark.parametrize("n_blue,n_yellow", [(1, 0), (1, 1), (2, 3), (6, 6), (0, 2)])
@pytest.mark.parametrize("path", ["python", "arrays"])
def test_builder_matches_reference(n_blue, n_yellow, path):
    field = presets.field("ssl-div-b")
    rng = np.random.default_rng(3)
    n = n_blue + n_yellow
    robots = np.column_stack([
        rng.uniform(-4, 4, n), rng.uniform(-3, 3, n), rng.uniform(-math.pi, math.pi, n),
        rng.uniform(-3, 3, n), rng.uniform(-3, 3, n), rng.uniform(-5, 5, n)])
    ball = np.array([0.3, -1.2, 0.0, 2.0, -1.0, 0.0])
    state = WorldState(0.0, ball, robots, tuple(f"r{i}" for i in range(n)), np.zeros(n))
    blue, yellow = list(range(n_blue)), list(range(n_blue, n))
    teams = [0] * n_blue + [1] * n_yellow
    agents = list(range(n))[::-1]  # any order
    b = ObservationBuilder(field, teams, agents, (-5, -5), (5, 5), ("g0", "g1"),
                           implementation=path)
    game = rng.uniform(-1, 1, (n, 2))
    obs = b.build(state, game)
    assert obs.shape == (n, b.size) and obs.dtype == np.float32
    for row, i in enumerate(agents):
        team = teams[i]
        own, opp = (blue, yellow) if team == 0 else (yellow, blue)
        want = np.concatenate([reference(field, team, i, own, opp, robots, ball), game[row]])
        np.testing.assert_allclose(obs[row], want, atol=1e-5)
        assert len(b.names_for(team)) == b.size
        assert b.space().contains(obs[row])
    if n_blue and n_yellow:
        assert b.names_for(0).count("opp0.dx") == 1
        mates = sum(name.endswith(".dx") and name.startswith("mate") for name in b.names_for(1))
        assert mates == n_yellow - 1


@pytest.mark.parametrize("path", ["python", "arrays"])
def test_values_clipped_to_bounds(path):
    field = presets.field("ssl-div-b")
    b = ObservationBuilder(field, [0], [0], implementation=path)
    robots = np.array([[0.0, 0.0, 0.0, 0.0, 0.0, 0.0]])
    ball = np.array([0.0, 0.0, 0.0, 1e6, 0.0, 0.0])  # absurd ball speed
    obs = b.build(WorldState(0.0, ball, robots, ("blue_0",), np.zeros(1)))[0]
    assert obs[b.names.index("ball.vx")] == pytest.approx(b.high[b.names.index("ball.vx")])
    assert b.space().contains(obs)


def test_implementation_choice():
    field = presets.field("ssl-div-b")
    assert ObservationBuilder(field, [0], [0]).path == "python"
    assert ObservationBuilder(field, [0] * 6 + [1] * 6, range(12)).path == "arrays"
    assert ObservationBuilder(field, [0], [0], implementation="arrays").path == "arrays"
    with pytest.raises(ValueError, match="implementation must be one of"):
        ObservationBuilder(field, [0], [0], implementation="c")


@pytest.mark.parametrize("teams,agents,game", [([0], [0], 4), ([0, 0, 1, 1], [0, 1], 4),
                                               ([0, 0, 1, 1], [2, 3], 0),
                                               ([0] * 6 + [1] * 6, list(range(12)), 0)])
def test_batch_build_equals_the_build_of_each_world(teams, agents, game):
    """The batched environments' observations: world by world the plain-Python build's, bit
    for bit (same arithmetic in float64), belief features a perfect sensor's."""
    f = presets.field("ssl-div-b")
    rng = np.random.default_rng(len(teams) + game)
    for features in (False, True):
        b = ObservationBuilder(f, teams, agents, [-1.0] * game, [1.0] * game,
                               [f"g{i}" for i in range(game)], implementation="python",
                               belief_features=features)
        n = 40
        robots = rng.uniform(-7.0, 7.0, (n, len(teams), 6))  # some beyond the bounds: clipped
        ball = rng.uniform(-5.0, 5.0, (n, 6))
        games = rng.uniform(-2.0, 2.0, (n, len(agents), game)) if game else None
        out = b.build_batch(robots, ball, games)
        names = tuple(f"r{i}" for i in range(len(teams)))
        for k in range(n):
            state = WorldState(0.0, ball[k], robots[k], names, np.array(teams))
            expected = b.build(state, None if games is None else games[k])
            np.testing.assert_array_equal(out[k], expected)
        assert out.dtype == np.float32 and out.shape == (n, len(agents), b.size)
    with pytest.raises(ValueError, match=rf"robots must have shape \(B, {len(teams)}, 6\)"):
        b.build_batch(np.zeros((3, len(teams) + 1, 6)), np.zeros((3, 6)), games)
