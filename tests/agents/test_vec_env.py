"""WorkerVecEnv: several environments per process, with stable-baselines3's VecEnv contract."""

from __future__ import annotations

import multiprocessing
import os
import re
import signal
import time

import gymnasium as gym
import numpy as np
import pytest

pytest.importorskip("stable_baselines3")
from faulty_envs import FailingAfter, HangingAfter, SlowToBuild  # noqa: E402
from stable_baselines3 import PPO  # noqa: E402
from stable_baselines3.common.monitor import Monitor  # noqa: E402
from stable_baselines3.common.utils import check_for_correct_spaces  # noqa: E402
from stable_baselines3.common.vec_env import (  # noqa: E402
    DummyVecEnv,
    VecCheckNan,
    VecNormalize,
)

import soccer_env  # noqa: E402,F401
from agents.vec.workers import DEFAULT_INFO_KEYS, WorkerVecEnv  # noqa: E402


def make_keeper():
    # Short episodes so that resets happen within a few dozen steps.
    return Monitor(gym.make("soccer_env/Goalkeeper-v0", max_episode_steps=30))


@pytest.fixture(scope="module")
def pair():
    fns = [make_keeper] * 5
    worker, dummy = WorkerVecEnv(fns, n_workers=2), DummyVecEnv(fns)
    yield worker, dummy
    worker.close()
    dummy.close()


def test_steps_like_dummy_vec_env(pair):
    """Same seeds and actions give the same observations, rewards, dones, resets and
    terminal observations as stable-baselines3's in-process DummyVecEnv."""
    worker, dummy = pair
    check_for_correct_spaces(worker, dummy.observation_space, dummy.action_space)
    assert worker.num_envs == 5
    for venv in pair:
        venv.seed(7)
    np.testing.assert_array_equal(worker.reset(), dummy.reset())
    rng = np.random.default_rng(0)
    resets = 0
    for _ in range(70):
        act = rng.uniform(-1, 1, (5, 6)).astype(np.float32)
        o1, r1, d1, i1 = worker.step(act)
        o2, r2, d2, i2 = dummy.step(act)
        np.testing.assert_array_equal(o1, o2)
        np.testing.assert_array_equal(r1, r2)
        np.testing.assert_array_equal(d1, d2)
        for a, b, done in zip(i1, i2, d1):
            assert set(a) <= set(DEFAULT_INFO_KEYS)
            assert a["TimeLimit.truncated"] == b["TimeLimit.truncated"]
            if done:
                resets += 1
                np.testing.assert_array_equal(a["terminal_observation"],
                                              b["terminal_observation"])
                assert a["episode"]["r"] == b["episode"]["r"]
                assert a["episode"]["l"] == b["episode"]["l"]
    assert resets >= 5  # every environment went through an automatic reset


def test_attributes_and_methods_by_index(pair):
    worker, _ = pair
    assert worker.get_attr("obs_mode") == ["truth"] * 5
    worker.set_attr("tag", "x", indices=[3, 1])
    assert worker.get_attr("tag", indices=[1, 3]) == ["x", "x"]
    assert not worker.has_attr("tag")  # not on every environment
    # Answers come in the order of the indices asked for, across workers.
    names = worker.env_method("get_wrapper_attr", "obs_mode", indices=[4, 0])
    assert names == ["truth", "truth"]
    assert worker.env_is_wrapped(Monitor) == [True] * 5
    lengths = worker.env_method("get_episode_lengths", indices=[0])
    assert isinstance(lengths[0], list)


def test_wrappers_and_learning():
    venv = VecNormalize(VecCheckNan(WorkerVecEnv([make_keeper] * 4, n_workers=2),
                                    raise_exception=True))
    try:
        model = PPO("MlpPolicy", venv, n_steps=32, batch_size=64, n_epochs=1, seed=0,
                    device="cpu")
        model.learn(256)
        assert model.num_timesteps == 256
    finally:
        venv.close()


def test_all_infos_on_request():
    venv = WorkerVecEnv([make_keeper] * 2, n_workers=2, info_keys=None)
    try:
        venv.reset()
        _, _, _, infos = venv.step(np.zeros((2, 6), np.float32))
        assert "truth" in infos[0] and "estimate" in infos[1]
    finally:
        venv.close()


def test_bad_arguments():
    with pytest.raises(ValueError, match="at least one"):
        WorkerVecEnv([])
    with pytest.raises(ValueError, match="n_workers"):
        WorkerVecEnv([make_keeper], n_workers=0)


@pytest.mark.parametrize("timeout", [0, -1.0, float("inf"), float("nan"), "5", True, None])
def test_a_reply_timeout_that_is_no_positive_number_of_seconds_is_refused(timeout):
    before = set(multiprocessing.active_children())
    with pytest.raises(ValueError, match=r"reply_timeout must be a finite number of seconds "
                                         rf"> 0, got {re.escape(repr(timeout))}"):
        WorkerVecEnv([make_keeper] * 2, n_workers=2, reply_timeout=timeout)
    assert set(multiprocessing.active_children()) <= before  # refused before any start


# -- faults ---------------------------------------------------------------------------------

@pytest.mark.parametrize("victim", [0, 1])
def test_a_killed_worker_ends_the_run_naming_it(victim, no_hang):
    """SIGKILL of either worker: the next step raises WorkerError naming the worker, its
    environments and the signal (not a bare EOFError, not a hang), and every process ends."""
    import os
    import signal

    from agents.vec.workers import WorkerError

    venv = WorkerVecEnv([make_keeper] * 4, n_workers=2)
    venv.reset()
    os.kill(venv.processes[victim].pid, signal.SIGKILL)
    with pytest.raises(WorkerError, match=rf"rollout worker {victim} .*environments "
                                          rf"{2 * victim}-{2 * victim + 1}.* SIGKILL") as err:
        for _ in range(5):
            venv.step(np.zeros((4, 6), np.float32))
    assert err.value.worker == victim and err.value.exitcode == -signal.SIGKILL
    venv.close()  # after a failure: returns, does not wait on anyone
    assert not any(p.is_alive() for p in venv.processes)


def test_an_environment_error_in_a_later_worker_carries_its_traceback(no_hang):
    """An exception inside an environment of worker 1 (not the first) ends the step with a
    WorkerError holding the environment's traceback; close() does not hang on worker 0."""
    from agents.vec.workers import WorkerError

    fns = [make_keeper, make_keeper, make_keeper, FailingAfter(make_keeper, after=3)]
    venv = WorkerVecEnv(fns, n_workers=2)
    venv.reset()
    for _ in range(3):
        venv.step(np.zeros((4, 6), np.float32))
    with pytest.raises(WorkerError, match=r"(?s)rollout worker 1 .*environment 3 raised.*the "
                                          "field's lights went out") as err:
        venv.step(np.zeros((4, 6), np.float32))
    assert "RuntimeError" in err.value.remote_traceback
    venv.close()
    assert not any(p.is_alive() for p in venv.processes)
    with pytest.raises(RuntimeError, match="closed"):
        venv.step(np.zeros((4, 6), np.float32))


def test_workers_leave_ctrl_c_to_the_parent(no_hang):
    """Ctrl-C reaches every process of the group: the workers ignore it (the parent handles
    the interrupt and closes them), so they answer the next step."""
    import os
    import signal

    venv = WorkerVecEnv([make_keeper] * 2, n_workers=2)
    try:
        venv.reset()
        for proc in venv.processes:
            os.kill(proc.pid, signal.SIGINT)
        obs, *_ = venv.step(np.zeros((2, 6), np.float32))
        assert obs.shape[0] == 2 and all(p.is_alive() for p in venv.processes)
    finally:
        venv.close()


def _no_children_left(venv) -> None:
    """Every worker of ``venv`` has ended and none is among this process's children."""
    assert not any(p.is_alive() for p in venv.processes)
    assert not set(venv.processes) & set(multiprocessing.active_children())


@pytest.mark.parametrize("victim", [0, 1])
def test_a_stopped_worker_ends_the_run_within_the_timeout(victim, no_hang):
    """SIGSTOP of either worker (alive, but answering nothing): the next step raises
    WorkerError naming the worker, its environments and the timeout, within the timeout and
    the time it takes to end the workers; close() returns at once and no worker is left."""
    from agents.vec.workers import WorkerError

    venv = WorkerVecEnv([make_keeper] * 4, n_workers=2, reply_timeout=1.0)
    venv.reset()
    venv.step(np.zeros((4, 6), np.float32))
    os.kill(venv.processes[victim].pid, signal.SIGSTOP)
    t0 = time.monotonic()
    with pytest.raises(WorkerError, match=rf"rollout worker {victim} .*environments "
                                          rf"{2 * victim}-{2 * victim + 1}\) stopped answering: "
                                          r"no reply within 1 s .*SIGSTOP") as err:
        venv.step(np.zeros((4, 6), np.float32))
    elapsed = time.monotonic() - t0
    assert 1.0 <= elapsed < 3.0, elapsed
    assert err.value.worker == victim and err.value.environments == range(2 * victim,
                                                                           2 * victim + 2)
    assert err.value.exitcode is None and err.value.timeout == 1.0
    t0 = time.monotonic()
    venv.close()
    assert time.monotonic() - t0 < 0.5
    _no_children_left(venv)


@pytest.mark.parametrize("how", ["loop", "deadlock"])
def test_an_environment_that_hangs_in_step_ends_the_run(how, no_hang):
    """An environment of worker 1 that never returns from a step (an endless loop, a
    deadlock): WorkerError naming worker 1 within the timeout, every process ended."""
    from agents.vec.workers import WorkerError

    fns = [make_keeper, make_keeper, make_keeper, HangingAfter(make_keeper, after=2, how=how)]
    venv = WorkerVecEnv(fns, n_workers=2, reply_timeout=1.5)
    venv.reset()
    for _ in range(2):
        venv.step(np.zeros((4, 6), np.float32))
    t0 = time.monotonic()
    with pytest.raises(WorkerError, match=r"rollout worker 1 .*environments 2-3\) stopped "
                                          r"answering: no reply within 1.5 s"):
        venv.step(np.zeros((4, 6), np.float32))
    assert time.monotonic() - t0 < 3.5
    venv.close()
    _no_children_left(venv)
    with pytest.raises(RuntimeError, match="closed"):
        venv.step(np.zeros((4, 6), np.float32))


def test_close_ends_a_stopped_worker(monkeypatch, no_hang):
    """close() with a stopped worker (no failure raised first) waits CLOSE_SECONDS for it,
    then ends it: it returns, and no worker is left."""
    from agents.vec import workers

    monkeypatch.setattr(workers, "CLOSE_SECONDS", 0.5)
    venv = WorkerVecEnv([make_keeper] * 2, n_workers=2)
    venv.reset()
    os.kill(venv.processes[0].pid, signal.SIGSTOP)
    t0 = time.monotonic()
    venv.close()
    assert time.monotonic() - t0 < 0.5 + workers.KILL_SECONDS + 1.0
    _no_children_left(venv)


def test_start_up_gets_its_own_allowance(monkeypatch, no_hang):
    """Until a worker has answered a step its replies get START_TIMEOUT, not the (shorter)
    reply timeout: environments slower to build than the timeout start, and a worker
    stopped before its first step is reported after START_TIMEOUT."""
    from agents.vec import workers

    venv = WorkerVecEnv([SlowToBuild(make_keeper, 0.5)] * 2, n_workers=2, reply_timeout=0.1)
    venv.reset()
    monkeypatch.setattr(workers, "START_TIMEOUT", 2.0)
    os.kill(venv.processes[1].pid, signal.SIGSTOP)
    with pytest.raises(workers.WorkerError, match=r"rollout worker 1 .*no reply within 2 s"):
        venv.step(np.zeros((2, 6), np.float32))
    _no_children_left(venv)
