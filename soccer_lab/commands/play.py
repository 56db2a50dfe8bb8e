"""``soccer-env play``: a person drives one robot with the keyboard against scripted robots.

As :func:`gymnasium.utils.play.play` does for Atari games, the environment's ``rgb_array``
frames are blitted to a pygame window, the held keys make the action and a frame rate paces
the steps; unlike it, the action is continuous and depends on the robot's heading (the arrows
drive an SSL robot in the field frame), the environment may be the PettingZoo match, and a
panel beside the frames shows the keys and the results.

* ``--task match``: the person plays ``blue_0`` of Match-v0 (the keeper slot of the kick-off
  formation); the other blue robots and the yellow team are the scripted teams of
  :func:`agents.studies.matches.team_policy` (:class:`~agents.team.ScriptedTeam`,
  :class:`~agents.humanoid_team.HumanoidTeam` for humanoids);
* ``--task shootout``: the striker of Shootout-v0 against its scripted keeper;
* ``--task keeper``: the keeper of Goalkeeper-v0 facing its seeded shots.

The frames show the field as the environments draw it: ``+x`` to the right (the goal blue
attacks), ``+y`` up. Keys (:func:`key_action`, :func:`key_map`): for an SSL robot the arrows or
WASD drive in that field frame, each the way it points on the screen (right: towards the
opponents' goal), at the robot's top speed; Q and E turn it at :data:`KEY_TURN_RATE`, space
arms the kicker (a kick when the ball reaches it), shift+space a chip, F the dribbler. A
humanoid walks in its body frame (up: forward, down: back, left and right: sideways), Q and E
turn it, space kicks, shift with left or right dives to that side; its head follows the ball
by itself. P pauses, R restarts the episode, Esc or closing the window quits.

Each episode's result is printed when it ends, and the next one starts with the next seed.
"""

from __future__ import annotations

import argparse
import functools
import math
import os
import sys
import textwrap
from collections.abc import Callable, Collection, Iterable
from typing import Any

import numpy as np

from soccer_env.envs.registration import GOALKEEPER_ID, SHOOTOUT_ID
from soccer_env.render import wrap_text
from soccer_lab.cli_args import (
    DEFAULT_ROBOT,
    HelpFormatter,
    add_env_arguments,
    env_kwargs_from_args,
)
from soccer_lab.extras import message

__all__ = ["parser", "main", "key_action", "key_map", "KeyState", "make_game", "run",
           "TASKS", "ACTION_KEYS", "KEY_TURN_RATE", "START_HOLD", "END_HOLD", "NEEDS_PYGAME"]

#: The tasks a person can play, and what they are.
TASKS = {
    "match": "you are blue_0 of a Match-v0 game; team-mates and opponents are scripted",
    "shootout": "you are the striker of Shootout-v0 against its scripted keeper",
    "keeper": "you are the keeper of Goalkeeper-v0 facing its seeded shots",
}

#: Environment ids of the single-robot tasks.
_ENV_IDS = {"shootout": SHOOTOUT_ID, "keeper": GOALKEEPER_ID}

#: The turn rate of Q and E [rad/s], or the robot's top turn rate if that is lower: an SSL
#: robot's 10 rad/s would turn it 1 rad in a 0.1 s tap.
KEY_TURN_RATE = 3.0

#: What the command says when pygame does not import (it then exits with 2).
NEEDS_PYGAME = "soccer-env play needs the render extra: pip install 'soccer-env[render]'"

#: Key names, as ``pygame.key.name`` gives them, of each control.
_UP, _DOWN, _LEFT, _RIGHT = ("up", "w"), ("down", "s"), ("left", "a"), ("right", "d")
_TURN_LEFT, _TURN_RIGHT, _KICK, _DRIBBLE = ("q",), ("e",), ("space",), ("f",)
_SHIFT = ("left shift", "right shift")
#: Every key :func:`key_action` reads.
ACTION_KEYS = frozenset(_UP + _DOWN + _LEFT + _RIGHT + _TURN_LEFT + _TURN_RIGHT + _KICK
                        + _DRIBBLE + _SHIFT)

#: How long the window shows an episode's end before the next episode [s].
END_HOLD = 1.0
#: How long it shows an episode's start before play begins [s].
START_HOLD = 0.5
#: Width of the panel beside the frames, and the least height of the window [px].
PANEL_WIDTH, PANEL_HEIGHT = 300, 540
#: The panel's colour.
_PANEL = (20, 24, 28)
#: The agent the person plays in the match, and its robot index in every task.
_USER_AGENT, _USER = "blue_0", 0


# ----------------------------------------------------------------------------------------
# Keys to actions
# ----------------------------------------------------------------------------------------


def _any(pressed: Collection[str], keys: Iterable[str]) -> bool:
    return any(k in pressed for k in keys)


def _axis(pressed: Collection[str], plus: Iterable[str], minus: Iterable[str]) -> float:
    """+1, -1 or 0 (both or neither held) for a pair of opposite keys."""
    return float(_any(pressed, plus)) - float(_any(pressed, minus))


def can_chip(spec: Any) -> bool:
    """Whether the robot ``spec`` chips: an SSL robot with ``chip_max_speed > 0``."""
    return spec.kind == "ssl" and spec.chip_max_speed > 0.0


def has_dribbler(spec: Any) -> bool:
    """Whether the robot ``spec`` has a dribbler: an SSL robot with ``dribbler_force > 0``."""
    return spec.kind == "ssl" and spec.dribbler_force > 0.0


def key_action(pressed: Collection[str], spec: Any, heading: float = 0.0) -> np.ndarray:
    """The action of the held keys for a robot of preset ``spec``.

    Args:
        pressed: names of the held keys as ``pygame.key.name`` gives them (``"up"``,
            ``"w"``, ``"space"``, ``"left shift"``, ...); others are ignored.
        spec: the robot preset (:class:`~soccer_env.presets.SSLRobotSpec` or
            :class:`~soccer_env.presets.HumanoidRobotSpec`).
        heading: the robot's heading in the field frame [rad] (what the SSL robot's field-frame
            drive is rotated by; a humanoid walks in its body frame and ignores it).

    Returns:
        A ``(6,)`` float32 action in ``[-1, 1]``, the environments' action space.

        SSL robot (``vx, vy, omega, kick, chip, dribble``): right/D and left/A give the
        field-frame wish ``f_x = +-1`` (towards the opponents' goal at ``+x``, drawn on the
        right / the own goal), up/W and down/S ``f_y = +-1``; opposite keys cancel. The wish
        is scaled to unit length (full speed, diagonals included) and rotated into the body
        frame: ``(vx, vy) = (c f_x + s f_y, -s f_x + c f_y)`` with ``(c, s) = (cos,
        sin)(heading)``. Q / E give ``omega = +-min(1, KEY_TURN_RATE / max_angular_speed)``
        (counter-clockwise positive). Space arms the kicker at full power (``kick = 1``,
        else 0); with shift a chip (``chip = 1``, else -1) when the robot chips; F turns the
        dribbler on (``dribble = 1``, else -1) when it has one.

        Humanoid (``vx, vy, omega, motion, pan, tilt``): up/W and down/S walk forward and
        backward (``vx = +-1``), left/A and right/D step sideways (``vy = +-1``), Q / E turn
        (``omega``, as above), in the body frame; space kicks (``motion = 1``); shift with
        left or right dives to that side (``motion = -1``, ``vy`` the side). The head entries
        are 0 (the environment aims the head).

    Raises:
        ValueError: if ``heading`` is not finite.
    """
    if not math.isfinite(heading):
        raise ValueError(f"heading must be a finite angle in rad, got {heading!r}")
    turn = min(1.0, KEY_TURN_RATE / spec.max_angular_speed)
    omega = turn * _axis(pressed, _TURN_LEFT, _TURN_RIGHT)
    kick = _any(pressed, _KICK)
    shift = _any(pressed, _SHIFT)
    if spec.kind == "humanoid":
        forward, left = _axis(pressed, _UP, _DOWN), _axis(pressed, _LEFT, _RIGHT)
        motion = 1.0 if kick else (-1.0 if shift and left != 0.0 else 0.0)
        action = [forward, left, omega, motion, 0.0, 0.0]
    else:
        fx, fy = _axis(pressed, _RIGHT, _LEFT), _axis(pressed, _UP, _DOWN)
        norm = math.hypot(fx, fy)
        if norm > 0.0:
            fx, fy = fx / norm, fy / norm
        c, s = math.cos(heading), math.sin(heading)
        action = [c * fx + s * fy, -s * fx + c * fy, omega, 1.0 if kick else 0.0,
                  1.0 if kick and shift and can_chip(spec) else -1.0,
                  1.0 if _any(pressed, _DRIBBLE) and has_dribbler(spec) else -1.0]
    return np.clip(np.array(action, dtype=np.float64), -1.0, 1.0).astype(np.float32)


def key_map(spec: Any) -> list[tuple[str, str]]:
    """The keys and what they do for a robot of preset ``spec``, as ``(keys, meaning)``
    rows (speeds in m/s, turn rates in rad/s): the help of the window, ``--keys`` and
    ``--help``."""
    turn = min(KEY_TURN_RATE, spec.max_angular_speed)
    if spec.kind == "humanoid":
        rows = [
            ("up / down, W / S", f"walk forward / back (body frame, up to "
                                 f"{spec.max_forward_speed:g} / {spec.max_backward_speed:g} "
                                 "m/s)"),
            ("left / right, A / D", f"step left / right (up to {spec.max_sideways_speed:g} "
                                    "m/s)"),
            ("Q / E", f"turn left / right ({turn:g} rad/s)"),
            ("space", "kick (the ball must lie at a foot)"),
            ("shift + left / right", "dive to that side"),
            ("(no key)", "the head follows the ball by itself"),
        ]
    else:
        rows = [
            ("right / left, D / A", f"drive towards their goal (right) / yours, up to "
                                    f"{spec.max_speed:g} m/s"),
            ("up / down, W / S", "drive up / down the screen (the field frame, whatever "
                                 "the robot's heading)"),
            ("Q / E", f"turn left / right ({turn:g} rad/s)"),
            ("space (hold)", "kick when the ball reaches the kicker"),
        ]
        if can_chip(spec):
            rows.append(("shift + space (hold)", "chip kick"))
        if has_dribbler(spec):
            rows.append(("F (hold)", "dribbler on"))
    return rows + [("P", "pause / resume"), ("R", "restart the episode"),
                   ("Esc", "quit (or close the window)")]


def _key_text(spec: Any, indent: str = "  ") -> str:
    return "\n".join(f"{indent}{keys:22s}{what}" for keys, what in key_map(spec))


# ----------------------------------------------------------------------------------------
# The window's key state
# ----------------------------------------------------------------------------------------


class KeyState:
    """What the window's events have asked for: the held action keys, pause, restart, quit.

    Like gymnasium's ``PlayableGame.process_event``: a key-down adds an action key to
    :attr:`pressed` and its key-up removes it; P toggles :attr:`paused`, R sets
    :attr:`restart`, Esc or closing the window clears :attr:`running`; losing the focus
    releases every key (the key-ups go to another window).

    Args:
        pygame: the pygame module (its event types and key names).
    """

    def __init__(self, pygame: Any) -> None:
        self.pg = pygame
        self.pressed: set[str] = set()
        self.paused = False
        self.restart = False
        self.running = True

    def process_event(self, event: Any) -> None:
        """Take one pygame event into the state."""
        pg = self.pg
        if event.type == pg.QUIT:
            self.running = False
        elif event.type == getattr(pg, "WINDOWFOCUSLOST", None):
            self.pressed.clear()
        elif event.type in (pg.KEYDOWN, pg.KEYUP):
            name = pg.key.name(event.key)
            if event.type == pg.KEYUP:
                self.pressed.discard(name)
            elif name in ACTION_KEYS:
                self.pressed.add(name)
            elif name == "escape":
                self.running = False
            elif name == "p":
                self.paused = not self.paused
            elif name == "r":
                self.restart = True


# ----------------------------------------------------------------------------------------
# Games: one environment and its scripted robots
# ----------------------------------------------------------------------------------------


def _heading(obs: np.ndarray) -> float:
    """The heading [rad] in the (blue) team frame of an observation, which stores
    ``(cos h, -sin h)`` at its entries 2 and 3 (:mod:`soccer_env.observations`)."""
    return math.atan2(-float(obs[3]), float(obs[2]))


class _Game:
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


class _MatchGame(_Game):
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
        return _heading(self.obs[_USER_AGENT])

    def step(self, action: np.ndarray) -> str | None:
        actions: dict[str, np.ndarray] = {}
        for team in self._teams:
            actions.update(team(self.obs))
        actions[_USER_AGENT] = action
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


class _TaskGame(_Game):
    """Shootout-v0 or Goalkeeper-v0 (robot 0 is the person's)."""

    def __init__(self, task: str, robot: str, env_kwargs: dict[str, Any]) -> None:
        import gymnasium as gym

        import soccer_env  # noqa: F401  (registers the environments)

        super().__init__()
        self.task = task
        self.env = gym.make(_ENV_IDS[task], robot=robot, **env_kwargs)
        self.unwrapped = self.env.unwrapped
        self.spec = self.unwrapped.robot_spec
        self.info: dict[str, Any] = {}

    def reset(self, seed: int) -> None:
        self.seed, self.over, self.banner = seed, False, ""
        self.obs, self.info = self.env.reset(seed=seed)

    def heading(self) -> float:
        return _heading(self.obs)

    def step(self, action: np.ndarray) -> str | None:
        self.obs, _, terminated, truncated, self.info = self.env.step(action)
        if not (terminated or truncated):
            return None
        self.over = True
        self.episodes += 1
        outcome = self.info.get("outcome")
        success = bool(self.info.get("is_success", False))
        if self.task == "keeper":
            success = success or outcome is None  # time up without a goal
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
                 render_width: int | None = None) -> _Game:
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
        return _MatchGame(robot, team_size, kwargs)
    return _TaskGame(task, robot, kwargs)


# ----------------------------------------------------------------------------------------
# The window
# ----------------------------------------------------------------------------------------


class _Window:
    """The environment's frames and, beside them, the panel: the task, what the game waits
    for, the results so far and the keys. The person's robot is ringed where the renderer
    drew it (:meth:`~soccer_env.render.Renderer.pixel`,
    :meth:`~soccer_env.render.Renderer.drawn_radius`)."""

    def __init__(self, pg: Any, game: _Game) -> None:
        self.pg = pg
        frame = game.env.render()
        self.frame_size = (frame.shape[1], frame.shape[0])
        self.screen = pg.display.set_mode((self.frame_size[0] + PANEL_WIDTH,
                                           max(self.frame_size[1], PANEL_HEIGHT)))
        pg.display.set_caption(f"soccer-env play: {game.task}")
        pg.font.init()
        self.font = pg.font.Font(None, 20)
        self.big = pg.font.Font(None, 36)
        self.help = key_map(game.spec)
        self.where = ("you defend the goal on the left" if game.task == "keeper"
                      else "you attack the goal on the right")

    def draw(self, game: _Game, banner: str) -> None:
        """Draw the environment's frame with the person's robot ringed, and the panel with
        ``banner`` (what the game waits for, or the latest result)."""
        pg = self.pg
        frame = game.env.render()
        self.screen.fill(_PANEL)
        self.screen.blit(pg.surfarray.make_surface(frame.swapaxes(0, 1)), (0, 0))
        renderer = game.unwrapped.renderer
        x, y = game.unwrapped.world.robot_array()[_USER, 0:2].tolist()
        ring = int(round(renderer.drawn_radius(_USER))) + 5
        height = renderer.contents.field_height
        self.screen.set_clip(pg.Rect(0, 0, self.frame_size[0], height))  # the field's part
        pg.draw.circle(self.screen, (255, 255, 255), renderer.pixel(x, y), ring, 2)
        self.screen.set_clip(None)
        self._panel(game, banner)
        pg.display.flip()

    def _panel(self, game: _Game, banner: str) -> None:
        x0, y = self.frame_size[0] + 12, 10
        width = PANEL_WIDTH - 20
        white, grey = (240, 240, 240), (170, 175, 180)
        you = "blue 0" if game.task == "match" else "blue"
        lines = [(f"soccer-env play: {game.task}, seed {game.seed}", white),
                 (f"you: {you} ({game.spec.name}), ringed in white", white),
                 (self.where, grey)]
        lines += [(text, white) for text in game.status()]
        for text, colour in lines:
            y = self._text(text, colour, x0, y, width)
        if banner:
            self.screen.blit(self.big.render(banner.upper(), True, (255, 215, 0)), (x0, y + 6))
        y += 46
        for keys, what in self.help:
            y = self._text(keys, white, x0, y, width)
            y = self._text(what, grey, x0 + 12, y, width - 12)

    def _text(self, text: str, colour: tuple[int, int, int], x: int, y: int, width: int
              ) -> int:
        """Draw ``text`` wrapped to ``width`` pixels from ``(x, y)``; the next line's y."""
        for part in wrap_text(self.font, text, width) if text else ():
            self.screen.blit(self.font.render(part, True, colour), (x, y))
            y += 18
        return y


# ----------------------------------------------------------------------------------------
# The loop
# ----------------------------------------------------------------------------------------


def run(game: _Game, pg: Any, seed: int, fps: float,
        max_steps: int | None = None, events: Callable[[], Iterable[Any]] | None = None,
        out: Callable[[str], None] | None = None) -> int:
    """Play until the person quits or ``max_steps`` steps are taken.

    Opens the window (:class:`_Window`) on the first episode's start. Each frame takes the
    window's events, steps the environment once with the held keys' action
    (:func:`key_action`) unless paused or holding, and draws. An episode's end holds
    its last frame for :data:`END_HOLD` seconds of play (``END_HOLD / control_dt`` frames),
    prints its result, and the next episode (the next seed) holds its first frame for
    :data:`START_HOLD` seconds. On quitting, an unfinished episode's line is printed.

    Args:
        game: the environment and its scripted robots, rendering ``rgb_array`` frames
            (:func:`make_game` with a ``render_width``).
        pg: the pygame module, its display initialised.
        seed: the first episode's seed (>= 0).
        fps: frames, and so steps, per second (0: as fast as it runs).
        max_steps: stop after this many environment steps (None: no limit).
        events: the frame's events (default ``pygame.event.get``).
        out: where the lines go (default: printed to stdout at once).

    Returns:
        The environment steps taken.
    """
    events = events or pg.event.get
    out = out or functools.partial(print, flush=True)
    keys = KeyState(pg)
    clock = pg.time.Clock()
    rate = 1.0 / game.unwrapped.world.control_dt
    start_hold, end_hold = round(START_HOLD * rate), round(END_HOLD * rate)
    game.reset(seed)
    window = _Window(pg, game)
    hold, steps = start_hold, 0
    shown, shown_left = "", 0  # the last event's banner and its frames to go
    while max_steps is None or steps < max_steps:
        for event in events():
            keys.process_event(event)
        if not keys.running:
            break
        if keys.restart:
            keys.restart = False
            game.reset(game.seed)
            hold, shown_left = start_hold, 0
        elif hold > 0:
            hold -= 1
            if hold == 0 and game.over:
                game.reset(game.seed + 1)
                hold = start_hold
        elif not keys.paused:
            line = game.step(key_action(keys.pressed, game.spec, game.heading()))
            steps += 1
            if game.banner:
                shown, shown_left = game.banner, end_hold
            if line is not None:
                out(line)
                hold = end_hold
        if keys.paused:
            banner = "paused"
        elif shown_left > 0:
            banner = shown
        else:
            banner = "ready" if hold else ""
        shown_left = max(0, shown_left - 1)
        window.draw(game, banner)
        clock.tick(fps)
    if not game.over:
        out(game.stopped())
    return steps


# ----------------------------------------------------------------------------------------
# The command
# ----------------------------------------------------------------------------------------


def parser() -> argparse.ArgumentParser:
    """The options of ``soccer-env play``."""
    from soccer_env import MAX_TEAM_SIZE, presets

    ssl, humanoid = presets.ROBOTS["ssl"], presets.ROBOTS["humanoid"]
    p = argparse.ArgumentParser(
        prog="soccer-env play",
        formatter_class=HelpFormatter,
        description=textwrap.fill(
            "Drive a robot with the keyboard against the scripted robots, in a window (needs "
            "the render extra). You play blue, whose goal to attack is on the right; your "
            "robot is ringed in white. With --obs-mode raw or perceived, what your team "
            "believes is drawn in cyan over the truth. Each episode's result is printed when "
            "it ends; the next one starts with the next seed.", 79),
        epilog=f"keys, SSL robots:\n{_key_text(ssl)}\n\nkeys, humanoids:\n"
               f"{_key_text(humanoid)}\n\nexamples:\n"
               "  soccer-env play\n"
               "  soccer-env play --task keeper --robot humanoid\n"
               "  soccer-env play --task shootout --obs-mode perceived --perception realistic")
    p.add_argument("--task", choices=list(TASKS), default="match",
                   help="; ".join(f"{k}: {v}" for k, v in TASKS.items()))
    p.add_argument("--team-size", type=int, default=None,
                   help=f"robots per team in the match, 1..{MAX_TEAM_SIZE} (default: 3)")
    p.add_argument("--seed", type=int, default=0,
                   help="seed of the first episode; each next episode takes the next")
    p.add_argument("--fps", type=float, default=60,
                   help="frames and steps per second, 0 for as fast as it runs; 60 is real "
                        "time at the environments' 60 Hz control rate")
    p.add_argument("--width", type=int, default=800,
                   help="width of the environment's frames in pixels, 200..3840 (the height "
                        "follows the field's; a panel with the keys is beside them)")
    add_env_arguments(p)
    p.add_argument("--max-steps", type=int, default=None, metavar="N",
                   help="stop after N environment steps (default: play until you quit)")
    p.add_argument("--keys", action="store_true",
                   help="print the keys of --robot and exit")
    return p


def main(argv: list[str] | None = None) -> int:
    """``soccer-env play``: drive a robot with the keyboard (see the module docstring).

    Returns:
        0 after playing (or ``--keys``), 2 when pygame is missing.
    """
    from soccer_env import MAX_TEAM_SIZE, presets

    p = parser()
    args = p.parse_args(argv)
    robot = args.robot or DEFAULT_ROBOT
    if args.keys:
        print(f"keys for robot {robot}:\n{_key_text(presets.ROBOTS[robot])}")
        return 0
    if args.team_size is not None and args.task != "match":
        p.error("--team-size applies to --task match only")
    team_size = 3 if args.team_size is None else args.team_size
    if not 1 <= team_size <= MAX_TEAM_SIZE:
        p.error(f"--team-size must be in 1..{MAX_TEAM_SIZE}, got {team_size}")
    if args.seed < 0:
        p.error(f"--seed must be >= 0, got {args.seed}")
    if not (math.isfinite(args.fps) and 0.0 <= args.fps <= 1000.0):
        p.error(f"--fps must be in [0, 1000] (0: as fast as it runs), got {args.fps}")
    if not 200 <= args.width <= 3840:
        p.error(f"--width must be in 200..3840 pixels, got {args.width}")
    if args.max_steps is not None and args.max_steps < 1:
        p.error(f"--max-steps must be >= 1, got {args.max_steps}")
    try:
        env_kwargs = env_kwargs_from_args(args)
    except ValueError as err:
        p.error(str(err))
    pygame, missing = _import_pygame()
    if pygame is None:
        print(missing, file=sys.stderr)
        return 2
    robot = env_kwargs.pop("robot", robot)  # --robot, else an --env-kwarg robot=...
    try:
        game = make_game(args.task, robot, team_size, env_kwargs, args.width)
    except (ValueError, TypeError) as err:
        p.error(str(err))
    pygame.display.init()
    try:
        run(game, pygame, args.seed, args.fps, args.max_steps)
    finally:
        game.close()
        pygame.display.quit()
    return 0


def _import_pygame() -> tuple[Any, str]:
    """The pygame module and ``""``, or None and the line saying how to install it
    (:func:`soccer_lab.extras.message`, or :data:`NEEDS_PYGAME` when pygame is there but
    does not import)."""
    text = message("play")
    if text is None:
        os.environ.setdefault("PYGAME_HIDE_SUPPORT_PROMPT", "1")
        try:
            import pygame
        except ImportError:
            return None, NEEDS_PYGAME
        return pygame, ""
    return None, text
