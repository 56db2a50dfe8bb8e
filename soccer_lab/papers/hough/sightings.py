"""The setting of Xu et al.'s (2012) Hough-fusion reproduction: its Table 1 geometry (five
robots, the ball's straight path), how the robots see the ball (a head camera aimed at it, or
the paper's reading: noise on each robot's estimate) and the fusion of their sighting lines
(see :mod:`soccer_lab.papers.hough`)."""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

from estimators import HeadCamera, fusion_weights, hough_fuse

__all__ = ["ROBOTS_MM", "PATH_MM", "WEIGHTINGS", "PAPER_SIGMA", "MM", "ball_path", "fuse",
           "sightings_camera", "head_sightings", "sightings_paper", "sightings_walking"]

#: Table 1 of Xu et al. (2012) (millimetres): robot positions, the ball's straight path.
ROBOTS_MM = np.array([[1000, 3500], [250, 2000], [1750, 350], [4250, 2400], [5600, 3900]],
                     dtype=float)
PATH_MM = (np.array([3000.0, 3200.0]), np.array([4500.0, 1200.0]))
#: The weightings of the sighting lines (:func:`estimators.fusion_weights`): equal, ``1/L``
#: and ``1/L^2``.
WEIGHTINGS = ("equal", "inverse", "inverse_square")
#: The paper's simulated noise [m]: 192 mm (section 4.3).
PAPER_SIGMA = 0.192
#: Millimetres per metre, for the tables.
MM = 1000.0


def ball_path(step_mm: float = 50.0) -> np.ndarray:
    """The ball's positions [mm] along :data:`PATH_MM`, ``step_mm`` apart (both ends
    included), as an ``(n, 2)`` array."""
    a, b = PATH_MM
    n = int(round(np.hypot(*(b - a)) / step_mm))
    return a + (b - a) * np.linspace(0.0, 1.0, n + 1)[:, None]


def fuse(pos: np.ndarray, est: np.ndarray, weighting: str, fallbacks: list[int]
         ) -> np.ndarray:
    """Hough fusion of the lines from ``pos`` towards ``est``; for (nearly) parallel lines
    (the ball on the line through two robots) the weighted mean of the robots' own estimates,
    counted in ``fallbacks``."""
    dist = np.hypot(*(est - pos).T)
    w = fusion_weights(dist, weighting)
    try:
        return hough_fuse(pos, est - pos, weights=w)
    except ValueError:
        fallbacks[0] += 1
        return (w[:, None] * est).sum(axis=0) / w.sum()


def sightings_camera(ball: np.ndarray, robots: np.ndarray, rng: np.random.Generator,
                     cam: HeadCamera, pixel_sigma: float, pose_sigma: float,
                     heading_sigma: float, sway_sigma: float
                     ) -> tuple[np.ndarray, np.ndarray]:
    """Per robot: its estimated position and its estimate of the ball (field frame, m), the
    head's true tilt off the believed one by ``N(0, sway_sigma^2)``."""
    return head_sightings(ball, robots, rng, cam, pixel_sigma, pose_sigma, heading_sigma,
                          lambda: (0.0, rng.normal(0.0, sway_sigma)))


def head_sightings(ball: np.ndarray, robots: np.ndarray, rng: np.random.Generator,
                   cam: HeadCamera, pixel_sigma: float, pose_sigma: float,
                   heading_sigma: float, sway: Callable[[], tuple[float, float]]
                   ) -> tuple[np.ndarray, np.ndarray]:
    """Per robot: its estimated position and its estimate of the ball (field frame, m) from
    its head camera aimed at the ball, the head's true pan and tilt off the believed ones by
    ``sway()`` [rad] (drawn per robot), pixel noise, and the pose errors."""
    est_pos = robots + rng.normal(0.0, pose_sigma, robots.shape)
    est_ball = np.empty_like(robots)
    for i, p in enumerate(robots):
        heading = rng.uniform(-math.pi, math.pi)  # the body faces anywhere; the head turns
        rel = ball - p
        c, s = math.cos(heading), math.sin(heading)
        local = np.array([[c * rel[0] + s * rel[1], -s * rel[0] + c * rel[1]]])
        dist = float(np.hypot(*rel))
        pan = math.atan2(local[0, 1], local[0, 0])
        tilt = math.atan2(cam.height, dist)  # the ball centred in the image
        d_pan, d_tilt = sway()
        uv, _ = cam.project(local, pan + d_pan, tilt + d_tilt)  # the swaying head
        uv = uv + rng.normal(0.0, pixel_sigma, uv.shape)
        g = cam.ground_point(uv, pan, tilt)[0]  # with the head angles the robot believes
        if not np.all(np.isfinite(g)):  # above the horizon: no range, only a bearing
            g = local[0] * (cam.height / math.tan(0.5 * cam.vfov)) / dist
        h_est = heading + rng.normal(0.0, heading_sigma)  # the robot's belief
        ce, se = math.cos(h_est), math.sin(h_est)
        est_ball[i] = est_pos[i] + [ce * g[0] - se * g[1], se * g[0] + ce * g[1]]
    return est_pos, est_ball


def sightings_paper(ball: np.ndarray, robots: np.ndarray, rng: np.random.Generator,
                    sigma: float) -> tuple[np.ndarray, np.ndarray]:
    """The paper's reading: per robot its true position and its estimate of the ball with
    Gaussian noise of ``sigma`` [m] per axis."""
    return robots.copy(), ball + rng.normal(0.0, sigma, robots.shape)


def sightings_walking(ball: np.ndarray, robots: np.ndarray, rng: np.random.Generator,
                      camera: HeadCamera, pixel_sigma: float, sway_pan: float,
                      sway_tilt: float, pose_sigma: float, heading_sigma: float
                      ) -> tuple[np.ndarray, np.ndarray]:
    """(d): :func:`sightings_camera` with the gait's sway of a walking robot: at a gait phase
    ``phi`` uniform in [0, 2) steps, the camera's true pan and tilt are the commanded ones plus
    ``sway_pan sin(pi phi)`` and ``sway_tilt sin(2 pi phi)`` [rad] (:mod:`soccer_env.sim.walk`
    at full activity), which the robot does not know of."""

    def sway() -> tuple[float, float]:
        phase = rng.uniform(0.0, 2.0)
        return sway_pan * math.sin(math.pi * phase), sway_tilt * math.sin(2.0 * math.pi * phase)

    return head_sightings(ball, robots, rng, camera, pixel_sigma, pose_sigma, heading_sigma,
                          sway)
