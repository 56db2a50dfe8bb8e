"""The games of ``soccer-env play``: one environment with its scripted robots, robot 0 left
to the person (:func:`make_game`): the match (:class:`MatchGame`) or a single-robot task
(:class:`TaskGame`), each keeping its episodes' results."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from soccer_env.envs.registration import GOALKEEPER_ID, SHOOTOUT_ID

__all__ = ["TASKS", "ENV_IDS", "USER_AGENT", "USER", "observed_heading", "Game", "MatchGame",
           "TaskGame", "make_game"]

#: The tasks a person can play, and what they are.
TASKS = {
    "match": "you are blue_0 of a Match-v0 game; team-mates and opponents are scripted",
    "shootout": "you are the striker of Shootout-v0 against its scripted keeper",
    "keeper": "you are the keeper of Goalkeeper-v0 facing its seeded shots",
}

#: Environment ids of the single-robot tasks.
ENV_IDS = {"shootout": SHOOTOUT_ID, "keeper": GOALKEEPER_ID}

#: The agent the person plays in the match, and its robot index in every task.
USER_AGENT, USER = "blue_0", 0


def observed_heading(obs: np.ndarray) -> float:
    """The heading [rad] in the (blue) team frame of an observation, which stores
    ``(cos h, -sin h)`` at its entries 2 and 3 (:mod:`soccer_env.observations`)."""
    return math.atan2(-float(obs[3]), float(obs[2]))


class Game:
    """One environment that the person plays robot 0 of (see :func:`make_game`).

    Attributes:
        seed: the present episode's seed.
        episodes, successes: episodes finished, and those won (a goal scored in the
            shootout, a save in the keeper task, a match won).
        over: whether the present episode has ended.
        banner: a word for the panel about the latest step (a goal, the episode's result),
            or empty.
    """

    task = ""
    #: The environment as built (a Gymnasium environment or the PettingZoo match) and the
    #: core underneath.
    env: Any
    unwrapped: Any
    #: The person's robot preset.
    spec: Any

    def __init__(self) -> None:
        self.seed = 0
        self.episodes = 0
        self.successes = 0
        self.over = False
        self.banner = ""

    @property
    def time(self) -> float:
        """The episode's simulated time [s]."""
        return float(self.unwrapped.world.time)

    def reset(self, seed: int) -> None:
        """Start the episode of ``seed``."""
        raise NotImplementedError

    def heading(self) -> float:
        """The person's robot's heading as its observation has it [rad]."""
        raise NotImplementedError

    def step(self, action: np.ndarray) -> str | None:
        """Step with the person's ``action``; the result line when the episode ends."""
        raise NotImplementedError

    def status(self) -> list[str]:
        """The panel's lines about the episode."""
        raise NotImplementedError

    def stopped(self) -> str:
        """The line of an episode left unfinished."""
        return f"{self.task} seed {self.seed}: stopped after {self.time:.2f} s"

    def close(self) -> None:
        self.env.close()


class MatchGame(Game):
    task = "match"

    def __init__(self, robot: str, team_size: int, env_kwargs: dict[str, Any]) -> None:
        import soccer_env
        from agents.studies.matches import team_policy

        super().__init__()
        self.env = soccer_env.parallel_env(blue=team_size, yellow=team_size, robot=robot,
                                           **env_kwargs)
        self.unwrapped = self.env
        self.spec = self.env.team_specs[0]
        self._teams = [team_policy("scripted", self.env, t) for t in ("blue", "yellow")]
        self.draws = 0

    def reset(self, seed: int) -> None:
        self.seed, self.over, self.banner = seed, False, ""
        self.obs, _ = self.env.reset(seed=seed)

    def heading(self) -> float:
        return observed_heading(self.obs[USER_AGENT])

    def step(self, action: np.ndarray) -> str | None:
        actions: dict[str, np.ndarray] = {}
        for team in self._teams:
            actions.update(team(self.obs))
        actions[USER_AGENT] = action
        before = list(self.env.score)
        self.obs, _, _, _, _ = self.env.step(actions)
        score = self.env.score
        self.banner = ""
        if score != before:
            self.banner = "GOAL blue" if score[0] > before[0] else "GOAL yellow"
        if self.env.agents:
            return None
        self.over = True
        self.episodes += 1
        blue, yellow = score
        if blue > yellow:
            self.successes += 1
            self.banner = "you won"
        elif blue == yellow:
            self.draws += 1
            self.banner = "draw"
        else:
            self.banner = "you lost"
        return (f"match seed {self.seed}: blue {blue} : {yellow} yellow after "
                f"{self.time:.1f} s, {self.banner}")

    def status(self) -> list[str]:
        if not self.episodes:
            return []
        lost = self.episodes - self.successes - self.draws
        return [f"matches: {self.successes} W {self.draws} D {lost} L"]

    def stopped(self) -> str:
        blue, yellow = self.env.score
        return f"{super().stopped()} (blue {blue} : {yellow} yellow)"


class TaskGame(Game):
    """Shootout-v0 or Goalkeeper-v0 (robot 0 is the person's)."""

    def __init__(self, task: str, robot: str, env_kwargs: dict[str, Any]) -> None:
        import gymnasium as gym

        import soccer_env  # noqa: F401  (registers the environments)

        super().__init__()
        self.task = task
        self.env = gym.make(ENV_IDS[task], robot=robot, **env_kwargs)
        self.unwrapped = self.env.unwrapped
        self.spec = self.unwrapped.robot_spec
        self.info: dict[str, Any] = {}

    def reset(self, seed: int) -> None:
        self.seed, self.over, self.banner = seed, False, ""
        self.obs, self.info = self.env.reset(seed=seed)

    def heading(self) -> float:
        return observed_heading(self.obs)

    def step(self, action: np.ndarray) -> str | None:
        self.obs, _, terminated, truncated, self.info = self.env.step(action)
        if not (terminated or truncated):
            return None
        self.over = True
        self.episodes += 1
        outcome = self.info.get("outcome")
        success = bool(self.info.get("is_success", False))
        if self.task == "keeper":
            success = success or not outcome  # time up without a goal
            self.banner = "goal" if not success else "save"
            what = "goal" if not success else f"save ({outcome or 'time up'})"
        else:
            self.banner = "goal" if success else (outcome or "time up")
            what = self.banner
        self.successes += success
        return f"{self.task} seed {self.seed}: {what} after {self.time:.2f} s"

    def status(self) -> list[str]:
        if not self.episodes:
            return []
        what = "saves" if self.task == "keeper" else "goals"
        return [f"{what}: {self.successes} of {self.episodes}"]


def make_game(task: str, robot: str, team_size: int = 3,
              env_kwargs: dict[str, Any] | None = None,
              render_width: int | None = None) -> Game:
    """The environment of ``task`` with its scripted robots, robot 0 left to the person.

    Args:
        task: a key of :data:`TASKS`.
        robot: a robot preset name (:data:`soccer_env.presets.ROBOTS`), for every robot.
        team_size: robots per team in the match (1 .. ``MAX_TEAM_SIZE``).
        env_kwargs: further keyword arguments of the environment (``obs_mode``,
            ``perception``, ...).
        render_width: the width of the environment's ``rgb_array`` frames [px], or None for
            an environment that does not render.

    Returns:
        The game: ``reset(seed)``, ``step(action)`` (the result line when the episode
        ends), ``heading()`` [rad], ``status()`` lines, ``env`` and ``unwrapped``.

    Raises:
        ValueError: for an unknown task, and what the environment raises for bad arguments.
    """
    if task not in TASKS:
        raise ValueError(f"task must be one of {list(TASKS)}, got {task!r}")
    kwargs = dict(env_kwargs or {})
    if render_width is not None:
        kwargs.update(render_mode="rgb_array", render_width=render_width)
    if task == "match":
        return MatchGame(robot, team_size, kwargs)
    return TaskGame(task, robot, kwargs)
