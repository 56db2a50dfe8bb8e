"""WorkerVecEnv: several environments per process, with stable-baselines3's VecEnv contract."""

from __future__ import annotations

import gymnasium as gym
import numpy as np
import pytest

pytest.importorskip("stable_baselines3")
from faulty_envs import FailingAfter  # noqa: E402
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
