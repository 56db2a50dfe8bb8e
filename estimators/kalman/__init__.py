"""Kalman filters: the filter core, its blocks, and the trackers built on its equations.

* :mod:`~estimators.kalman.core`: :class:`KalmanFilter`, one set of equations for the linear
  filter and the EKF (a building block: ``predict`` / ``update`` / ``innovation``);
* :mod:`~estimators.kalman.blocks`: the same steps as functions in plain floats for the ball
  state (``predict_covariance``, ``innovation``, ``update``, ...), and on rows for many balls,
  what the ball trackers' updates are written in;
* :mod:`~estimators.kalman.ball`: the EKF of Zhao, Wang and Li (2012) for delayed
  overhead-camera detections (:class:`BallTracker`, :class:`BallFilterConfig`);
  :mod:`~estimators.kalman.least_squares`: its least-squares baseline
  (:class:`LeastSquaresBall`); :mod:`~estimators.kalman.ball_batch`: the EKF of many
  environments as arrays (:class:`BallTrackerBatch`); :mod:`~estimators.kalman.ball_kernels`:
  the EKF's frame, prediction and eq. 19 as compiled kernels over rows of tracks, which both
  run;
* :mod:`~estimators.kalman.kick`: the kick-aware ball tracker (:class:`KickAwareBall`), each
  motion since a kick or a collision fitted whole to the two-phase friction model
  (:mod:`~estimators.kalman.segments`);
* :mod:`~estimators.kalman.imm`: the interacting multiple model ball tracker (:class:`IMMBall`),
  rest, rolling and maneuver filters weighed by how well each predicted the detections, their
  switching a Markov chain (:mod:`~estimators.kalman.modes`), its prediction and update
  compiled (:mod:`~estimators.kalman.imm_kernels`);
* :mod:`~estimators.kalman.lines`: a humanoid team's kick-aware ball tracker
  (:class:`LineBallTracker`), fed each robot's sighting line at its capture time, a kick
  hypothesis beside the track with its kick time searched (:mod:`~.line_kernels`);
* :mod:`~estimators.kalman.robots`: decoupled constant-velocity pose trackers for many robots
  (:class:`RobotTracker`); :mod:`~estimators.kalman.driven`: a team's own robots predicted
  from the commands it sent them instead (:class:`CommandHistory`, a Smith predictor).

The ball trackers are built from the shared parts of :mod:`estimators.tracking` (gate, track
initiator, replay buffer, track quality) and differ in their motion models and updates. The
ball and robot trackers have batched forms (:class:`BallTrackerBatch`,
:class:`RobotTrackerBatch`): many independent trackers as arrays, updated by one kernel call
per batch of frames; the single trackers call the same kernels as batches of one.
"""

from ..tracking import CHI2_2DOF_999
from .ball import BallFilterConfig, BallTrack, BallTracker
from .ball_batch import BallTrackerBatch
from .core import KalmanFilter, check_matrix, check_vector
from .driven import CommandHistory
from .imm import IMMBall
from .kick import KickAwareBall
from .least_squares import LeastSquaresBall
from .lines import LineBallTracker, SightingNoise
from .robots import RobotTracker, RobotTrackerBatch

__all__ = [
    "KalmanFilter",
    "check_vector",
    "check_matrix",
    "BallFilterConfig",
    "BallTrack",
    "BallTracker",
    "BallTrackerBatch",
    "LeastSquaresBall",
    "KickAwareBall",
    "IMMBall",
    "LineBallTracker",
    "SightingNoise",
    "CHI2_2DOF_999",
    "RobotTracker",
    "RobotTrackerBatch",
    "CommandHistory",
]
