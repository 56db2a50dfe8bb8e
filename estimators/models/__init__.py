"""Models shared by the sensors (to simulate) and the filters (to predict and weigh).

* :mod:`~estimators.models.motion`: motion models ``transition(x, dt) -> (f(x), F, Q)``: the
  ball decelerated by carpet friction (:class:`FrictionBallMotion`), constant velocity
  (:class:`ConstantVelocityMotion`), and :func:`wrap_angle`;
* :mod:`~estimators.models.measurement`: measurement models (:class:`PositionMeasurement`,
  :class:`PoseMeasurement`), the same objects that a sensor uses to simulate a detection;
* :mod:`~estimators.models.ball`: the closed-form rolling ball (:class:`FrictionBallModel`),
  for prediction over any horizon (a goalkeeper's interception);
* :mod:`~estimators.models.camera`: the pinhole head camera and its ground projection
  (:class:`HeadCamera`).
"""

from .ball import FrictionBallModel
from .camera import HeadCamera
from .measurement import MIN_SIGMA_THETA, MIN_SIGMA_XY, PoseMeasurement, PositionMeasurement
from .motion import PAPER_CYCLE, ConstantVelocityMotion, FrictionBallMotion, wrap_angle

__all__ = [
    "FrictionBallMotion",
    "ConstantVelocityMotion",
    "wrap_angle",
    "PAPER_CYCLE",
    "PositionMeasurement",
    "PoseMeasurement",
    "MIN_SIGMA_XY",
    "MIN_SIGMA_THETA",
    "FrictionBallModel",
    "HeadCamera",
]
