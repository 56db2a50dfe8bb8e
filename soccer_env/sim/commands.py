"""Robot models: from a policy's normalised action to physical commands.

A robot model owns its action space and maps a batch of actions ``(N, action_size)`` in
``[-1, 1]`` to the physical commands of :meth:`World.step <soccer_env.sim.world.World.step>`:
:class:`SSLRobot` for SSL robots, :class:`HumanoidRobot` for the walk engine of humanoids.
Both have six action entries, so SSL and humanoid robots share one action space shape.
"""

from __future__ import annotations

import math
from collections import deque

import numpy as np
from gymnasium import spaces

from soccer_env.presets import HumanoidRobotSpec, RobotSpec, SSLRobotSpec
from soccer_env.sim.walk import DIVE

__all__ = ["SSLRobot", "HumanoidRobot", "robot_model", "CommandChannel", "CommandChannelBatch",
           "validate_actions", "OUT_OF_RANGE_MODES"]

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
        :meth:`World.step <soccer_env.sim.world.World.step>` (columns
        :data:`~soccer_env.sim.world.COMMAND_FIELDS`)."""
        return actions * self._scale

    def actions(self, commands: np.ndarray) -> np.ndarray:
        """The actions ``(N, 6)`` whose :meth:`commands` are the physical ``commands``
        (``(N, 6)``, :data:`~soccer_env.sim.world.COMMAND_FIELDS`), clipped to [-1, 1]: each
        velocity and kick speed beyond the robot's limit becomes the limit (the speed norm is
        capped again by the world), chip and dribble keep their sign."""
        commands = np.asarray(commands, dtype=np.float64)
        return np.clip(commands / self._scale, -1.0, 1.0)


class HumanoidRobot:
    """Action mapping of a humanoid's walk engine (:mod:`soccer_env.sim.walk`).

    Action (``Box(-1, 1, (6,), float32)``):

    ====  ========  ====================================================================
    idx   name      meaning
    ====  ========  ====================================================================
    0     vx        forward walking speed: positive values times ``max_forward_speed``,
                    negative times ``max_backward_speed`` [m/s]
    1     vy        leftward walking speed, times ``max_sideways_speed`` [m/s]
    2     omega     turn rate, times ``max_turn_speed`` [rad/s]; the walk engine scales
                    ``(vx, vy, omega)`` into its speed ellipsoid
    3     motion    > 0 starts a kick motion at ``motion * kick_max_speed`` (ignored while
                    one runs); the ball flies only if it is at a foot when the foot strikes;
                    < -0.5 dives (falls on purpose) to the left if ``vy >= 0``, else to the
                    right
    4     pan       head pan target, times ``head_pan_limit`` [rad], positive to the left
    5     tilt      head tilt target from ``head_tilt_min`` (-1) to ``head_tilt_max`` (+1)
                    [rad], positive looking down
    ====  ========  ====================================================================
    """

    action_names = ("vx", "vy", "omega", "motion", "pan", "tilt")
    action_size = 6

    def __init__(self, spec: HumanoidRobotSpec) -> None:
        self.spec = spec
        mid = 0.5 * (spec.head_tilt_max + spec.head_tilt_min)
        half = 0.5 * (spec.head_tilt_max - spec.head_tilt_min)
        self._fwd = np.array([spec.max_forward_speed, spec.max_sideways_speed,
                              spec.max_turn_speed, spec.kick_max_speed, spec.head_pan_limit,
                              half])
        self._back = self._fwd.copy()
        self._back[0] = spec.max_backward_speed
        self._offset = np.array([0.0, 0.0, 0.0, 0.0, 0.0, mid])
        # The head columns' scale and offset as Python floats, for one robot at a time.
        self._head = (float(self._fwd[4]), float(self._offset[4]), float(self._fwd[5]),
                      float(self._offset[5]))

    def action_space(self) -> spaces.Box:
        """A fresh ``Box(-1, 1, (6,), float32)``."""
        return spaces.Box(-1.0, 1.0, (self.action_size,), np.float32)

    def commands(self, actions: np.ndarray) -> np.ndarray:
        """Map validated actions ``(N, 6)`` in [-1, 1] to the walk engine's commands
        (:data:`~soccer_env.sim.walk.HUMANOID_COMMAND_FIELDS`)."""
        scale = np.where(actions[:, 0:1] >= 0.0, self._fwd, self._back)
        out = actions * scale + self._offset
        motion = actions[:, 3]
        out[:, 3] = np.where(motion > 0.0, out[:, 3], np.where(motion < -0.5, DIVE, 0.0))
        return out

    def head_command(self, pan: float, tilt: float) -> tuple[float, float]:
        """The walk engine's head commands ``(head_pan, head_tilt)`` [rad] that aim the head at
        ``pan``, ``tilt`` [rad]: what :meth:`commands` makes of the action entries
        :meth:`action_for_head` gives (clipped into the head's range)."""
        a4, a5 = self.action_for_head(pan, tilt)
        k4, o4, k5, o5 = self._head
        return a4 * k4 + o4, a5 * k5 + o5

    def action_for_head(self, pan: float, tilt: float) -> tuple[float, float]:
        """The action entries 4 and 5 that aim the head at ``pan``, ``tilt`` [rad] (clipped
        into the head's range)."""
        s = self.spec
        a4 = pan / s.head_pan_limit if s.head_pan_limit > 0.0 else 0.0
        half = 0.5 * (s.head_tilt_max - s.head_tilt_min)
        a5 = (tilt - 0.5 * (s.head_tilt_max + s.head_tilt_min)) / half if half > 0.0 else 0.0
        return max(-1.0, min(1.0, a4)), max(-1.0, min(1.0, a5))


def robot_model(spec: RobotSpec) -> SSLRobot | HumanoidRobot:
    """The action mapping of a robot preset."""
    return HumanoidRobot(spec) if spec.kind == "humanoid" else SSLRobot(spec)


#: Up to this many entries :func:`validate_actions` checks in plain Python; above, numpy's
#: reductions are cheaper (batches of environments).
_PYTHON_CHECK_SIZE = 256


def validate_actions(actions: np.ndarray, names: list[str] | tuple[str, ...], mode: str
                     ) -> np.ndarray:
    """Check a ``(N, A)`` float array of actions for agents ``names`` and apply ``mode``.

    NaN or infinite entries raise ``ValueError`` naming the agent. Entries outside
    ``[-1, 1]`` are clipped (``mode="clip"``) or raise ``ValueError`` (``mode="raise"``).
    Returns the (possibly clipped) array; the input is never modified.
    """
    if actions.size <= _PYTHON_CHECK_SIZE:
        flat = actions.ravel().tolist()
        # Fast path in plain Python (cheaper than numpy reductions at these sizes): a NaN or
        # an infinity makes the sum non-finite; finite values in [-1, 1] cannot overflow it.
        if math.isfinite(sum(flat)) and min(flat) >= -1.0 and max(flat) <= 1.0:
            return actions
    elif np.abs(actions).max() <= 1.0:  # NaN compares False: NaN, inf and |a| > 1 go on
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


#: Steps of command losses a channel draws at once.
LOSS_BLOCK = 256


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
        self.reset(None)

    def reset(self, rng: np.random.Generator | None, delay_steps: int | None = None,
              loss: float | None = None) -> None:
        """Empty the pipe: until the first commands arrive the robots stand still. A
        ``delay_steps`` or ``loss`` given replaces the channel's (an episode's drawn
        figures)."""
        if delay_steps is not None:
            self.delay_steps = int(delay_steps)
        if loss is not None:
            self.loss = float(loss)
        self.passthrough = self.delay_steps == 0 and self.loss == 0.0
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
            if not self._losses:  # draw the losses of the next LOSS_BLOCK steps at once
                draws = (self._rng.random((LOSS_BLOCK, self.n)) < self.loss).tolist()
                self._losses = [[i for i, lost in enumerate(row) if lost] for row in draws]
            lost = self._losses.pop()
            if lost:
                out = out.copy()
                out[lost] = self._last[lost]
        self._last = out
        return out


class CommandChannelBatch:
    """The :class:`CommandChannel` of one team in ``m`` environments, as arrays: every
    environment's commands queued and delivered in one operation per step.

    Environment ``k``'s commands come out as a :class:`CommandChannel` with the same generator
    delivers them, bit for bit: the same queue, and the losses drawn from the same generator
    in the same blocks of :data:`LOSS_BLOCK` steps (used from the block's last row, as the
    single channel pops them).

    Args:
        m: environments.
        n_robots: the team's robots.
        delay_steps, loss: as :class:`CommandChannel`'s (the same in every environment).
    """

    def __init__(self, m: int, n_robots: int, delay_steps: int, loss: float) -> None:
        self.m, self.n = int(m), int(n_robots)
        self.delay_steps, self.loss = int(delay_steps), float(loss)
        self.passthrough = self.delay_steps == 0 and self.loss == 0.0
        self._queue = np.zeros((max(self.delay_steps, 1), self.m, self.n, 6))
        self._head = 0
        self._last = np.zeros((self.m, self.n, 6))
        self._blocks = np.zeros((self.m, LOSS_BLOCK, self.n), dtype=bool)
        self._left = np.zeros(self.m, dtype=np.int64)
        self._rngs: list[np.random.Generator | None] = [None] * self.m

    def reset(self, k: int, rng: np.random.Generator | None) -> None:
        """Empty environment ``k``'s pipe (:meth:`CommandChannel.reset`)."""
        self._rngs[k] = rng
        self._queue[:, k] = 0.0
        self._last[k] = 0.0
        self._left[k] = 0

    def send(self, commands: np.ndarray) -> np.ndarray:
        """Queue every environment's commands ``(m, N, 6)``; return those its robots execute
        now."""
        if self.passthrough:
            return commands
        if self.delay_steps:
            out = self._queue[self._head].copy()
            self._queue[self._head] = commands
            self._head = (self._head + 1) % self.delay_steps
        else:
            out = np.array(commands, dtype=np.float64)
        if self.loss > 0.0:
            for k in np.nonzero(self._left == 0)[0].tolist():
                self._blocks[k] = self._rngs[k].random((LOSS_BLOCK, self.n)) < self.loss
                self._left[k] = LOSS_BLOCK
            self._left -= 1
            lost = self._blocks[np.arange(self.m), self._left]
            if lost.any():
                out[lost] = self._last[lost]
        self._last = out
        return out
