"""The simulation protocol's robot control: ``RobotControl`` datagrams to the world's commands,
and the ``RobotControlResponse`` that answers them.

A team's software sends one ``RobotControl`` per control cycle, one ``RobotCommand`` per robot
(``id``: the robot's number in its team). Each command sets the whole command of its robot
(:data:`~soccer_env.sim.world.COMMAND_FIELDS`: body-frame velocity [m/s] and turn rate
[rad/s], kick speed [m/s], chip, dribbler); a robot no command names keeps its last one.

* ``move_command``: ``local_velocity`` (``forward``, ``left``, ``angular``) is the body-frame
  command as it is; ``global_velocity`` (``x``, ``y``, ``angular``) is turned into the body frame
  by the robot's heading as the world has it; ``wheel_velocity`` is not supported (the world's
  robots take body velocities) and refused; none: the robot stands.
* ``kick_speed`` [m/s] arms the kicker (the world caps it at the robot's kicker); a
  ``kick_angle`` [degrees] above 0 makes the kick a chip (at the robot's chip angle).
* ``dribbler_speed`` [rpm] above 0 turns the dribbler on.

A command that names a robot the team does not have, that moves by wheel velocities, or
that carries a number that is not finite or beyond :data:`MAX_SPEED`, :data:`MAX_TURN_RATE` or
:data:`MAX_KICK_SPEED`, is not applied: the response carries a ``SimulatorError`` with its
code (``UNKNOWN_ROBOT``, ``UNSUPPORTED_MOVE``, ``OUT_OF_RANGE``) and the robot keeps its last
command. A datagram that does not parse raises :class:`~soccer_env.protocol.datagrams.PacketError`
for the caller to count and drop.
"""

from __future__ import annotations

import math

import numpy as np
from ssl_protocol.sim import ssl_simulation_robot_control_pb2 as control_pb2
from ssl_protocol.sim import ssl_simulation_robot_feedback_pb2 as feedback_pb2

from soccer_env.protocol.datagrams import parse

__all__ = ["MAX_SPEED", "MAX_TURN_RATE", "MAX_KICK_SPEED", "DRIBBLER_RPM",
           "read_robot_control", "apply_robot_control", "robot_control"]

#: The largest speed a command may ask for [m/s] (the world caps it at the robot's).
MAX_SPEED = 20.0
#: The largest turn rate [rad/s].
MAX_TURN_RATE = 100.0
#: The largest kick speed [m/s].
MAX_KICK_SPEED = 50.0
#: The dribbler speed [rpm] :func:`robot_control` asks for when a command turns it on (the
#: world's dribbler is on or off).
DRIBBLER_RPM = 10_000.0


def read_robot_control(data: bytes) -> control_pb2.RobotControl:
    """Parse and check one ``RobotControl`` datagram; raises
    :class:`~soccer_env.protocol.datagrams.PacketError` (``"oversized"``, ``"malformed"``,
    ``"incomplete"``)."""
    control = parse(data, control_pb2.RobotControl)
    return control


def _command(cmd: control_pb2.RobotCommand, heading: float) -> tuple[list[float] | None, str,
                                                                       str]:
    """The world command of one ``RobotCommand`` (None with an error code and message)."""
    vx = vy = w = 0.0
    move = cmd.move_command.WhichOneof("command") if cmd.HasField("move_command") else None
    if move == "wheel_velocity":
        return None, "UNSUPPORTED_MOVE", "wheel velocities are not supported; send " \
                                         "local_velocity or global_velocity"
    if move == "local_velocity":
        m = cmd.move_command.local_velocity
        vx, vy, w = m.forward, m.left, m.angular
    elif move == "global_velocity":
        m = cmd.move_command.global_velocity
        c, s = math.cos(heading), math.sin(heading)
        vx, vy, w = c * m.x + s * m.y, -s * m.x + c * m.y, m.angular
    numbers = (vx, vy, w, cmd.kick_speed, cmd.kick_angle, cmd.dribbler_speed)
    if not all(math.isfinite(v) for v in numbers) or math.hypot(vx, vy) > MAX_SPEED \
            or abs(w) > MAX_TURN_RATE or not 0.0 <= cmd.kick_speed <= MAX_KICK_SPEED:
        return None, "OUT_OF_RANGE", (f"velocity ({vx:g}, {vy:g}) m/s, turn {w:g} rad/s, kick "
                                      f"{cmd.kick_speed:g} m/s: at most {MAX_SPEED:g} m/s, "
                                      f"{MAX_TURN_RATE:g} rad/s, kick 0-{MAX_KICK_SPEED:g} m/s,"
                                      " all finite")
    return [vx, vy, w, cmd.kick_speed, 1.0 if cmd.kick_angle > 0.0 else 0.0,
            1.0 if cmd.dribbler_speed > 0.0 else 0.0], "", ""


def apply_robot_control(control: control_pb2.RobotControl, commands: np.ndarray,
                        first: int, size: int, headings: np.ndarray,
                        ball_contact: np.ndarray | None = None
                        ) -> feedback_pb2.RobotControlResponse:
    """Write ``control``'s commands for one team into ``commands`` (the world's ``(N, 6)``
    command array, changed in place) and return the response (module docstring).

    ``first`` is the world index of the team's robot 0 and ``size`` its number of robots;
    ``headings`` ``(N,)`` the robots' headings [rad]; ``ball_contact`` ``(N,)`` whether each
    robot's dribbler touches the ball, for the feedback (None: not reported). The feedback
    names each robot a command named that the team has."""
    response = feedback_pb2.RobotControlResponse()
    for cmd in control.robot_commands:
        if cmd.id >= size:
            err = response.errors.add()
            err.code = "UNKNOWN_ROBOT"
            err.message = (f"robot {cmd.id}: the team has robots 0-{size - 1}" if size
                           else f"robot {cmd.id}: the team has no robots")
            continue
        i = first + int(cmd.id)
        row, code, message = _command(cmd, float(headings[i]))
        if row is None:
            err = response.errors.add()
            err.code, err.message = code, f"robot {cmd.id}: {message}"
        else:
            commands[i] = row
        fb = response.feedback.add()
        fb.id = cmd.id
        if ball_contact is not None:
            fb.dribbler_ball_contact = bool(ball_contact[i])
    return response


def robot_control(commands: np.ndarray, ids: list[int] | range | None = None,
                  chip_angle: float = math.pi / 4) -> control_pb2.RobotControl:
    """The ``RobotControl`` of a team's physical commands ``(n, 6)`` (body-frame ``vx, vy``
    [m/s], ``omega`` [rad/s], kick speed [m/s] (<= 0: none), chip (> 0), dribble (> 0)), for
    the robots ``ids`` (default ``0..n-1``): the inverse of :func:`apply_robot_control`. A
    chip goes out as ``kick_angle`` ``chip_angle`` [rad] in degrees (the world chips at its
    robot's own angle), the dribbler as :data:`DRIBBLER_RPM`."""
    rows = np.asarray(commands, dtype=np.float64).reshape(-1, 6)
    control = control_pb2.RobotControl()
    for i, row in zip(range(len(rows)) if ids is None else ids, rows):
        cmd = control.robot_commands.add(id=int(i))
        move = cmd.move_command.local_velocity
        move.forward, move.left, move.angular = (float(row[0]), float(row[1]), float(row[2]))
        if row[3] > 0.0:
            cmd.kick_speed = float(row[3])
            cmd.kick_angle = math.degrees(chip_angle) if row[4] > 0.0 else 0.0
        cmd.dribbler_speed = DRIBBLER_RPM if row[5] > 0.0 else 0.0
    return control
