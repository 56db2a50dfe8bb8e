"""stable-baselines3's own vectorised environments on the package's environments, as the
libraries page says: ``SubprocVecEnv`` with every start method (the environments pickle into
fresh processes) and ``VecVideoRecorder`` on rendered keepers."""

from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("stable_baselines3")
from stable_baselines3.common.env_util import make_vec_env  # noqa: E402
from stable_baselines3.common.vec_env import (  # noqa: E402
    DummyVecEnv,
    SubprocVecEnv,
    VecVideoRecorder,
)

import soccer_env  # noqa: E402,F401

GK = "soccer_env/Goalkeeper-v0"
#: The id that imports the package in a fresh process (Gymnasium's ``module:id``): what
#: ``SubprocVecEnv`` needs with the ``forkserver`` and ``spawn`` start methods, whose workers
#: do not inherit this process's registrations.
GK_IMPORTING = "soccer_env:soccer_env/Goalkeeper-v0"


@pytest.mark.parametrize("start_method", ["fork", "forkserver", "spawn"])
def test_subproc_vec_env_steps_the_keeper_with_every_start_method(start_method):
    venv = make_vec_env(GK_IMPORTING, n_envs=2, seed=3, vec_env_cls=SubprocVecEnv,
                        vec_env_kwargs={"start_method": start_method})
    try:
        obs = venv.reset()
        # The same seeds in one process: the same first observations.
        dummy = make_vec_env(GK, n_envs=2, seed=3, vec_env_cls=DummyVecEnv)
        np.testing.assert_array_equal(obs, dummy.reset())
        for _ in range(5):
            obs, rewards, dones, infos = venv.step(np.zeros((2, 6), np.float32))
        assert np.isfinite(obs).all() and np.isfinite(rewards).all()
        assert {"truth", "estimate", "outcome"} <= set(infos[0])
    finally:
        venv.close()


def test_vec_video_recorder_writes_a_video(tmp_path):
    pytest.importorskip("moviepy")
    venv = make_vec_env(GK, n_envs=1, seed=0, env_kwargs={"render_mode": "rgb_array",
                                                          "render_width": 160})
    recorder = VecVideoRecorder(venv, str(tmp_path), record_video_trigger=lambda step: step == 0,
                                video_length=8, name_prefix="keeper")
    recorder.reset()
    for _ in range(10):
        recorder.step(np.zeros((1, 6), np.float32))
    recorder.close()
    videos = list(tmp_path.glob("keeper*.mp4"))
    assert len(videos) == 1 and videos[0].stat().st_size > 1_000
