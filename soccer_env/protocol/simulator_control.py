"""The simulation protocol's simulator control: ``SimulatorCommand`` datagrams that place the ball
and the robots, answered with a ``SimulatorResponse``.

Supported: ``control.teleport_ball`` (position [m], height [m], velocity [m/s]; a coordinate
left out keeps the ball's present one, a velocity or height left out is 0; ``roll`` starts a
moving ball rolling, otherwise it starts sliding as after a kick) and
``control.teleport_robot`` (position [m] and orientation [rad], each kept where left out;
field-frame velocity [m/s] and turn rate [rad/s], 0 where left out). Not supported, and
answered with an error (code ``UNSUPPORTED``) while the rest of the command applies:
``by_force`` moves, ``present`` (adding or removing robots: a match's roster is fixed),
``teleport_safely``, a ``simulation_speed`` other than 1 and ``config`` (the vision preset and
the robots are chosen when the server starts). A teleport the world refuses (outside the walls,
not finite) or of a robot the team does not have is answered with ``OUT_OF_RANGE`` or
``UNKNOWN_ROBOT`` and changes nothing.
"""

from __future__ import annotations

from typing import Any

from ssl_protocol.sim import ssl_simulation_control_pb2 as sim_pb2
from ssl_protocol.state import ssl_gc_common_pb2 as common_pb2

from soccer_env.protocol.datagrams import parse

__all__ = ["read_simulator_command", "apply_simulator_command"]


def read_simulator_command(data: bytes) -> sim_pb2.SimulatorCommand:
    """Parse and check one ``SimulatorCommand`` datagram; raises
    :class:`~soccer_env.protocol.datagrams.PacketError` (``"oversized"``, ``"malformed"``,
    ``"incomplete"``)."""
    command = parse(data, sim_pb2.SimulatorCommand)
    return command


def _error(response: sim_pb2.SimulatorResponse, code: str, message: str) -> None:
    err = response.errors.add()
    err.code, err.message = code, message


def _ball(t: sim_pb2.TeleportBall, world: Any, response: sim_pb2.SimulatorResponse) -> None:
    if t.by_force or t.teleport_safely:
        _error(response, "UNSUPPORTED", "teleport_ball: by_force and teleport_safely are not "
                                        "supported; the ball was teleported as asked")
    x, y = (float(v) for v in world.ball_array()[:2])
    x, y = (t.x if t.HasField("x") else x), (t.y if t.HasField("y") else y)
    z, vx, vy, vz = t.z, t.vx, t.vy, t.vz
    try:
        world.set_ball(x, y, vx, vy, z=z, vz=vz, sliding=not t.roll and (vx or vy) != 0.0)
    except ValueError as exc:
        _error(response, "OUT_OF_RANGE", f"teleport_ball: {exc}")


def _robot(t: sim_pb2.TeleportRobot, world: Any, response: sim_pb2.SimulatorResponse) -> None:
    team = t.id.team
    size, first = ((world.n_blue, 0) if team == common_pb2.BLUE
                   else (world.n_yellow, world.n_blue) if team == common_pb2.YELLOW
                   else (0, 0))
    name = f"{common_pb2.Team.Name(team).lower()} robot {t.id.id}"
    if not t.id.HasField("id") or t.id.id >= size:
        _error(response, "UNKNOWN_ROBOT", f"teleport_robot: no {name} in this match (blue "
                                          f"{world.n_blue}, yellow {world.n_yellow} robots)")
        return
    if t.by_force or t.HasField("present"):
        _error(response, "UNSUPPORTED", f"teleport_robot {name}: by_force and present are not "
                                        "supported (the roster is fixed)")
        if t.HasField("present"):
            return
    i = first + int(t.id.id)
    x, y, theta, vx, vy, w = (float(v) for v in world.snapshot().robots[i])
    pose = (t.x if t.HasField("x") else x, t.y if t.HasField("y") else y,
            t.orientation if t.HasField("orientation") else theta)
    try:
        world.set_robot(i, *pose, t.v_x, t.v_y, t.v_angular)
    except ValueError as exc:
        _error(response, "OUT_OF_RANGE", f"teleport_robot {name}: {exc}")


def apply_simulator_command(command: sim_pb2.SimulatorCommand, world: Any
                            ) -> sim_pb2.SimulatorResponse:
    """Apply ``command`` to ``world`` (a reset :class:`~soccer_env.sim.world.World`) and
    return the response (module docstring)."""
    response = sim_pb2.SimulatorResponse()
    control = command.control
    if command.HasField("config"):
        _error(response, "UNSUPPORTED", "config is not supported: the vision preset and the "
                                        "robots are chosen when the server starts")
    if control.HasField("simulation_speed") and control.simulation_speed != 1.0:
        _error(response, "UNSUPPORTED", f"simulation_speed {control.simulation_speed:g}: "
                                        "only 1 (real time) or the stepped mode")
    if control.HasField("teleport_ball"):
        _ball(control.teleport_ball, world, response)
    for t in control.teleport_robot:
        _robot(t, world, response)
    return response
