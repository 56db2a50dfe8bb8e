"""BenchMARL's task of the match (agents.runs.benchmarl): its configuration and the match it
makes run everywhere; the task class and enum need BenchMARL and run in ``make
test-benchmarl`` (its own environment), skipped in the main suite."""

from __future__ import annotations

import os
import pickle
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import soccer_env
from agents.runs.benchmarl import MatchTaskConfig, match_config, match_env_kwargs
from soccer_env.envs.flat_info import EVENT_CODES

ROOT = Path(__file__).resolve().parents[2]
TINY = {"max_cycles": 10}


def _needs_benchmarl() -> None:
    pytest.importorskip("benchmarl", reason="the benchmarl extra (make test-benchmarl)")


# Configuration (no BenchMARL) ------------------------------------------------------------


def test_the_configuration_takes_some_fields_and_defaults_the_rest():
    config = match_config({"blue": 1, "env_kwargs": {"control_dt": 0.04}})
    assert config == {"blue": 1, "yellow": 2, "match_duration": 30.0, "max_cycles": 1800,
                      "obs_mode": "truth", "perception": None,
                      "shaping": {"ball_progress": 1.0, "ball_distance": 0.1},
                      "env_kwargs": {"control_dt": 0.04}}
    assert match_config() == match_config(None) == match_config({})
    assert match_env_kwargs(config) == {
        "blue": 1, "yellow": 2, "match_duration": 30.0, "max_cycles": 1800,
        "obs_mode": "truth", "shaping": {"ball_progress": 1.0, "ball_distance": 0.1},
        "control_dt": 0.04, "info_mode": "flat"}


def test_the_configuration_refuses_what_the_task_cannot_use():
    with pytest.raises(TypeError, match="SoccerTask.MATCH takes no colour, team_size"):
        match_config({"team_size": 3, "colour": "blue"})
    with pytest.raises(ValueError, match="max_cycles must be a whole number >= 1"):
        MatchTaskConfig(max_cycles=0)
    with pytest.raises(ValueError, match="the task makes the match with info_mode='flat'"):
        match_config({"env_kwargs": {"info_mode": "full"}})


def test_the_match_has_flat_infos_of_numbers_under_fixed_keys():
    """What TorchRL's wrapper asks of every agent's info: the keys of the first reset at
    every step, each value a number."""
    env = soccer_env.parallel_env(**match_env_kwargs(match_config(TINY)))
    _, infos = env.reset(seed=0)
    keys = {agent: list(info) for agent, info in infos.items()}
    assert set(keys) == {"blue_0", "blue_1", "yellow_0", "yellow_1"}
    for _ in range(3):
        _, _, _, _, infos = env.step({a: env.action_space(a).sample() for a in env.agents})
        for agent, info in infos.items():
            assert list(info) == keys[agent]
            assert all(isinstance(v, float) and np.isfinite(v) for v in info.values())
    assert "event" in keys["blue_0"] and "score_yellow" in keys["yellow_1"]


def test_the_task_classes_say_which_extra_they_need_without_benchmarl():
    code = ("import sys\nsys.modules['benchmarl'] = None\n"
            "import agents.runs.benchmarl as m\n"
            "try:\n    m.SoccerTask\nexcept ModuleNotFoundError as err:\n    print(err)\n")
    run = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True,
                         text=True, env={**os.environ, "PYTHONPATH": str(ROOT)}, timeout=120)
    assert run.returncode == 0, run.stderr
    assert "agents.runs.benchmarl.SoccerTask needs BenchMARL: pip install torch==2.13.0 && " \
           "pip install 'soccer-env[benchmarl]' (missing: benchmarl)" in run.stdout
    with pytest.raises(AttributeError, match="has no attribute 'SoccerTeam'"):
        import agents.runs.benchmarl as module

        module.SoccerTeam  # noqa: B018


# The task (BenchMARL) --------------------------------------------------------------------


@pytest.fixture
def task():
    _needs_benchmarl()
    from agents.runs.benchmarl import SoccerTask

    return SoccerTask.MATCH.get_task(TINY)


def test_the_task_makes_the_wrapped_match_grouped_by_team(task):
    from torchrl.envs.utils import check_env_specs

    env = task.get_env_fun(num_envs=1, continuous_actions=True, seed=0, device="cpu")()
    check_env_specs(env)
    assert task.group_map(env) == {"blue": ["blue_0", "blue_1"],
                                   "yellow": ["yellow_0", "yellow_1"]}
    assert task.supports_continuous_actions() and not task.supports_discrete_actions()
    assert task.max_steps(env) == 10 and not task.has_render(env)
    assert task.env_name() == "soccer_env" and task.state_spec(env) is None
    action = task.action_spec(env)["blue", "action"]
    assert tuple(action.shape) == (2, 6)
    assert float(action.space.low.min()) == -1.0 and float(action.space.high.max()) == 1.0
    assert set(task.observation_spec(env)["blue"].keys()) == {"observation"}
    info = task.info_spec(env)["yellow", "info"]
    assert {"event", "score_blue", "score_yellow", "truth_ball_x"} <= set(info.keys())
    rollout = env.rollout(12)  # truncated after max_cycles
    assert rollout.shape[0] == 10 and bool(rollout[-1]["next", "truncated"])


def test_each_match_of_an_env_function_takes_the_next_seed(task):
    def first_observation(make):
        return make().reset()["blue", "observation"]

    make = task.get_env_fun(num_envs=2, continuous_actions=True, seed=3, device="cpu")
    again = task.get_env_fun(num_envs=2, continuous_actions=True, seed=3, device="cpu")
    first, second = first_observation(make), first_observation(make)
    assert not np.array_equal(first.numpy(), second.numpy())  # the kick-off jitter
    np.testing.assert_array_equal(first.numpy(), first_observation(again).numpy())


def test_the_goals_logged_per_batch(task):
    import torch
    from tensordict import TensorDict

    event = torch.zeros(2, 50, 2)
    event[0, 10] = EVENT_CODES["goal"]
    event[1, 20] = EVENT_CODES["touch"]
    batch = TensorDict({"next": {"blue": {"info": {"event": event}}}}, batch_size=[2, 50])
    assert task.log_info(batch) == {"match/goals_per_1k": 10.0}


def test_the_enum_loads_a_yaml_configuration_and_the_task_pickles(task, tmp_path):
    from agents.runs.benchmarl import SoccerMatchClass, SoccerTask

    assert SoccerTask.MATCH.associated_class() is SoccerMatchClass
    assert SoccerTask.MATCH.get_from_yaml().config == match_config()
    path = tmp_path / "match.yaml"
    path.write_text("blue: 1\nyellow: 1\nmax_cycles: 10\nenv_kwargs:\n  control_dt: 0.04\n")
    loaded = SoccerTask.MATCH.get_from_yaml(str(path))
    assert loaded.config == match_config({"blue": 1, "yellow": 1, "max_cycles": 10,
                                          "env_kwargs": {"control_dt": 0.04}})
    assert pickle.loads(pickle.dumps(task)) == task
    assert pickle.loads(pickle.dumps(SoccerTask.MATCH)) is SoccerTask.MATCH
    # A new process finds the classes by name, as BenchMARL's reload unpickles its config.pkl.
    (tmp_path / "task.pkl").write_bytes(pickle.dumps(task))
    code = (f"import pickle\ntask = pickle.loads(open({str(tmp_path / 'task.pkl')!r}, 'rb')"
            ".read())\nprint(type(task).__module__, type(task).__name__, task.config['blue'])\n")
    run = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True,
                         text=True, env={**os.environ, "PYTHONPATH": str(ROOT)}, timeout=120)
    assert run.returncode == 0, run.stderr
    assert run.stdout.split() == ["agents.runs.benchmarl", "SoccerMatchClass", "2"]
