"""Kalman filters: the filter core and the trackers built on its equations.

* :mod:`~estimators.kalman.core`: :class:`KalmanFilter`, one set of equations for the linear
  filter and the EKF (a building block: ``predict`` / ``update`` / ``innovation``);
* :mod:`~estimators.kalman.ball`: ball trackers for delayed overhead-camera detections, the
  EKF of Zhao, Wang and Li (2012; :class:`BallTracker`, :class:`BallFilterConfig`) and
  its least-squares baseline (:class:`LeastSquaresBall`);
* :mod:`~estimators.kalman.kick`: the kick-aware ball tracker (:class:`KickAwareBall`), each
  motion since a kick or a collision fitted whole to the two-phase friction model;
* :mod:`~estimators.kalman.imm`: the interacting multiple model ball tracker (:class:`IMMBall`),
  rest, rolling and maneuver filters weighed by how well each predicted the detections;
* :mod:`~estimators.kalman.robots`: decoupled constant-velocity pose trackers for many robots
  (:class:`RobotTracker`).

The ball and robot trackers have batched twins (:class:`BallTrackerBatch`,
:class:`RobotTrackerBatch`): many independent trackers as arrays, updated by one array
operation per batch of frames, equal to the single trackers bit for bit.
"""

from .ball import CHI2_2DOF_999, BallFilterConfig, BallTracker, BallTrackerBatch, LeastSquaresBall
from .core import KalmanFilter, check_matrix, check_vector
from .imm import IMMBall
from .kick import KickAwareBall
from .robots import RobotTracker, RobotTrackerBatch

__all__ = [
    "KalmanFilter",
    "check_vector",
    "check_matrix",
    "BallFilterConfig",
    "BallTracker",
    "BallTrackerBatch",
    "LeastSquaresBall",
    "KickAwareBall",
    "IMMBall",
    "CHI2_2DOF_999",
    "RobotTracker",
    "RobotTrackerBatch",
]
