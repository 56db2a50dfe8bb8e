"""The scripted team's compiled kernels equal the rules they port, bit for bit."""

from __future__ import annotations

import math

import numpy as np

import soccer_env
from agents.scripted import ScriptedTeam
from agents.scripted.attack import roll
from agents.scripted.motion import command
from estimators import FrictionBallModel
from soccer_env.envs.keeper import drive_command, turn_command


def test_command_kernel_is_drive_command_and_turn_command_bit_for_bit():
    """motion.command: drive_command's velocity and turn_command's rate, bit for bit (with
    and without a speed cap, at the target)."""
    rng = np.random.default_rng(6)
    n = 3000
    px, py, tx, ty = rng.uniform(-4.0, 4.0, (4, n))
    tx[:10], ty[:10] = px[:10], py[:10]  # already there
    h = rng.uniform(-math.pi, math.pi, n)
    face = rng.uniform(-4.0, 4.0, n)
    for k in range(n):
        c, s = math.cos(h[k]), math.sin(h[k])
        cap = (None, 2.0, 5.0)[k % 3]
        vx, vy = drive_command(px[k], py[k], c, s, tx[k], ty[k], 3.0, 4.0, cap)
        omega = turn_command(c, s, face[k], 10.0)
        got = command(3.0, 4.0, 10.0, px[k], py[k], c, s, tx[k], ty[k], face[k],
                      math.inf if cap is None else cap, 0.5, -1.0)
        assert got == (vx / 3.0, vy / 3.0, omega, 0.5, -1.0, -1.0)


def test_roll_kernel_is_the_friction_ball_model_bit_for_bit():
    """attack.roll: FrictionBallModel.predict's position of a moving ball, bit for bit
    (before and after the ball stops)."""
    rng = np.random.default_rng(7)
    model = FrictionBallModel(0.3)
    for _ in range(3000):
        state = np.concatenate([rng.uniform(-4.0, 4.0, 2), rng.normal(0.0, 2.0, 2)])
        dt = float(rng.uniform(0.0, 12.0))
        x, y = (float(v) for v in model.predict(state, dt)[0:2])
        assert roll(0.3, *state.tolist(), dt) == (x, y)


def test_role_kernel_ranks_like_sorting_the_defenders():
    """roles.role: the attacker of least cost, the others ranked within their line of three
    by (lateral position, index), as sorting each line gives; a barred robot never
    attacks."""
    env = soccer_env.parallel_env(blue=6, yellow=1)
    team = ScriptedTeam.for_env(env, "blue")
    g = team.geometry
    rng = np.random.default_rng(8)
    for _ in range(300):
        xs, ys = rng.uniform(-4.0, 4.0, 6), rng.uniform(-3.0, 3.0, 6)
        bx, by = rng.uniform(-4.0, 4.0, 2)
        barred = int(rng.integers(-1, 6))
        roles = [team.roles.role(i, xs.tolist(), ys.tolist(), bx, by, barred)
                 for i in range(1, 6)]
        attackers = [i for i, r in zip(range(1, 6), roles) if r[0] == "attacker"]
        assert len(attackers) == 1 and attackers[0] != barred
        defenders = [i for i in range(1, 6) if i != attackers[0]]
        fx, fy = bx + g.goal_x, by
        norm = math.hypot(fx, fy) or 1.0
        nx, ny = -fy / norm, fx / norm
        for start in range(0, len(defenders), 3):
            line = sorted(defenders[start:start + 3],
                          key=lambda k: ((xs[k] + g.goal_x) * nx + ys[k] * ny, k))
            for slot, k in enumerate(line):
                assert roles[k - 1] == ("defender", start + slot, len(defenders))
