"""Robot models: from a policy's normalised action to physical commands.

A robot model owns its action space and maps a batch of actions ``(N, action_size)`` in
``[-1, 1]`` to :class:`~soccer_env.physics.RobotCommands`. Only the SSL model exists now; the
humanoid walk engine will implement the same interface.
"""

from __future__ import annotations

import math
from collections import deque

import numpy as np
from gymnasium import spaces

from .presets import SSLRobotSpec

__all__ = ["SSLRobot", "CommandChannel", "validate_actions", "OUT_OF_RANGE_MODES"]

#: Allowed values of the ``out_of_range_actions`` argument of the environments.
OUT_OF_RANGE_MODES = ("clip", "raise")


class SSLRobot:
    """Action mapping of an SSL robot.

    Action (``Box(-1, 1, (6,), float32)``):

    ====  ========  ====================================================================
    idx   name      meaning
    ====  ========  ====================================================================
    0     vx        forward velocity, times ``max_speed`` [m/s]
    1     vy        leftward velocity, times ``max_speed`` [m/s]; the norm of (vx, vy)
                    is capped at ``max_speed``
    2     omega     turn rate, times ``max_angular_speed`` [rad/s], counter-clockwise
    3     kick      kicker power; values <= 0 leave the kicker disarmed, ``p`` in (0, 1]
                    arms it at ``p * kicker_max_speed`` (capped at ``kick_speed_cap``)
    4     chip      > 0 makes the armed kick a chip kick
    5     dribble   > 0 turns the dribbler on
    ====  ========  ====================================================================
    """

    action_names = ("vx", "vy", "omega", "kick", "chip", "dribble")
    action_size = 6

    def __init__(self, spec: SSLRobotSpec) -> None:
        self.spec = spec
        # vx, vy, omega to physical units; kick power to m/s (<= 0 stays "no kick"); the chip
        # and dribble columns keep their sign, which is all the world reads.
        self._scale = np.array([spec.max_speed, spec.max_speed, spec.max_angular_speed,
                                spec.kicker_max_speed, 1.0, 1.0])

    def action_space(self) -> spaces.Box:
        """A fresh ``Box(-1, 1, (6,), float32)``."""
        return spaces.Box(-1.0, 1.0, (self.action_size,), np.float32)

    def commands(self, actions: np.ndarray) -> np.ndarray:
        """Map validated actions ``(N, 6)`` in [-1, 1] to the physical commands of
        :meth:`World.step <soccer_env.physics.World.step>` (columns
        :data:`~soccer_env.physics.COMMAND_FIELDS`)."""
        return actions * self._scale


def validate_actions(actions: np.ndarray, names: list[str] | tuple[str, ...], mode: str
                     ) -> np.ndarray:
    """Check a ``(N, A)`` float array of actions for agents ``names`` and apply ``mode``.

    NaN or infinite entries raise ``ValueError`` naming the agent. Entries outside
    ``[-1, 1]`` are clipped (``mode="clip"``) or raise ``ValueError`` (``mode="raise"``).
    Returns the (possibly clipped) array; the input is never modified.
    """
    flat = actions.ravel().tolist()
    # Fast path in plain Python (cheaper than numpy reductions at these sizes): a NaN or an
    # infinity makes the sum non-finite; finite values in [-1, 1] cannot overflow it.
    if math.isfinite(sum(flat)) and min(flat) >= -1.0 and max(flat) <= 1.0:
        return actions
    finite = np.isfinite(actions)
    if not finite.all():
        row, col = np.argwhere(~finite)[0]
        raise ValueError(
            f"action for agent {names[row]!r} contains a non-finite value "
            f"{actions[row, col]!r} at index {col}; actions must be finite and in [-1, 1]"
        )
    if mode == "raise":
        row, col = np.argwhere(np.abs(actions) > 1.0)[0]
        raise ValueError(
            f"action for agent {names[row]!r} has {actions[row, col]!r} at index {col}, "
            "outside the allowed range [-1, 1] (pass out_of_range_actions='clip' to clip)"
        )
    return np.clip(actions, -1.0, 1.0)


class CommandChannel:
    """The radio and firmware between a policy and its robots: commands take effect
    ``delay_steps`` control steps late, and each robot misses a command with probability
    ``loss`` (it keeps executing the previous one, as SSL robots do).

    Args:
        n_robots: robots in the world.
        delay_steps: actuation latency in control steps (0: immediate).
        loss: per-robot, per-command loss probability.
    """

    def __init__(self, n_robots: int, delay_steps: int, loss: float) -> None:
        self.n = n_robots
        self.delay_steps = int(delay_steps)
        self.loss = float(loss)
        self.passthrough = self.delay_steps == 0 and self.loss == 0.0
        self.reset(None)

    def reset(self, rng: np.random.Generator | None) -> None:
        """Empty the pipe: until the first commands arrive the robots stand still."""
        self._rng = rng
        idle = np.zeros((self.n, 6))
        self._queue = deque([idle] * self.delay_steps)
        self._last = idle
        self._losses: list[list[int]] = []

    def send(self, commands: np.ndarray) -> np.ndarray:
        """Queue ``commands`` ``(N, 6)``; return those the robots execute now."""
        if self.passthrough:
            return commands
        self._queue.append(commands)
        out = self._queue.popleft()
        if self.loss > 0.0:
            if not self._losses:  # draw the losses of the next 256 steps at once
                draws = (self._rng.random((256, self.n)) < self.loss).tolist()
                self._losses = [[i for i, lost in enumerate(row) if lost] for row in draws]
            lost = self._losses.pop()
            if lost:
                out = out.copy()
                out[lost] = self._last[lost]
        self._last = out
        return out
