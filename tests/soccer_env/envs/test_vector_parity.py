"""The batched tasks (``make_vec(..., vectorization_mode="vector_entry_point")``) answer as
Gymnasium's ``SyncVectorEnv`` of the same single environments (``vectorization_mode="sync"``)
in everything a client reads: observations, rewards, terminations, truncations and infos
(every key, mask, dtype and value, nested dicts included; full and flat), in each autoreset
mode, through resets with a ``reset_mask`` and every way of seeding, in truth and perceived
modes. The batched match (:class:`~soccer_env.envs.batched_match.MatchBatch`, not a
Gymnasium vector environment) gives every match's per-agent infos as its single
``SoccerParallelEnv`` does.

Each world runs in a space of its own here (``SHARD_SIZE = 1``): in a shared space a world's
coordinates are offset by its patch's origin and round differently in the last bits
(:mod:`soccer_env.sim.batch`), which the infos' float64 truth would show; apart, the batch's
physics is the single worlds' bit for bit, and so is every return.
"""

from __future__ import annotations

from typing import Any

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.vector import AutoresetMode

import soccer_env
import soccer_env.perception.batched as perception_batch
import soccer_env.sim.batch as world_batch
from soccer_env.envs.batched import GoalkeeperVectorEnv, ShootoutVectorEnv
from soccer_env.envs.batched_match import MatchBatch
from soccer_env.envs.flat_info import EVENT_CODES

GK, SO = "soccer_env/Goalkeeper-v0", "soccer_env/Shootout-v0"
NEXT, SAME, OFF = AutoresetMode.NEXT_STEP, AutoresetMode.SAME_STEP, AutoresetMode.DISABLED
SHAPING = {"intercept": 2.0, "ball_distance": 0.5, "action_cost": 0.1, "outside_area": 1.0}


def assert_same(ours: Any, theirs: Any, path: str = "info") -> None:
    """``ours`` equals ``theirs`` exactly: dicts with the same keys, arrays of the same dtype
    and shape and equal values (object arrays element by element), other values of the same
    type and equal."""
    if isinstance(theirs, dict):
        assert isinstance(ours, dict), f"{path}: {type(ours).__name__}, not a dict"
        assert set(ours) == set(theirs), f"{path}: keys differ: {set(ours) ^ set(theirs)}"
        for key, value in theirs.items():
            assert_same(ours[key], value, f"{path}[{key!r}]")
    elif isinstance(theirs, np.ndarray):
        assert isinstance(ours, np.ndarray), f"{path}: {type(ours).__name__}, not an array"
        assert (ours.dtype, ours.shape) == (theirs.dtype, theirs.shape), (
            f"{path}: {ours.dtype}{ours.shape} against {theirs.dtype}{theirs.shape}")
        if theirs.dtype == object:
            for k, (a, b) in enumerate(zip(ours.tolist(), theirs.tolist())):
                assert_same(a, b, f"{path}[{k}]")
        else:
            np.testing.assert_array_equal(ours, theirs, err_msg=path, strict=True)
    elif isinstance(theirs, tuple):
        assert type(ours) is tuple and len(ours) == len(theirs), f"{path}: {ours!r}"
        for k, (a, b) in enumerate(zip(ours, theirs)):
            assert_same(a, b, f"{path}[{k}]")
    else:
        assert type(ours) is type(theirs) and ours == theirs, f"{path}: {ours!r} != {theirs!r}"


def assert_same_returns(ours: tuple, theirs: tuple, what: str) -> None:
    """Two ``step`` (or ``reset``) returns are the same, the infos last."""
    for a, b, name in zip(ours[:-1], theirs[:-1], ("obs", "rewards", "terminated",
                                                   "truncated")):
        np.testing.assert_array_equal(a, b, err_msg=f"{what}: {name}", strict=True)
    assert_same(ours[-1], theirs[-1], f"{what}: info")


def pair(env_id: str, n: int, mode: AutoresetMode, **kwargs: Any) -> tuple[Any, Any]:
    """The batch and the ``SyncVectorEnv`` of ``n`` single environments, same arguments."""
    ours = gym.make_vec(env_id, num_envs=n, vectorization_mode="vector_entry_point",
                        autoreset_mode=mode, **kwargs)
    theirs = gym.make_vec(env_id, num_envs=n, vectorization_mode="sync",
                          vector_kwargs={"autoreset_mode": mode}, **kwargs)
    assert isinstance(ours.unwrapped, (GoalkeeperVectorEnv, ShootoutVectorEnv))
    return ours, theirs


def random_actions(rng: np.random.Generator, obs: np.ndarray, attack: bool) -> np.ndarray:
    """Random actions for the observations ``obs`` ``(n, d)``; ``attack``: a Shootout
    attacker's, driving at the ball (its body-frame offset, entries 7 and 8) and kicking,
    with noise, so that it scores, misses and gets saved."""
    n = len(obs)
    actions = rng.uniform(-1.0, 1.0, (n, 6))
    if attack:
        actions[:, 0:3] *= 0.2
        actions[:, 0:2] += np.clip(20.0 * obs[:, 7:9], -1.0, 1.0)
        actions[:, 3] = 1.0
        actions[:, 4:6] = 0.0
    return np.clip(actions, -1.0, 1.0).astype(np.float32)


def run_side_by_side(env_id: str, mode: AutoresetMode, steps: int, n: int = 4,
                     seed: int = 7, **kwargs: Any) -> dict[str, Any]:
    """Step the batch and the ``SyncVectorEnv`` with the same random actions (attacking ones
    for the Shootout) for ``steps`` steps, every return compared; every 37th step (and,
    autoreset off, whenever an episode has ended) some environments reset with a
    ``reset_mask`` and seeds drawn as an int, a list with Nones, or None. Returns how many
    episodes ended, the outcomes seen and how many masked resets ran."""
    ours, theirs = pair(env_id, n, mode, **kwargs)
    rng = np.random.default_rng(seed)
    obs = theirs.reset(seed=seed)
    assert_same_returns(ours.reset(seed=seed), obs, "reset")
    obs = obs[0]
    ended = np.zeros(n, dtype=bool)
    counts: dict[str, Any] = {"ends": 0, "masked resets": 0, "outcomes": set()}
    for t in range(steps):
        if t % 37 == 36 or (mode == OFF and ended.any()):
            mask = rng.random(n) < 0.4
            if mode == OFF:
                mask |= ended
            if not mask.any():
                mask[rng.integers(n)] = True
            seeds = [int(rng.integers(1000)), None,
                     [int(s) if rng.random() < 0.5 else None
                      for s in rng.integers(0, 1000, n)]][t % 3]
            other = theirs.reset(seed=seeds, options={"reset_mask": mask.copy()})
            assert_same_returns(ours.reset(seed=seeds, options={"reset_mask": mask.copy()}),
                                other, f"masked reset before step {t}")
            obs = other[0]
            counts["masked resets"] += 1
            ended &= ~mask
        actions = random_actions(rng, obs, env_id == SO)
        mine, other = ours.step(actions), theirs.step(actions)
        obs = other[0]
        assert_same_returns(mine, other, f"step {t}")
        ended = other[2] | other[3]
        counts["ends"] += int(ended.sum())
        finished = other[4].get("final_info", other[4])  # (SAME_STEP: the finished episodes')
        counts["outcomes"].update(finished["outcome"][other[2]].tolist())
    ours.close()
    theirs.close()
    return counts


@pytest.fixture(autouse=True)
def apart(monkeypatch):
    """Every world of a batch in a space of its own (see the module docstring)."""
    monkeypatch.setattr(world_batch, "SHARD_SIZE", 1)


@pytest.mark.parametrize("env_id,mode,kwargs,batched_vision", [
    (GK, NEXT, {"max_episode_steps": 50}, False),
    (GK, SAME, {"max_episode_steps": 50, "info_mode": "flat", "shaping": SHAPING}, False),
    (GK, OFF, {"max_episode_steps": 50, "obs_mode": "perceived"}, False),
    (GK, SAME, {"max_episode_steps": 50, "obs_mode": "perceived", "perception": "ssl-2012"},
     True),
    (GK, OFF, {"max_episode_steps": 50, "obs_mode": "perceived", "perception": "ssl-2012",
               "info_mode": "flat"}, True),
    (SO, NEXT, {"max_episode_steps": 80, "obs_mode": "perceived", "info_mode": "flat",
                "shaping": {"ball_progress": 1.0, "ball_distance": 0.5, "action_cost": 0.1}},
     False),
    (SO, SAME, {"max_episode_steps": 80}, False),
    (SO, OFF, {"max_episode_steps": 80, "obs_mode": "perceived", "perception": "ssl-2012"},
     True),
    (SO, NEXT, {"max_episode_steps": 80, "obs_mode": "perceived"}, True),
])
def test_the_batch_returns_what_sync_vector_env_returns(env_id, mode, kwargs, batched_vision,
                                                        monkeypatch):
    """Goalkeeper and Shootout, each autoreset mode, truth and perceived (each environment's
    own pipeline, and the batched one), full and flat infos; short time limits so that
    episodes end and restart often."""
    if batched_vision:  # the batched pipeline, which runs from 48 environments by default
        monkeypatch.setattr(perception_batch, "MIN_BATCH", 1)
    counts = run_side_by_side(env_id, mode, steps=200, **kwargs)
    assert counts["ends"] >= 4 and counts["masked resets"] >= 5 and counts["outcomes"]


def assert_same_layout(ours: Any, theirs: Any, path: str = "info") -> None:
    """``ours`` is laid out as ``theirs``: the same keys, masks, dtypes and shapes."""
    if isinstance(theirs, dict):
        assert set(ours) == set(theirs), f"{path}: keys differ: {set(ours) ^ set(theirs)}"
        for key, value in theirs.items():
            if key.startswith("_"):
                assert_same(ours[key], value, f"{path}[{key!r}]")
            else:
                assert_same_layout(ours[key], value, f"{path}[{key!r}]")
    elif isinstance(theirs, np.ndarray):
        assert (ours.dtype, ours.shape) == (theirs.dtype, theirs.shape), path


def test_humanoid_keepers_infos_as_sync_vector_env():
    """A humanoid keeper with its team-mates: ``robot_state`` too. The infos are laid out as
    ``SyncVectorEnv``'s, and what the physics and the rules give is equal; the batch's
    humanoid heads (``robot_state``'s ``pan``, ``tilt``, ``sway``), and with them what the
    robots see (``estimate``, observations), part from the single environments' in the
    last digits after a while (their head control and cameras run per environment)."""
    ours, theirs = pair(GK, 3, NEXT, robot="humanoid", max_episode_steps=15)
    rng = np.random.default_rng(2)
    a, b = ours.reset(seed=2), theirs.reset(seed=2)
    assert_same(a[1], b[1], "reset")
    ends = 0
    for t in range(40):
        actions = rng.uniform(-1.0, 1.0, (3, 6)).astype(np.float32)
        a, b = ours.step(actions), theirs.step(actions)
        for x, y in zip(a[1:4], b[1:4]):
            np.testing.assert_array_equal(x, y, strict=True)
        assert_same_layout(a[4], b[4], f"step {t}")
        for key in ("truth", "reward_terms", "outcome", "shot", "shot_fired",
                    "keeper_touched", "is_success"):
            if key in b[4]:
                assert_same(a[4][key], b[4][key], f"step {t}: {key}")
        for name in ("fallen", "kicking", "odometry", "falls", "kicks"):
            assert_same(a[4]["robot_state"]["blue_0"][name],
                        b[4]["robot_state"]["blue_0"][name], f"step {t}: {name}")
        ends += int((b[2] | b[3]).sum())
    assert ends >= 6


def test_reset_mask_resets_only_those_environments():
    env = GoalkeeperVectorEnv(3, max_episode_steps=30)
    first, _ = env.reset(seed=0)
    stepped = env.step(np.zeros((3, 6)))[0]
    obs, info = env.reset(seed=5, options={"reset_mask": np.array([False, True, False])})
    np.testing.assert_array_equal(obs[[0, 2]], stepped[[0, 2]])
    fresh, _ = GoalkeeperVectorEnv(3).reset(seed=5)
    np.testing.assert_array_equal(obs[1], fresh[1])  # seeded seed + k, as SyncVectorEnv
    assert info["_truth"].tolist() == [False, True, False]
    assert info["outcome"].tolist() == [None, "", None]
    for bad, error in [([True, False, True], TypeError), (np.ones(2, bool), ValueError),
                       (np.ones(3), TypeError), (np.zeros(3, bool), ValueError)]:
        with pytest.raises(error, match="reset_mask"):
            env.reset(options={"reset_mask": bad})
    with pytest.raises(ValueError, match="takes no options"):
        env.reset(options={"reset_mask": np.ones(3, bool), "shots": 1})


def test_autoreset_disabled_waits_for_a_masked_reset():
    env = GoalkeeperVectorEnv(2, max_episode_steps=3, autoreset_mode="Disabled")
    assert env.metadata["autoreset_mode"] == OFF
    env.reset(seed=1)
    for _ in range(3):
        _, _, terminated, truncated, _ = env.step(np.zeros((2, 6)))
    assert (terminated | truncated).all()
    with pytest.raises(RuntimeError, match=r"environments \[0, 1\] have ended"):
        env.step(np.zeros((2, 6)))
    obs, info = env.reset(options={"reset_mask": np.array([True, False])})
    assert info["_truth"].tolist() == [True, False]
    with pytest.raises(RuntimeError, match=r"environments \[1\] have ended"):
        env.step(np.zeros((2, 6)))
    env.reset(options={"reset_mask": np.array([False, True])})
    _, rewards, terminated, truncated, info = env.step(np.zeros((2, 6)))
    assert not (terminated | truncated).any() and info["outcome"].tolist() == ["", ""]


@pytest.mark.parametrize("mode", [SAME, "Disabled"])
def test_the_sync_fallback_takes_the_vector_arguments(mode):
    """Where the batch falls back to single environments (rendering), ``autoreset_mode`` goes
    to the ``SyncVectorEnv`` and the task's arguments to ``gymnasium.make``."""
    with pytest.warns(UserWarning, match="SyncVectorEnv: the batched Goalkeeper does not "
                                         "render"):
        env = gym.make_vec(GK, num_envs=2, vectorization_mode="vector_entry_point",
                           autoreset_mode=mode, render_mode="rgb_array", render_width=64,
                           max_episode_steps=5)
    assert isinstance(env, gym.vector.SyncVectorEnv)
    assert env.autoreset_mode == AutoresetMode(mode) == env.metadata["autoreset_mode"]
    env.reset(seed=0)
    for _ in range(5):
        truncated = env.step(np.zeros((2, 6), np.float32))[3]
    assert truncated.all()
    env.close()


def throw(world: Any, k: int) -> None:
    """Send match ``k``'s ball towards the yellow goal (0), past it over the goal line (1)
    or over a touch line (2), from 0.3 m inside the line."""
    f = world.field
    x, y, vx, vy = [(f.half_length - 0.3, 0.0, 3.0, 0.0),
                    (f.half_length - 0.3, 0.5 * f.goal_width + 0.4, 3.0, 0.0),
                    (0.5, f.half_width - 0.3, 0.0, 3.0)][k % 3]
    world.set_ball(x, y, vx, vy)


@pytest.mark.parametrize("kwargs,batched_vision", [
    ({"blue": 2, "yellow": 2, "match_duration": 1.0,
      "shaping": {"ball_progress": 1.0, "ball_distance": 0.5}}, False),
    ({"blue": 1, "yellow": 2, "max_cycles": 50, "obs_mode": "perceived", "info_mode": "flat"},
     False),
    ({"blue": 2, "yellow": 1, "match_duration": 1.0, "obs_mode": "perceived",
      "perception": "ssl-2012", "field": "ssl-2012"}, True),
])
def test_the_batched_match_infos_are_the_parallel_envs(kwargs, batched_vision, monkeypatch):
    """``MatchBatch.infos()`` after a reset and ``step(..., infos=True)`` equal the single
    matches' infos (full and flat, truth and perceived), through goals, outs and restarts;
    ``infos()`` after a step that ended a match gives the next match's reset infos."""
    if batched_vision:
        monkeypatch.setattr(perception_batch, "MIN_BATCH", 1)
    n = 3
    batch = MatchBatch(n, **kwargs)
    singles = [soccer_env.parallel_env(**kwargs) for _ in range(n)]
    agents = singles[0].possible_agents
    batch.reset(seed=4)
    for k, (ours, single) in enumerate(zip(batch.infos(), singles)):
        assert_same(ours, single.reset(seed=4 + k)[1], f"reset {k}")
    rng = np.random.default_rng(4)
    events, ends = set(), 0
    for t in range(100):
        if t % 20 == 5:
            for k, single in enumerate(singles):
                throw(batch.batch.worlds[k], k)
                throw(single.world, k)
        actions = rng.uniform(-1.0, 1.0, (n, len(agents), 6)).astype(np.float32)
        step = batch.step(actions, infos=True)
        now = batch.infos()
        for k, single in enumerate(singles):
            _, _, terminated, truncated, info = single.step(dict(zip(agents, actions[k])))
            assert_same(step.infos[k], info, f"step {t}, match {k}")
            events.add(info[agents[0]]["event"])
            if terminated[agents[0]] or truncated[agents[0]]:
                ends += 1
                info = single.reset()[1]
            assert_same(now[k], info, f"after step {t}, match {k}")
    assert ends >= 3
    names = ("", "goal", "goal_line", "touch")
    flat = [float(EVENT_CODES[name]) for name in names]
    assert set(flat if kwargs.get("info_mode") == "flat" else names) <= events
