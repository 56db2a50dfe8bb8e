"""Perception: the pipelines that turn sensor output into what a team or a robot believes.

* :mod:`~soccer_env.perception.base`: configuration (:class:`PerceptionConfig`);
* :mod:`~soccer_env.perception.options`: the option families, one registry each (ball
  filters, ball trackers, fusion, localization, detectors);
* :mod:`~soccer_env.perception.overhead`: SSL teams: truth, raw detections, filtered beliefs;
* :mod:`~soccer_env.perception.humanoid` and :mod:`~soccer_env.perception.brain`: humanoid
  teams: localization, radio, Hough fusion, particle tracking per robot;
* :mod:`~soccer_env.perception.pixels`: trackers on rendered images;
* :mod:`~soccer_env.perception.match`: both teams of a world.

Perception reads the world state, head states and odometry; it never writes the simulation.
"""

from soccer_env.perception.base import OBS_MODES, Perception, PerceptionConfig
from soccer_env.perception.match import MatchPerception
from soccer_env.perception.options import (
    BALL_FILTERS,
    BALL_TRACKERS,
    DETECTORS,
    FUSIONS,
    LOCALIZATIONS,
    ROBOT_PREDICTIONS,
)
from soccer_env.perception.overhead import (
    FilteredPerception,
    RawPerception,
    TruthPerception,
    make_perception,
)

__all__ = ["OBS_MODES", "BALL_FILTERS", "DETECTORS", "LOCALIZATIONS", "FUSIONS",
           "BALL_TRACKERS", "ROBOT_PREDICTIONS", "Perception", "PerceptionConfig",
           "TruthPerception", "RawPerception", "FilteredPerception", "make_perception",
           "MatchPerception"]
