"""Presets: the single source of truth for every physical and sensor constant of the package.

Each preset names its source. Units are SI throughout (metres, seconds, kilograms, radians).
A preset is a frozen dataclass in a table, a :class:`~estimators.registry.Registry` of one
family (:data:`FIELDS`, :data:`BALLS`, :data:`ROBOTS`, :data:`VISION`, :data:`HEAD_CAMERAS`,
:data:`RADIO_PRESETS`, :data:`OVERHEAD_FRAMES`, :data:`HEAD_FRAMES`, :data:`RULES`) that
describes each preset by its source; register your own with
``TABLE.register(name, spec, source)``. Derive a variant with the function of its table
(:func:`field`, :func:`ball`, :func:`robot`, :func:`vision`, :func:`head_camera`,
:func:`radio`, :func:`overhead_frame`, :func:`head_frame`, :func:`rules`), which validates the
overrides::

    >>> from soccer_env import presets
    >>> presets.robot("ssl", kick_speed_cap=8.0).kick_speed_cap
    8.0

* :mod:`~soccer_env.presets.world`: fields, balls, SSL and humanoid robots;
* :mod:`~soccer_env.presets.sensors`: overhead vision (SSL), head cameras (humanoids), the team
  radio;
* :mod:`~soccer_env.presets.images`: nominal colours and the appearance of rendered frames;
* :mod:`~soccer_env.presets.rules`: the numbers of the game flow's rule books (:data:`RULES`).

Conventions: the field frame has its origin at the centre spot, +x towards the goal that the
blue team attacks, +y to the left of +x, angles counter-clockwise in radians. Blue defends the
goal at ``x = -length / 2``.
"""

from soccer_env.presets.images import (
    COLOURS,
    HEAD_FRAMES,
    OVERHEAD_FRAMES,
    RGB,
    HeadFrameSpec,
    OverheadFrameSpec,
    head_frame,
    overhead_frame,
)
from soccer_env.presets.rules import RULES, HumanoidRuleSpec, RuleSpec, rules
from soccer_env.presets.sensors import (
    HEAD_CAMERAS,
    RADIO_PRESETS,
    SENSOR_PRESETS,
    VISION,
    HeadCameraSpec,
    RadioSpec,
    VisionSpec,
    head_camera,
    radio,
    vision,
)
from soccer_env.presets.world import (
    BALLS,
    DEFAULT_FIELDS,
    FIELDS,
    GRAVITY,
    ROBOTS,
    BallSpec,
    FieldSpec,
    HumanoidRobotSpec,
    RobotSpec,
    SSLRobotSpec,
    ball,
    default_field,
    field,
    robot,
)

__all__ = [
    "FieldSpec", "BallSpec", "SSLRobotSpec", "HumanoidRobotSpec", "RobotSpec", "FIELDS", "BALLS",
    "ROBOTS", "DEFAULT_FIELDS", "field", "ball", "robot", "default_field", "GRAVITY",
    "VisionSpec", "VISION", "vision", "HeadCameraSpec", "HEAD_CAMERAS", "head_camera",
    "RadioSpec", "RADIO_PRESETS", "radio", "RGB", "COLOURS", "OverheadFrameSpec", "OVERHEAD_FRAMES",
    "overhead_frame", "HeadFrameSpec", "HEAD_FRAMES", "head_frame", "RuleSpec", "HumanoidRuleSpec",
    "RULES", "rules", "SENSOR_PRESETS",
]
