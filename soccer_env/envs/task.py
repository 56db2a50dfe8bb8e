"""The Gymnasium side of the task seam: :class:`SingleAgentTask`, a task whose robot 0 (blue)
learns, with ``reset`` and ``step`` fixed; and the :func:`action_cost` shaping term the tasks
share. Its hooks are listed with the core's in :mod:`soccer_env.envs.base`."""

from __future__ import annotations

import abc
from collections.abc import Mapping
from typing import Any, ClassVar

import gymnasium as gym
import numpy as np

from soccer_env.envs.base import SoccerCore
from soccer_env.envs.flat_info import (
    NO_OUTCOME,
    OUTCOME_CODES,
    as_float64,
    flat_common,
    flat_keys,
)
from soccer_env.envs.registration import GYMNASIUM
from soccer_env.envs.settings import EnvSettings
from soccer_env.perception.base import OBS_MODES, PerceptionConfig
from soccer_env.presets import BallSpec, FieldSpec, RobotSpec
from soccer_env.render import Banner
from soccer_env.sim.commands import HumanoidRobot, SSLRobot, validate_actions
from soccer_env.state import WorldState
from soccer_env.validation import (
    check_choice,
    check_options,
    check_seed,
    parse_scales,
    real_array,
)

__all__ = ["SingleAgentTask", "action_cost"]


class SingleAgentTask(SoccerCore, gym.Env):
    """A Gymnasium task on :class:`SoccerCore`: robot 0 (blue) is the learner.

    ``reset`` and ``step`` are fixed. A task implements :meth:`_place`, :meth:`_outcome`,
    :meth:`_success` and :meth:`_reward_terms` (abstract), and optionally the other hooks
    listed in :mod:`soccer_env.envs.base`. Its constructor takes the settings
    (:class:`~soccer_env.envs.settings.EnvSettings`) and builds itself with
    :meth:`_build_learner`, then sets :attr:`builder` and ``observation_space``.

    The episode ends (terminated) when :meth:`_outcome` names an outcome; ``info["outcome"]``
    names it (:data:`~soccer_env.envs.flat_info.NO_OUTCOME`, the empty string, before) and
    ``info["is_success"]`` says whether it is a success (:meth:`_success`).
    Truncation is left to the registration's ``max_episode_steps``.

    With ``info_mode="flat"`` the info is :func:`~soccer_env.envs.flat_info.flat_common`'s
    entries for robot 0, then ``outcome`` and ``is_success`` as numbers and the task's own
    numbers (:attr:`FLAT_TASK_KEYS`, filled by :meth:`_flat_task_info`).
    """

    #: The task's own flat info keys, after ``outcome`` and ``is_success``.
    FLAT_TASK_KEYS: ClassVar[tuple[str, ...]] = ()
    #: The banner's words for each outcome: ``{outcome: (headline, detail)}``.
    OUTCOME_TEXT: ClassVar[dict[str, tuple[str, str]]] = {}

    #: The learner's action mapping (:class:`~soccer_env.sim.commands.SSLRobot` or
    #: :class:`~soccer_env.sim.commands.HumanoidRobot`), set by :meth:`_build_learner`.
    robot_model: SSLRobot | HumanoidRobot

    def _take_settings(self, keywords: Mapping[str, Any]
                       ) -> tuple[EnvSettings, RobotSpec, FieldSpec, BallSpec]:
        """The settings among the constructor's ``keywords`` (its ``**settings``;
        :meth:`~soccer_env.envs.settings.EnvSettings.from_keywords`, the error naming the
        task's class), ``obs_mode`` checked, and the robot, field and ball presets they name
        (one robot preset for every robot)."""
        cls = type(self)
        s = EnvSettings.from_keywords(cls.__name__, keywords, cls.__init__)
        check_choice("obs_mode", s.obs_mode, OBS_MODES)  # before it picks the default perception
        return (s, *s.presets())

    def _build_learner(self, settings: EnvSettings, spec: RobotSpec, field: FieldSpec,
                       ball: BallSpec, n_blue: int, n_yellow: int) -> None:
        """Build the task (:meth:`_build`) with ``n_blue`` and ``n_yellow`` robots of
        ``spec``, both teams perceiving as the settings say: the shaping scales of
        :attr:`SHAPING` (``shaping``), the world, and the learner's :attr:`robot_model` and
        ``action_space``."""
        self.shaping = parse_scales("shaping", settings.shaping, self.SHAPING)
        config = PerceptionConfig.create(settings.perception, settings.obs_mode, spec.kind)
        self._build(settings, team_specs=(spec, spec), n_blue=n_blue, n_yellow=n_yellow,
                    field=field, ball=ball, obs_mode=settings.obs_mode,
                    perceptions=(config, config), policy_heads=[0])
        self.robot_model = self._models[0]
        self.action_space = self.robot_model.action_space()

    # ------------------------------------------------------------------------------------
    # Hooks
    # ------------------------------------------------------------------------------------

    @abc.abstractmethod
    def _outcome(self, state: WorldState, event: Any) -> str | None:
        """The episode's outcome at ``state`` (None while it goes on)."""

    @abc.abstractmethod
    def _success(self, outcome: str) -> bool:
        """Whether ``outcome`` is a success (``info["is_success"]``)."""

    @abc.abstractmethod
    def _reward_terms(self, state: WorldState, action: np.ndarray, outcome: str | None
                      ) -> dict[str, float]:
        """The step's named reward terms (the reward is their sum)."""

    def _observe(self, belief: Any) -> np.ndarray:
        """The learner's observation from its ``belief`` (default: the task's
        :attr:`builder`, an :class:`~soccer_env.observations.ObservationBuilder` for robot
        0)."""
        return self.builder.build(belief)[0]

    def _others(self, actions: np.ndarray) -> None:
        """Fill the rows of the other robots in ``actions`` ``(N, 6)`` (row 0 is the
        learner's; the others are zeros: standing still)."""

    def _task_info(self, info: dict[str, Any]) -> None:
        """Add the task's own entries to ``info`` (in place)."""

    def _flat_task_info(self, info: dict[str, float]) -> None:
        """Add the task's own flat entries, :attr:`FLAT_TASK_KEYS`, to ``info`` (in place;
        floats)."""

    def _zero_terms(self) -> dict[str, float]:
        """The reward terms of the first observation, all zero (default: ``"outcome"`` and
        every term of the task's ``shaping`` scales)."""
        return dict.fromkeys(("outcome", *self.shaping), 0.0)

    @property
    def flat_info_keys(self) -> tuple[str, ...]:
        """The keys of this environment's flat infos (``info_mode="flat"``), in order: the
        same at every reset and step."""
        return flat_keys(self._zero_terms(), ("outcome", "is_success", *self.FLAT_TASK_KEYS))

    # ------------------------------------------------------------------------------------

    #: Whether an episode runs (set by :meth:`reset`, cleared when it terminates).
    _running = False
    #: How the last episode ended (its outcome), None while one runs or before the first.
    _ended: str | None = None

    def reset(self, *, seed: int | None = None, options: dict[str, Any] | None = None):
        check_seed(seed)
        check_options(options, (), type(self).__name__)
        # Gymnasium's seeding takes Python integers only; numpy's are as good a seed.
        super().reset(seed=None if seed is None else int(seed))
        state = self._start(self.np_random)
        self._running, self._ended = True, None
        self._note_reset(seed)
        obs = self._observe(self._seen)
        info = self._info(state, self._zero_terms(), None)
        if self.render_mode == "human":
            self.render()
        return obs, info

    def step(self, action):
        if not self._running:
            if self._ended is not None:
                raise RuntimeError(f"the episode has ended ({self._ended!r}): call reset() "
                                   "before stepping again")
            raise RuntimeError("call reset() before step()")
        act = real_array("action", action)
        if act.shape != (6,):
            names = ", ".join(self._models[0].action_names)
            raise ValueError(f"action must have shape (6,) ({names}), got {act.shape}")
        act = validate_actions(act[None], self._learner, self.out_of_range_actions)
        n = self.world.n_robots
        if n > 1:
            full = np.zeros((n, 6))
            full[0] = act[0]
            self._others(full)
        else:
            full = act
        state, event = self._advance(full)
        outcome = self._outcome(state, event)
        terms = self._reward_terms(state, act[0], outcome)
        reward = float(sum(terms.values()))
        obs = self._observe(self._seen)
        info = self._info(state, terms, outcome)
        if outcome is not None:  # terminated: a further step would act on a finished shot
            self._running, self._ended = False, outcome
        if self.render_mode == "human":
            self.render()
        return obs, reward, outcome is not None, False, info

    def _info(self, state: WorldState, terms: dict[str, float], outcome: str | None
              ) -> dict[str, Any]:
        if self._flat:
            flat = flat_common(state, self._shown_belief, 0, self._fallen(0), terms)
            flat["outcome"] = float(OUTCOME_CODES[NO_OUTCOME if outcome is None else outcome])
            flat["is_success"] = 1.0 if outcome is not None and self._success(outcome) else 0.0
            self._flat_task_info(flat)
            return as_float64(flat)
        truth = state.truth_dict()
        info = {"truth": truth,
                "estimate": self._estimate(state, self._shown_belief, truth),
                "reward_terms": terms, "outcome": NO_OUTCOME if outcome is None else outcome}
        self._task_info(info)
        if self.world.walk is not None:
            info["robot_state"] = self.world.humanoid_state()
        if outcome is not None:
            info["is_success"] = self._success(outcome)
        return info

    # ------------------------------------------------------------------------------------
    # The outcome banner

    def _time_limit(self) -> int | None:
        """The registered ``max_episode_steps`` of the task this environment was made as
        (``gymnasium.make`` by its id), or None. The banner assumes the registered limit: a
        ``max_episode_steps`` given to ``gymnasium.make`` is the wrapper's, which the
        environment does not see."""
        spec = getattr(self, "spec", None)
        task = GYMNASIUM.get(spec.id) if spec is not None else None
        return None if task is None else task.max_episode_steps

    def _banner(self) -> Banner | None:
        """The outcome banner on frames after the episode's end: the outcome
        (:attr:`OUTCOME_TEXT`; green for a success, red otherwise), or the time limit once the
        registered ``max_episode_steps`` are played."""
        if self._ended is not None:
            head, detail = self.OUTCOME_TEXT.get(self._ended, (self._ended.upper(), ""))
            return Banner(head, detail, "good" if self._success(self._ended) else "bad")
        limit = self._time_limit()
        w = self.world
        if self._running and limit is not None and round(w.time / w.control_dt) >= limit:
            return Banner("TIME LIMIT", f"{w.time:.1f} s played, no outcome")
        return None


def action_cost(action: np.ndarray, scale: float, dt: float) -> float:
    """The ``action_cost`` shaping term of a step of ``dt`` seconds: ``-scale (vx^2 + vy^2 +
    omega^2) / 3`` of the normalised ``action`` per second."""
    return -scale * float(action[0:3] @ action[0:3]) / 3.0 * dt
