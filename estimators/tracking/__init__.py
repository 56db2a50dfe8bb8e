"""The parts the ball trackers are built from, as Stone Soup composes a tracker from an
initiator, a gate, an updater and a deleter.

* :mod:`~estimators.tracking.gate`: :class:`Gate`, which of a frame's detections is the
  tracked ball (nearest neighbour within a chi-square quantile) and whether a rejected one is
  the ball kicked where it is;
* :mod:`~estimators.tracking.initiator`: :class:`TrackInitiator`, a new track from gated-out
  detections that agree with each other, and :func:`prior_gain`, the finite-difference
  velocity combined with a prior;
* :mod:`~estimators.tracking.replay`: :class:`ReplayBuffer`, latency compensation: frames
  processed at their capture time, late ones replayed in order;
* :mod:`~estimators.tracking.quality`: :class:`TrackQualityMixin`, the one implementation of
  :class:`~estimators.protocol.TrackQuality` (``covariance``, ``last_fused``,
  ``since_start``, with ``initialized`` and ``time``) from a track's :class:`TrackTimes`.

The Kalman blocks the trackers' updates are written in are
:mod:`estimators.kalman.blocks`. A ball tracker then supplies its motion model and its
update: :class:`~estimators.BallTracker` (the friction EKF), :class:`~estimators.IMMBall`
(three mode-matched Kalman filters mixed) and :class:`~estimators.KickAwareBall` (a
least-squares fit of each motion) share the gate, the initiator's agreement and the quality;
the first two also the replay buffer and the initiator's candidates.
"""

from .gate import CHI2_2DOF_999, MAX_SPEED_CHANGE, Gate
from .initiator import Candidates, TrackInitiator, prior_gain
from .quality import TrackQualityMixin, TrackTimes
from .replay import ReplayBuffer

__all__ = [
    "Gate",
    "CHI2_2DOF_999",
    "MAX_SPEED_CHANGE",
    "TrackInitiator",
    "Candidates",
    "prior_gain",
    "ReplayBuffer",
    "TrackQualityMixin",
    "TrackTimes",
]
