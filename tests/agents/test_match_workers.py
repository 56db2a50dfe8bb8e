"""MatchWorkerVecEnv: the match VecEnv with its matches in worker processes gives the same
batches as the in-process one whatever the number of workers, keeps the VecEnv contract
(opponents, self-play, attributes), and fails fast."""

from __future__ import annotations

import os
import signal

import numpy as np
import pytest

pytest.importorskip("stable_baselines3")

from stable_baselines3 import PPO  # noqa: E402

from agents.policies import NumpyPolicy  # noqa: E402
from agents.sb3.policies import SB3Policy  # noqa: E402
from agents.vec.factories import make_match_vec_env  # noqa: E402
from agents.vec.match import MatchVecEnv  # noqa: E402
from agents.vec.match_workers import MatchWorkerVecEnv  # noqa: E402
from agents.vec.self_play import SelfPlayCallback  # noqa: E402
from agents.vec.workers import WorkerError  # noqa: E402

#: Short 2 vs 2 matches (24 control steps), so that runs cross match ends and resets.
SHORT = {"blue": 2, "yellow": 2, "match_duration": 0.4}


pytestmark = pytest.mark.usefixtures("one_torch_thread")


def _run(venv, steps: int, seed: int = 0) -> list:
    """Everything the VecEnv returns over ``steps`` random steps."""
    rng = np.random.default_rng(seed)
    out = [venv.reset()]
    for _ in range(steps):
        obs, rewards, dones, infos = venv.step(
            rng.uniform(-1, 1, (venv.num_envs, 6)).astype(np.float32))
        out += [obs, rewards, dones, infos]
    return out


def _same(a, b) -> None:
    if isinstance(a, dict):
        assert a.keys() == b.keys()
        for k in a:
            _same(a[k], b[k])
    elif isinstance(a, (list, tuple)):
        assert len(a) == len(b)
        for x, y in zip(a, b):
            _same(x, y)
    elif isinstance(a, np.ndarray):
        assert a.dtype == b.dtype and np.array_equal(a, b)
    else:
        assert a == b


def _strip_times(batches: list) -> list:
    """The episode's wall-clock time differs between runs: drop it."""
    for item in batches:
        if isinstance(item, list):
            for info in item:
                if isinstance(info, dict) and "episode" in info:
                    info["episode"] = {k: v for k, v in info["episode"].items() if k != "t"}
    return batches


@pytest.mark.parametrize("learner,opponent", [("blue", "scripted"), ("both", None)])
def test_results_do_not_depend_on_the_number_of_workers(learner, opponent):
    runs = {}
    for workers in (0, 1, 3):
        venv = make_match_vec_env(SHORT, n_matches=5, learner=learner, opponent=opponent,
                                  seed=7, workers=workers)
        try:
            runs[workers] = _strip_times(_run(venv, 60))
        finally:
            venv.close()
    assert isinstance(venv, MatchWorkerVecEnv) and venv.workers == 3
    _same(runs[0], runs[1])
    _same(runs[0], runs[3])
    ends = sum(int(d.sum()) for d in runs[3][3::4])
    assert ends >= 10  # the runs crossed match ends (auto-reset, terminal observations)


def test_opponent_pool_draws_do_not_depend_on_the_number_of_workers():
    rng = np.random.default_rng(0)
    probe = MatchVecEnv(SHORT, n_matches=1)
    size = probe.observation_space.shape[0]
    probe.close()
    pool = [NumpyPolicy([("linear", rng.normal(0, 0.3, (6, size)), np.zeros(6))], "clip",
                        -np.ones(6), np.ones(6)) for _ in range(3)]
    runs = []
    for workers in (0, 2):
        venv = make_match_vec_env(SHORT, n_matches=4, learner="blue", opponent="idle",
                                  seed=3, workers=workers)
        try:
            venv.set_opponent_pool(pool)
            batches = _strip_times(_run(venv, 80))
            drawn = [next(i for i, p in enumerate(pool) if np.array_equal(
                p.layers[0][1], o.layers[0][1])) for o in venv.opponents]
            runs.append((batches, drawn))
        finally:
            venv.close()
    _same(runs[0][0], runs[1][0])
    assert runs[0][1] == runs[1][1]


def test_attributes_methods_and_images_reach_each_entrys_match():
    venv = make_match_vec_env({**SHORT, "render_mode": "rgb_array", "render_width": 160},
                              n_matches=3, learner="blue", seed=0, workers=2)
    try:
        venv.reset()
        assert venv.num_envs == 6 and venv.entry_agents[2] == (1, "blue_0")
        assert venv.get_attr("match_duration") == [0.4] * 6
        venv.set_attr("match_duration", 9.0, indices=[2])
        assert venv.get_attr("match_duration") == [0.4, 0.4, 9.0, 9.0, 0.4, 0.4]
        states = venv.env_method("state", indices=[0, 5])
        assert len(states) == 2 and states[0].shape == states[1].shape
        images = venv.get_images()
        assert len(images) == 3 and images[0].ndim == 3
        assert venv.has_attr("score") and not venv.has_attr("no_such_attribute")
        with pytest.raises(IndexError, match="batch entry 6 out of range 0..5"):
            venv.get_attr("score", indices=[6])
    finally:
        venv.close()


def test_self_play_across_worker_processes():
    venv = make_match_vec_env(SHORT, n_matches=2, learner="blue", opponent="idle", seed=0,
                              workers=2)
    try:
        model = PPO("MlpPolicy", venv, n_steps=32, batch_size=64, n_epochs=1, seed=0)
        callback = SelfPlayCallback(update_every=64, pool_size=2)
        model.learn(256, callback=callback)
        assert callback.n_updates >= 3 and model.num_timesteps >= 256
        opponents = venv.opponents
        assert len(opponents) == 2 and all(isinstance(o, NumpyPolicy) for o in opponents)
        # The workers hold copies of the callback's pool (the learner at two updates).
        pool = venv.opponent_pool
        assert len(pool) == 2
        for ours, theirs in zip(callback.pool, pool):
            assert np.array_equal(ours.layers[0][1], theirs.layers[0][1])
    finally:
        venv.close()


def test_a_live_model_opponent_is_refused_and_a_lambda_is_carried():
    venv = make_match_vec_env(SHORT, n_matches=2, learner="blue", opponent="idle", seed=0,
                              workers=2)
    try:
        model = PPO("MlpPolicy", venv, n_steps=32, batch_size=64, seed=0)
        with pytest.raises(ValueError, match="live stable-baselines3 model"):
            venv.set_opponent(SB3Policy(model))
        venv.set_opponent(lambda obs: np.full((len(obs), 6), 0.5, np.float32))
        venv.reset()
        venv.step(np.zeros((venv.num_envs, 6), np.float32))
    finally:
        venv.close()


def test_bad_actions_leave_every_match_as_it_was():
    venv = make_match_vec_env(SHORT, n_matches=2, learner="blue", seed=0, workers=2)
    try:
        venv.reset()
        before = venv.env_method("state")
        bad = np.zeros((venv.num_envs, 6), np.float32)
        bad[3, 0] = np.nan
        with pytest.raises(ValueError, match="blue_1 of match 1"):
            venv.step(bad)
        with pytest.raises(ValueError, match=r"actions must have shape \(4, 6\)"):
            venv.step(np.zeros((3, 6), np.float32))
        _same(venv.env_method("state"), before)
        venv.step(np.zeros((venv.num_envs, 6), np.float32))
    finally:
        venv.close()
    with pytest.raises(ValueError, match="workers must be an integer >= 0, got -1"):
        make_match_vec_env(SHORT, workers=-1)
    with pytest.raises(ValueError, match="learner must be one of"):
        make_match_vec_env(SHORT, learner="red", workers=2)


def test_a_match_that_raises_or_a_worker_that_dies_is_reported(no_hang):
    venv = make_match_vec_env(SHORT, n_matches=4, learner="blue", seed=0, workers=2)
    venv.reset()
    venv.set_attr("world", None, indices=[5])  # breaks match 2, in worker 1
    with pytest.raises(WorkerError, match=r"(?s)rollout worker 1 .*raised.*AttributeError"):
        venv.step(np.zeros((venv.num_envs, 6), np.float32))
    assert all(not p.is_alive() for p in venv.processes)
    venv.close()

    venv = make_match_vec_env(SHORT, n_matches=2, learner="blue", seed=0, workers=2)
    venv.reset()
    os.kill(venv.processes[0].pid, signal.SIGKILL)
    with pytest.raises(WorkerError, match="rollout worker 0 .* died: killed by SIGKILL"):
        venv.step(np.zeros((venv.num_envs, 6), np.float32))
    venv.close()


def test_a_stopped_match_worker_is_reported_within_the_timeout(no_hang):
    """SIGSTOP of a match worker (alive, answering nothing): WorkerError naming it and its
    batch entries within the timeout, exit code None; close() returns at once and no worker
    is left."""
    import multiprocessing
    import time

    venv = make_match_vec_env(SHORT, n_matches=4, learner="blue", seed=0, workers=2,
                              reply_timeout=1.0)
    venv.reset()
    venv.step(np.zeros((venv.num_envs, 6), np.float32))
    os.kill(venv.processes[1].pid, signal.SIGSTOP)
    t0 = time.monotonic()
    with pytest.raises(WorkerError, match=r"rollout worker 1 .*environments 4-7\) stopped "
                                          r"answering: no reply within 1 s .*SIGSTOP") as err:
        venv.step(np.zeros((venv.num_envs, 6), np.float32))
    assert time.monotonic() - t0 < 3.0
    assert err.value.exitcode is None and err.value.environments == range(4, 8)
    t0 = time.monotonic()
    venv.close()
    assert time.monotonic() - t0 < 0.5
    assert not any(p.is_alive() for p in venv.processes)
    assert not set(venv.processes) & set(multiprocessing.active_children())


@pytest.mark.parametrize("timeout", [0, -2, float("inf"), "60"])
def test_a_bad_reply_timeout_is_refused(timeout):
    with pytest.raises(ValueError, match="reply_timeout must be a finite number of seconds "
                                         "> 0, got"):
        MatchWorkerVecEnv(SHORT, n_matches=2, workers=2, reply_timeout=timeout)
    with pytest.raises(ValueError, match="reply_timeout must be a finite number of seconds"):
        make_match_vec_env(SHORT, n_matches=2, workers=2, reply_timeout=timeout)


@pytest.mark.skipif(not hasattr(os, "sched_getaffinity"), reason="no CPU affinity here")
def test_workers_are_pinned_to_cpus_when_they_take_the_machine():
    usable = sorted(os.sched_getaffinity(0))
    venv = make_match_vec_env(SHORT, n_matches=2, workers=2, pin=True)
    try:
        assert venv.cpus == [usable[0], usable[1 % len(usable)]]
        for proc, cpu in zip(venv.processes, venv.cpus):
            assert os.sched_getaffinity(proc.pid) == {cpu}
    finally:
        venv.close()
    venv = make_match_vec_env(SHORT, n_matches=2, workers=2, pin=False)
    try:
        assert venv.cpus == [None, None]
        assert all(os.sched_getaffinity(p.pid) == set(usable) for p in venv.processes)
    finally:
        venv.close()
    venv = make_match_vec_env(SHORT, n_matches=2, workers=1)  # fewer workers than CPUs
    try:
        assert venv.cpus == [None] if len(usable) > 1 else [usable[0]]
    finally:
        venv.close()
