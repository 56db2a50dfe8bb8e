"""The keys of ``soccer-env play``: what the held keys make of a robot's action
(:func:`key_action`), the keys and what they do (:func:`key_map`), and the window's key state
(:class:`KeyState`: held keys, pause, restart, quit)."""

from __future__ import annotations

import math
from collections.abc import Collection, Iterable
from typing import Any

import numpy as np

__all__ = ["KEY_TURN_RATE", "ACTION_KEYS", "can_chip", "has_dribbler", "key_action", "key_map",
           "key_text", "KeyState"]

#: The turn rate of Q and E [rad/s], or the robot's top turn rate if that is lower: an SSL
#: robot's 10 rad/s would turn it 1 rad in a 0.1 s tap.
KEY_TURN_RATE = 3.0

#: Key names, as ``pygame.key.name`` gives them, of each control.
_UP, _DOWN, _LEFT, _RIGHT = ("up", "w"), ("down", "s"), ("left", "a"), ("right", "d")
_TURN_LEFT, _TURN_RIGHT, _KICK, _DRIBBLE = ("q",), ("e",), ("space",), ("f",)
_SHIFT = ("left shift", "right shift")
#: Every key :func:`key_action` reads.
ACTION_KEYS = frozenset(_UP + _DOWN + _LEFT + _RIGHT + _TURN_LEFT + _TURN_RIGHT + _KICK
                        + _DRIBBLE + _SHIFT)


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


def key_text(spec: Any, indent: str = "  ") -> str:
    """:func:`key_map` of ``spec`` as text, one ``keys  meaning`` line each after
    ``indent`` (``--keys`` and the help's epilog)."""
    return "\n".join(f"{indent}{keys:22s}{what}" for keys, what in key_map(spec))


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
