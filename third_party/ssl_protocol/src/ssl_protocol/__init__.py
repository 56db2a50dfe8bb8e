"""Python classes of the RoboCup Small Size League protocols, generated from the league's
official ``.proto`` files (see ``README.md`` beside ``pyproject.toml`` for the sources, their
commits and the generation command):

* ``ssl_protocol.vision``: ``SSL_WrapperPacket``, ``SSL_DetectionFrame``,
  ``SSL_GeometryData`` (SSL-Vision);
* ``ssl_protocol.state``: ``Referee`` and the game events (the game controller);
* ``ssl_protocol.ci``: the game controller's CI mode (``CiInput``, ``CiOutput``);
* ``ssl_protocol.sim``: the simulation protocol (``RobotControl``, ``RobotControlResponse``,
  ``SimulatorCommand``, ``SimulatorResponse``).

Licensed GPL-3.0, as the ``.proto`` files they come from.
"""

#: Where the classes come from: the repositories and the commits of their ``.proto`` files.
SOURCES = {
    "RoboCup-SSL/ssl-game-controller": "v3.23.0 (66b8255dc22a04ef5b850dad40cc7f165be4bf83)",
    "RoboCup-SSL/ssl-simulation-protocol": "65ad6148671a2b1ead58be0b625ca0f8d269ced8",
}
