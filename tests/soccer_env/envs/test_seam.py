"""The task seam: required hooks are abstract, the common settings are declared once and every
task takes them with its own arguments, and the title card's words come from rendering."""

from __future__ import annotations

import dataclasses
import inspect
from typing import Any

import numpy as np
import pytest

from soccer_env import presets
from soccer_env.envs.base import SoccerCore
from soccer_env.envs.goalkeeper import GoalkeeperEnv
from soccer_env.envs.match import SoccerParallelEnv
from soccer_env.envs.settings import EnvSettings, settings_keywords
from soccer_env.envs.shootout import ShootoutEnv
from soccer_env.envs.task import SingleAgentTask
from soccer_env.perception.base import PerceptionConfig
from soccer_env.render.title import TeamCard, perception_text, seed_text, title_card
from soccer_env.validation import keyword_names

#: Every setting, as each task documents it, with its default.
SETTINGS = {"robot": "ssl", "field": None, "ball": None, "obs_mode": "truth",
            "perception": None, "render_mode": None, "shaping": None,
            "control_dt": 1.0 / 60.0, "physics_dt": 1.0 / 240.0,
            "out_of_range_actions": "clip", "render_width": 960, "render_view": "field",
            "head": "auto", "belief_features": False, "info_mode": "full"}
#: Each task's own arguments.
OWN = {GoalkeeperEnv: {"shots", "mates"}, ShootoutEnv: {"start"},
       SoccerParallelEnv: {"blue", "yellow", "match_duration", "max_cycles",
                           "formation_jitter", "game"}}


def test_settings_are_declared_once_with_their_defaults():
    assert {f.name: f.default for f in dataclasses.fields(EnvSettings)} == SETTINGS


@pytest.mark.parametrize("cls", list(OWN), ids=lambda c: c.__name__)
def test_every_task_takes_its_own_arguments_and_the_settings(cls):
    assert set(keyword_names(cls.__init__)) == OWN[cls] | set(SETTINGS)
    params = inspect.signature(cls).parameters
    assert all(params[name].default == default for name, default in SETTINGS.items())


class _Still(SingleAgentTask):
    """One robot that stands: every hook but ``_success``."""

    @settings_keywords
    def __init__(self, **settings: Any) -> None:
        s, spec, field, ball = self._take_settings(settings)
        self._build_learner(s, spec, field, ball, n_blue=1, n_yellow=0)
        self.builder = self._observation_builder([0], teams=[0])
        self.observation_space = self.builder.space()

    def _place(self, rng):
        return np.zeros((1, 3)), (1.0, 0.0)

    def _outcome(self, state, event):
        return None

    def _reward_terms(self, state, action, outcome):
        return {"outcome": 0.0}


def test_a_task_without_a_required_hook_cannot_be_made():
    with pytest.raises(TypeError, match="abstract method.*_success"):
        _Still()


def test_a_task_with_every_required_hook_takes_every_setting():
    class Done(_Still):
        def _success(self, outcome: str) -> bool:
            return False

    env = Done(obs_mode="raw", perception="realistic", info_mode="flat", control_dt=0.02)
    assert env.settings.obs_mode == "raw" and env.world.control_dt == 0.02
    assert env.shaping == {} and env.flat_info_keys[-2:] == ("outcome", "is_success")
    obs, info = env.reset(seed=0)
    assert obs.shape == env.observation_space.shape
    with pytest.raises(TypeError, match=r"Done\(\) got an unexpected keyword argument "
                                        r"'colour'.*allowed: .*'render_view'"):
        Done(colour="red")


def test_the_core_declares_what_it_reads():
    hints = SoccerCore.__annotations__
    for name in ("settings", "world", "field", "ball_spec", "team_specs", "perceptions",
                 "shaping", "builder", "TASK_ID", "SHAPING"):
        assert name in hints
    assert {"_place"} <= SoccerCore.__abstractmethods__
    assert {"_place", "_outcome", "_success", "_reward_terms"} == \
        SingleAgentTask.__abstractmethods__


def test_title_card_words():
    ssl = PerceptionConfig.create("realistic", "perceived", "ssl")
    assert seed_text(None, 0) == "unseeded" and seed_text(4, 2) == "seed 4 + 2 episodes"
    assert perception_text("truth", ssl, False, None) == "truth (no sensors)"
    assert perception_text("perceived", ssl, False, None) == \
        "perceived: vision realistic, ball filter ekf"
    hum = PerceptionConfig.create(None, "raw", "humanoid")
    assert perception_text("raw", hum, True, None) == \
        "raw: head cameras, dead reckoning, own sightings"
    robot = presets.robot("ssl").name
    lines = title_card("x/Y-v0", "seed 1", [TeamCard(0, 2, robot, "a"), TeamCard(1, 1, robot,
                                                                             "b")])
    assert lines == ["x/Y-v0    seed 1", f"blue: 2 {robot} robots,  yellow: 1 {robot} robot",
                     "blue obs a", "yellow obs b"]
