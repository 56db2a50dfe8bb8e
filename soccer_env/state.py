"""Snapshots that flow between the layers, each immutable or a read-only copy:

* :class:`WorldState`: the truth at one instant (from the simulation);
* :class:`HeadState`: every robot's head servos, gait sway and blindness (from the walk
  engine; what the head cameras read);
* :class:`BodyState`: what the robots' bodies report (heads, odometry, gait, falls; from the
  walk engine; what a humanoid's perception reads besides its camera frames);
* :class:`Belief`: what a team or a robot believes, laid out like the truth (from perception;
  what the observation builder reads), with how sure it is (:class:`BeliefQuality`, when the
  environment's belief features ask for it) and, for drawing, how it is spread
  (:class:`BeliefSpread`, filled by the renderer's scene only);
* :class:`Attention`: what a robot believes that its head controller needs (from perception;
  what the simulation's head control reads).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

__all__ = ["WorldState", "HeadState", "BodyState", "Belief", "BeliefQuality", "BeliefSpread",
           "Attention", "state_dict", "BALL_FIELDS", "ROBOT_FIELDS", "BALL_STATUSES"]

#: Columns of :attr:`WorldState.ball`.
BALL_FIELDS = ("x", "y", "z", "vx", "vy", "vz")
#: Columns of :attr:`WorldState.robots`.
ROBOT_FIELDS = ("x", "y", "theta", "vx", "vy", "omega")


class WorldState(NamedTuple):
    """The truth at one instant, in the field frame.

    Attributes:
        time: simulated time since the world was reset [s].
        ball: ``(6,)`` ball ``x, y`` [m], height ``z`` of its lowest point above the carpet
            [m], velocity ``vx, vy, vz`` [m/s].
        robots: ``(N, 6)`` robot poses ``x, y, theta`` [m, rad] and velocities
            ``vx, vy, omega`` [m/s, rad/s], field frame, one row per robot in ``names`` order.
        names: robot names (``blue_0``, ..., ``yellow_0``, ...).
        teams: ``(N,)`` 0 for blue, 1 for yellow.

    The arrays are read-only copies; holding a snapshot is safe while the world steps on.
    (A ``NamedTuple``: immutable, and several times cheaper to create than a frozen dataclass,
    which matters since every step makes one.)
    """

    time: float
    ball: np.ndarray
    robots: np.ndarray
    names: tuple[str, ...]
    teams: np.ndarray

    def truth_dict(self) -> dict[str, object]:
        """The ``info["truth"]`` entry: ball and every robot in field coordinates.

        Keys: ``time`` [s]; ``ball_position`` (x, y) [m]; ``ball_velocity`` (vx, vy) [m/s];
        ``ball_height`` [m]; ``robot_pose`` {name: (x, y, theta)}; ``robot_velocity``
        {name: (vx, vy, omega)}. ``info["estimate"]`` has the same keys.
        """
        return state_dict(self.time, self.ball, self.robots, self.names)


def state_dict(time: float, ball: np.ndarray, robots: np.ndarray, names: tuple[str, ...]
               ) -> dict[str, object]:
    """Ball and robot arrays (layouts :data:`BALL_FIELDS`, :data:`ROBOT_FIELDS`) as the dict of
    ``info["truth"]`` / ``info["estimate"]`` (values are views of the arrays)."""
    return {
        "time": time,
        "ball_position": ball[0:2],
        "ball_velocity": ball[3:5],
        "ball_height": float(ball[2]),
        "robot_pose": {n: robots[i, 0:3] for i, n in enumerate(names)},
        "robot_velocity": {n: robots[i, 3:6] for i, n in enumerate(names)},
    }


class HeadState(NamedTuple):
    """The heads of ALL robots of the world at one step (from the walk engine), arrays ``(N,)``.

    Attributes:
        pan, tilt: head servo angles as the robot knows them [rad]; pan positive to the left,
            tilt positive looking down (as :class:`estimators.HeadCamera`).
        sway_pan, sway_tilt: the gait's sway of the camera's true orientation [rad], unknown
            to the robot (the true angles are ``pan + sway_pan``, ``tilt + sway_tilt``).
        blind: the robot sees nothing (fallen or getting up).
    """

    pan: np.ndarray
    tilt: np.ndarray
    sway_pan: np.ndarray
    sway_tilt: np.ndarray
    blind: np.ndarray

    @classmethod
    def steady(cls, n: int, pan: float = 0.0, tilt: float = 0.0) -> HeadState:
        """``n`` heads at ``pan``, ``tilt`` [rad], without sway, none blind."""
        return cls(np.full(n, float(pan)), np.full(n, float(tilt)), np.zeros(n), np.zeros(n),
                   np.zeros(n, dtype=bool))


#: States of a ball track, in the order of the belief features' one-hot entries:
#: ``tracking`` (measurements arrive), ``coasting`` (none in the latest frame period: the
#: estimate is a prediction), ``reset`` (the track (re)started a few measurements ago: its
#: velocity is still poorly known), ``lost`` (never seen, or not for a long time).
BALL_STATUSES = ("tracking", "coasting", "reset", "lost")


class BeliefQuality(NamedTuple):
    """How sure a belief is (what the belief features of the observation read).

    Attributes:
        ball_sigma: standard deviation of the believed ball position [m] per axis
            (``sqrt`` of the mean of the two axes' variances); ``inf`` when unknown.
        ball_velocity_sigma: the same for its velocity [m/s].
        ball_age: time since the capture of the latest ball measurement the robot itself
            made or (SSL) its team's vision delivered [s]; ``inf`` if none yet.
        ball_status: index in :data:`BALL_STATUSES`.
        pose_sigma: ``(N, 2)`` spread of each robot's believed pose: position [m] per axis
            and heading [rad] (a robot's own row is what its observation reads).
        fused_age: (humanoids) time since the latest fused estimate of the team's sightings
            [s]; for SSL teams, whose vision is fused already, ``ball_age``.
        seen_by: (humanoids) how many robots' sightings went into the latest fused estimate;
            for SSL teams 1 while the vision sees the ball, else 0.
        ball_measured: field-frame ``(x, y)`` [m] of the latest ball measurement: the robot's
            own latest sighting (humanoids; None when it had no range) or the vision's latest
            detection (SSL teams); None if there is none. Beside the belief it shows what the
            filter has not (yet) taken in: a kicked ball's detections that the tracker still
            rejects or smooths away.
        ball_modes: the probabilities of the ball filter's motion modes at the belief's time
            (an interacting multiple model filter's: rest, rolling, maneuver; see
            :attr:`estimators.IMMBall.MODES`), or None for a filter without modes.
    """

    ball_sigma: float
    ball_velocity_sigma: float
    ball_age: float
    ball_status: int
    pose_sigma: np.ndarray
    fused_age: float
    seen_by: int
    ball_measured: np.ndarray | None = None
    ball_modes: np.ndarray | None = None


class BeliefSpread(NamedTuple):
    """How a belief is spread, for drawing it: the filters' position covariances and
    particles, read without changing them (nothing an observation reads comes from here).

    A 2-sigma ellipse of a covariance ``C`` has the semi-axes ``2 sqrt(lambda_k)`` along the
    eigenvectors of ``C`` (``lambda_k`` its eigenvalues). Where a filter keeps only a scalar
    standard deviation ``sigma`` per axis (the SSL robot filters' per-axis position filters,
    raw detections' sensor noise, dead reckoning's grown variance) the covariance is
    ``sigma^2 I`` and the ellipse a circle of radius ``2 sigma``.

    Attributes:
        ball: ``(2, 2)`` covariance of the believed ball position ``(x, y)`` [m^2], or None
            when the filter has none (never seen, or no filter).
        robots: ``(N, 2, 2)`` covariances of the believed robot positions [m^2], one per
            robot in the belief's order; NaN where not modelled (robots never seen, a
            humanoid's team-mates and opponents).
        ball_particles: ``(K, 2)`` positions [m] of a particle ball tracker's particles,
            moved by the mean's predicted displacement from the filter's time to the
            belief's, or None.
        pose_particles: ``(K, 3)`` particles ``x, y, theta`` [m, m, rad] of the robot's own
            self-localization (a humanoid's KLD particle filter, at its latest camera frame),
            or None.
        robot: the robot whose belief this is (its index in the world), or None for a team's
            shared belief.
    """

    ball: np.ndarray | None
    robots: np.ndarray
    ball_particles: np.ndarray | None = None
    pose_particles: np.ndarray | None = None
    robot: int | None = None


class Belief(NamedTuple):
    """A belief laid out like :class:`~soccer_env.state.WorldState`'s arrays: ``ball`` (6,)
    ``x, y, z, vx, vy, vz`` and ``robots`` (N, 6) ``x, y, theta, vx, vy, omega``, at
    ``time``; ``quality`` says how sure it is (None unless the environment's belief features
    ask for it); ``spread`` its covariances and particles (:class:`BeliefSpread`; None
    except in what an environment hands its renderer)."""

    time: float
    ball: np.ndarray
    robots: np.ndarray
    quality: BeliefQuality | None = None
    spread: BeliefSpread | None = None


class BodyState(NamedTuple):
    """What every robot's own body reports at one step (the walk engine's view of the
    humanoids; SSL robots report zeros and are never fallen), per robot in world order.

    Attributes:
        heads: the :class:`HeadState` of every robot.
        odometry: the displacement ``(dx, dy, dtheta)`` [m, m, rad] that the robot's walk
            engine believes it made over the last step, in the body frame at the step's start.
        gait: the gait's body-frame velocity ``(vx, vy, omega)`` [m/s, rad/s].
        fallen: the robot is down (fallen or getting up): it neither acts, sees nor sends.
        lying: direction [rad, body frame] of a fallen robot's body once it lies on the ground,
            else None.
    """

    heads: HeadState
    odometry: tuple[tuple[float, float, float], ...]
    gait: tuple[tuple[float, float, float], ...]
    fallen: tuple[bool, ...]
    lying: tuple[float | None, ...]


class Attention(NamedTuple):
    """What a robot's head controller needs to know of its belief at one instant.

    Attributes:
        pose: its believed pose ``(x, y, theta)`` [m, m, rad].
        ball: the believed ball ``(x, y, vx, vy)`` [m, m/s], or None if never seen.
        ball_age: time since the latest sighting of the ball, its own or a team-mate's [s].
        landmark_age: time since it last saw a landmark [s].
    """

    pose: np.ndarray
    ball: np.ndarray | None
    ball_age: float
    landmark_age: float
