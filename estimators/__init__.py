"""Estimators and motion models for robot soccer, usable without the environment.

Everything here takes and returns numpy arrays, depends on numpy only, and never on
``soccer_env``. Random draws come from explicit ``numpy.random.Generator`` arguments.
"""

from .ball_models import FrictionBallModel

__all__ = ["FrictionBallModel"]
