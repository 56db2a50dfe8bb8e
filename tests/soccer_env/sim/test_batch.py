"""WorldBatch: many worlds in one space behave as the same worlds stepped apart (to rounding:
each world's coordinates are offset by its patch), never touch each other, and restart one at a
time."""

from __future__ import annotations

import copy
import pickle

import numpy as np
import pytest

from soccer_env import presets
from soccer_env.sim.batch import WorldBatch
from soccer_env.sim.world import World

FIELD = presets.field("ssl-div-b")
BALL, ROBOT = presets.ball(FIELD.ball), presets.robot("ssl")


def _poses(n: int, robots: int) -> np.ndarray:
    xs = np.linspace(-3.0, 3.0, robots)
    return np.stack([np.column_stack([xs, np.full(robots, 0.2 * k - 0.5),
                                      np.linspace(0.0, np.pi, robots)]) for k in range(n)])


def _pair(n: int, n_blue: int, n_yellow: int, shard_size: int | None = None
          ) -> tuple[WorldBatch, list[World]]:
    poses, balls = _poses(n, n_blue + n_yellow), np.array([[0.1 * k, 0.05] for k in range(n)])
    batch = WorldBatch(n, FIELD, BALL, ROBOT, n_blue, n_yellow, shard_size=shard_size)
    batch.reset(poses, balls)
    apart = [World(FIELD, BALL, ROBOT, n_blue, n_yellow) for _ in range(n)]
    for w, p, b in zip(apart, poses, balls):
        w.reset(p, tuple(b))
    return batch, apart


def _commands(rng: np.random.Generator, steps: int, n: int, robots: int) -> np.ndarray:
    c = rng.uniform(-1.5, 1.5, (steps, n, robots, 6))
    c[..., 3] = np.where(rng.random((steps, n, robots)) < 0.2, 5.0, 0.0)  # armed kickers
    c[..., 4] = rng.random((steps, n, robots)) < 0.3  # some of them chips
    c[..., 5] = rng.random((steps, n, robots)) < 0.2  # dribblers
    return c


@pytest.mark.parametrize("n_blue,n_yellow,shard_size", [(1, 0, None), (1, 1, None),
                                                         (1, 1, 3)])
def test_a_batch_steps_as_the_same_worlds_apart(n_blue, n_yellow, shard_size):
    """Kicks, chips (flight and bounces), dribbling, the sliding-to-rolling switch and ball
    exits happen at the same steps; positions and velocities agree to rounding. With a
    shard size of 3, the four worlds lie in two spaces."""
    n, robots = 4, n_blue + n_yellow
    batch, apart = _pair(n, n_blue, n_yellow, shard_size)
    assert len(batch.spaces) == (1 if shard_size is None else 2)
    for k in range(n):  # robot 0 just behind the ball, facing it
        for w in (batch.worlds[k], apart[k]):
            w.set_robot(0, 0.1 * k - 0.12, 0.05, 0.0)
    commands = _commands(np.random.default_rng(1), 240, n, robots)
    commands[:20, :, 0] = [0.4, 0.0, 0.0, 5.0, 0.0, 0.0]  # up to the ball, kick...
    commands[:20, 1::2, 0, 4] = 1.0  # ... chipped in every other world
    events = 0
    for t, c in enumerate(commands):
        batch.step(c)
        for w, ck in zip(apart, c):
            w.step(ck)
        for k in range(n):
            b, a = batch.worlds[k], apart[k]
            assert b.kicked == a.kicked and b.touched == a.touched, (t, k)
            assert batch.touched()[k].tolist() == a.touched and batch.times[k] == a.time
            assert (b.ball_airborne, b.ball_sliding) == (a.ball_airborne, a.ball_sliding), (t, k)
            assert (b.ball_exit is None) == (a.ball_exit is None), (t, k)
            np.testing.assert_allclose(b.robot_array(), a.robot_array(), atol=1e-9)
            np.testing.assert_allclose(b.ball_array(), a.ball_array(), atol=1e-9)
            assert b.time == a.time
            events += sum(b.kicked) + b.ball_airborne
    assert events > 0  # the run exercised the kicker and the flight
    for k in range(n):  # the batch's state array is every world's state
        np.testing.assert_array_equal(batch.state[k, 1:], batch.worlds[k].robot_array())


def test_worlds_never_touch_each_other():
    """Robots of world 0 driven into its walls at full speed, the others idle: nothing of
    world 0 reaches its neighbours, whose robots and balls stay exactly where they were."""
    batch = WorldBatch(4, FIELD, BALL, ROBOT, 2, 0)
    wx = FIELD.half_length + FIELD.boundary - 0.2
    poses = np.array([[[wx, 0.0, 0.0], [-wx, 0.0, np.pi]]] * 4)
    batch.reset(poses, np.zeros((4, 2)))
    batch.worlds[0].set_ball(0.0, 0.0, 6.0, 4.0)
    before = batch.state[1:].copy()
    c = np.zeros((4, 2, 6))
    c[0, :, 0] = 5.0
    for _ in range(120):
        batch.step(c)
    np.testing.assert_array_equal(batch.state[1:], before)
    # World 0's robots stay inside their own walls.
    assert np.all(np.abs(batch.state[0, 1:, 0]) < FIELD.half_length + FIELD.boundary)


def test_restart_starts_one_world_and_leaves_the_others():
    batch, _ = _pair(3, 1, 0)
    c = np.zeros((3, 1, 6))
    c[:, :, 0] = 1.0
    for _ in range(30):
        batch.step(c)
    moved = batch.state.copy()
    batch.restart(1, np.array([[0.5, 0.5, 0.0]]), (1.0, -1.0))
    assert batch.worlds[1].time == 0.0 and batch.worlds[0].time == pytest.approx(0.5)
    np.testing.assert_array_equal(batch.state[1, 1], [0.5, 0.5, 0.0, 0.0, 0.0, 0.0])
    np.testing.assert_array_equal(batch.state[1, 0], [1.0, -1.0, 0.0, 0.0, 0.0, 0.0])
    np.testing.assert_array_equal(batch.state[[0, 2]], moved[[0, 2]])
    batch.step(c)
    assert batch.worlds[1].time == pytest.approx(1 / 60)


def test_bad_input_names_the_argument():
    with pytest.raises(ValueError, match=r"n_worlds must be an integer in 1..65536, got 0"):
        WorldBatch(0, FIELD, BALL, ROBOT, 1, 0)
    with pytest.raises(ValueError, match="rngs must hold 2 generators"):
        WorldBatch(2, FIELD, BALL, ROBOT, 1, 0).reset(np.zeros((2, 1, 3)), np.zeros((2, 2)),
                                                      [np.random.default_rng(0)])
    batch = WorldBatch(2, FIELD, BALL, ROBOT, 1, 0)
    with pytest.raises(RuntimeError, match="reset"):
        batch.step(np.zeros((2, 1, 6)))
    with pytest.raises(ValueError, match=r"robot_poses must have shape \(2, 1, 3\)"):
        batch.reset(np.zeros((2, 3)), np.zeros((2, 2)))
    with pytest.raises(ValueError, match=r"ball_positions must have shape \(2, 2\)"):
        batch.reset(np.zeros((2, 1, 3)), np.zeros(2))
    with pytest.raises(ValueError, match="position must be finite and inside the walls"):
        batch.reset(np.full((2, 1, 3), 50.0), np.zeros((2, 2)))
    batch.reset(np.zeros((2, 1, 3)) + [[[1.0, 0.0, 0.0]]], np.zeros((2, 2)))
    with pytest.raises(ValueError, match=r"commands must have shape \(2, 1, 6\)"):
        batch.step(np.zeros((2, 6)))


@pytest.mark.parametrize("robots", [("humanoid", "humanoid"), ("ssl", "humanoid")])
def test_humanoids_step_in_the_batch_as_in_worlds_apart(robots):
    """Humanoids' walks and kicks (foot strikes; two humanoids, the ball at the blue one's
    feet), falls after an SSL robot's impacts with their lying bodies and getting up (the
    ball far away), and the restart of a world whose robot lies: the same events at the same
    steps as separate worlds, positions to rounding. (A ball squeezed between two robots
    can come out differently: the shared space may order the contacts differently.)"""
    field = presets.field("humanoid-kid")
    ball = presets.ball(field.ball)
    specs = [presets.robot(r) for r in robots]
    ramming = robots[0] == "ssl"
    n = 3
    poses = np.array([[[-0.3 - 0.1 * k, 0.0, 0.0], [0.3, 0.05 * k, np.pi]] for k in range(n)])
    balls = np.array([[2.0, 2.0 - 0.1 * k] if ramming else [-0.12 - 0.1 * k, 0.0]
                      for k in range(n)])
    batch = WorldBatch(n, field, ball, specs, 1, 1)
    batch.reset(poses, balls, [np.random.default_rng(k) for k in range(n)])
    apart = [World(field, ball, specs, 1, 1) for _ in range(n)]
    for k, (w, p, b) in enumerate(zip(apart, poses, balls)):
        w.reset(p, tuple(b), np.random.default_rng(k))
    rng = np.random.default_rng(4)
    falls = kicks = lying = 0
    for t in range(400):
        c = np.zeros((n, 2, 6))
        for k in range(n):
            for i, spec in enumerate(specs):
                if spec.kind == "humanoid":  # walk at the other robot, kick now and then
                    c[k, i, :3] = (0.3, rng.uniform(-0.1, 0.1), rng.uniform(-0.5, 0.5))
                    c[k, i, 3] = 3.0 if rng.random() < 0.05 else 0.0
                else:  # ram the humanoid
                    c[k, i, :3] = (1.5, 0.0, rng.uniform(-2, 2))
        if t == 250:  # restart world 1 (ramming: its humanoid lies, grounded)
            p1 = np.array([[-0.5, 0.2, 0.0], [0.5, -0.2, np.pi]])
            batch.restart(1, p1, (0.0, 0.0), np.random.default_rng(9))
            apart[1].reset(p1, (0.0, 0.0), np.random.default_rng(9))
        batch.step(c)
        for w, ck in zip(apart, c):
            w.step(ck)
        for k in range(n):
            b, a = batch.worlds[k], apart[k]
            assert b.walk.fallen == a.walk.fallen and b.kicked == a.kicked, (t, k)
            assert b.touched == a.touched and batch.times[k] == a.time, (t, k)
            assert len(b._lying) == len(a._lying), (t, k)
            np.testing.assert_allclose(b.robot_array(), a.robot_array(), atol=1e-9)
            np.testing.assert_allclose(b.ball_array(), a.ball_array(), atol=1e-9)
            falls += sum(b.walk.fallen)
            kicks += sum(b.kicked)
            lying += len(b._lying)
    if ramming:
        assert falls > 0 and lying > 0  # robots fell, lay and got up
    else:
        assert kicks > 0


@pytest.mark.parametrize("copier", ["deepcopy", "pickle"])
def test_a_copied_batch_steps_as_the_original(copier):
    """A batch of five worlds in three spaces (shard size 2), copied mid-run (kicks, chips,
    dribbling, robots pushing each other): original and copy step identically, bit for bit,
    through a world's restart; the copy's worlds are views of its own state, its spaces its
    own, its collision handlers bound to it."""
    n, robots = 5, 3
    batch, _ = _pair(n, 2, 1, shard_size=2)
    commands = _commands(np.random.default_rng(2), 300, n, robots)
    for c in commands[:100]:
        batch.step(c)
    twin = copy.deepcopy(batch) if copier == "deepcopy" else pickle.loads(pickle.dumps(batch))
    assert len(twin.spaces) == 3 and not set(map(id, twin.spaces)) & set(map(id, batch.spaces))
    for k, w in enumerate(twin.worlds):
        assert np.shares_memory(w.robot_array(), twin.state[k])
        assert w.space is twin.spaces[k // 2]
    for t, c in enumerate(commands[100:]):
        if t == 50:
            for b in (batch, twin):
                b.restart(3, np.array([[0.5, 0.5, 0.0], [-0.5, 0.5, 0.0], [1.0, -1.0, np.pi]]),
                          (0.0, 0.2))
        batch.step(c)
        twin.step(c)
        np.testing.assert_array_equal(twin.state, batch.state, err_msg=f"step {t}")
        np.testing.assert_array_equal(twin.touched(), batch.touched(), err_msg=f"step {t}")
        np.testing.assert_array_equal(twin.times, batch.times)
        assert [k for k, _ in twin.exits()] == [k for k, _ in batch.exits()], t
