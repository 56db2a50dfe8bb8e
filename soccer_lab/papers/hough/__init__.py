"""Cooperative ball localization of Xu, Xie, Wang and Ni (2012): Hough-space fusion
on its Table 1 geometry.

``soccer-env paper hough``: five robots at the paper's positions (a 6 m x 4 m field), the ball
moving in 50 mm steps in a straight line from (3000, 3200) to (4500, 1200) mm. Each robot's
sighting becomes a line from its (estimated) position towards its estimate of the ball, and
:func:`estimators.hough_fuse` fuses the lines with equal, ``1/L`` and ``1/L^2`` weights.
Two noise models:

* **head camera** (ours): each robot turns its head (:class:`estimators.HeadCamera`, 0.56 m,
  51 degrees, 720 x 625) to look at the ball, the ball's pixel gets Gaussian noise
  (``pixel_sigma``), the gait sways the head so that the true tilt differs from the one the
  robot assumes by ``sway_sigma`` (our assumption: a walking KidSize torso rocks by a few
  degrees), and the robot projects the pixel back onto the ground with its assumed tilt; its
  own pose is known to ``pose_sigma`` (position, m) and ``heading_sigma`` (rad), as a
  localization would give. A
  pixel error moves the ground point along the ray by about ``d^2 / (h f)``, so far sightings
  are poor in range but good in bearing: fusing bearings from several robots beats any one
  robot's own estimate.
* **the paper's reading**: Gaussian noise of 192 mm on each robot's estimate of the ball (the
  paper does not say exactly what it perturbs; this is one reading), lines from the true robot
  positions.

Reports the mean error of the fused position along the path (``trials`` noise draws per ball
position), the best single robot's own estimate, and the error against the number of robots
(1 to 5; for one robot, its own estimate), beside the paper's figures.

**Why the paper's 87 / 118 = 0.74 is not met: the noise models that bound it.** A second table
(``seeds`` independent seeds of ``trials`` draws per ball position each) runs four noise
models on the same geometry and fuses each draw with every weighting: equal, ``1/L``,
``1/L^2`` and ``"inverse_variance"``, ``K_i = 1 / s_i^2`` with
``s_i^2 = D_i^2 (sigma_b^2 + sigma_h^2) + sigma_p^2`` the variance of line ``i``'s
perpendicular offset at the fused point (derived in :mod:`estimators.fusion.hough`: the
Gauss-Markov weights of the line fit, so the weighting that is optimal for each model once its
sigmas are put in; ``D_i`` taken at the ``1/L`` fused point, then fused again, as
:func:`estimators.fuse_sightings` does). ``L_i`` is the robot's own range estimate
``|estimate - position|``, as in the first table.

* **(a) isotropic**: Gaussian noise of ``sigma`` per axis on each robot's estimate of the ball,
  lines from the true robot positions (the paper's reading above; also with the paper's 192 mm
  read as the 2-D RMS, ``sigma = 192 / sqrt 2`` mm). A line's offset at the ball is the
  estimate's error across the line, ``s_i = sigma`` whatever the distance: equal weights are
  optimal and ``1/L`` can only hurt.
* **(b) bearing only**: each robot's sighting direction has Gaussian error ``sigma_b`` (the
  paper's 192 mm over the mean robot-ball distance along the path, 2.59 m: 4.3 degrees), its
  position and the range are exact, so a single robot's error is its lateral error alone.
  ``s_i = D_i sigma_b``: ``1/L^2`` is optimal. (Isotropic noise on each estimate with a
  standard deviation proportional to the distance, the paper's own reason for weighting,
  gives the lines the same offsets to first order, so the same fused errors.)
* **(c) bearing and pose**: (b) plus a Gaussian error of 192 mm per axis on each robot's
  position (the paper's "nodes" read as the robots), the range exact from the believed
  position. ``s_i^2 = D_i^2 sigma_b^2 + sigma_p^2``, the two terms equal at the mean distance.
  (A heading error turns the line about the robot as a bearing error does, so it is folded
  into ``sigma_b`` here.)
* **(d) our head camera, walking**: as the head-camera model above, but with the robot
  preset's gait sway (``robot``, :data:`soccer_env.presets.ROBOTS`: ``sway_pan`` in yaw,
  ``sway_tilt`` in pitch, at a uniformly random gait phase of a walking robot, as
  :mod:`soccer_env.sim.walk` sways the torso) in place of the Gaussian tilt sway, and the
  geometry and pixel noise of the preset's camera; pose errors ``pose_sigma`` and
  ``heading_sigma``. The pan sway is a bearing error the robot does not know of (RMS
  ``sway_pan / sqrt 2``); the tilt sway and the vertical pixel noise move the ground point
  along the sighting line (the range error growing with ``d^2``) and so never move the line.
  ``sigma_b^2 = sway_pan^2 / 2 + (pixel_sigma / f)^2``, ``sigma_p = pose_sigma``,
  ``sigma_h = heading_sigma``.

Every row prints each robot's own error, the best single robot (the one with the smallest mean
error, chosen after the fact), the fused errors, and the ratios (mean and standard deviation
over the seeds, each seed's ratio taken on the same draws). The report ends with what a team
with our head camera should use: the weighting with the smallest error in (d), and by how much
team fusion beats the best single robot.

**Code.** :mod:`.sightings` (the Table 1 geometry, the robots' sightings under each noise model
and the fusion of their lines), :mod:`.simulation` (the first table), :mod:`.models` (the noise
models that bound the claim), :mod:`.report` (the paper's figures, the tables and the figure);
:func:`run` checks the :class:`Settings`, runs both and writes the report.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from soccer_env.presets import ROBOTS, HumanoidRobotSpec
from soccer_lab.papers.common import check_count, write_report
from soccer_lab.papers.hough import report
from soccer_lab.papers.hough.models import MODEL_WEIGHTINGS, NOISE_MODELS, simulate_models
from soccer_lab.papers.hough.report import HARDWARE_BASELINE_READINGS, PAPER
from soccer_lab.papers.hough.sightings import PATH_MM, ROBOTS_MM
from soccer_lab.papers.hough.simulation import simulate

__all__ = ["run", "Settings", "ROBOTS_MM", "PATH_MM", "PAPER", "HARDWARE_BASELINE_READINGS",
           "NOISE_MODELS", "MODEL_WEIGHTINGS"]


@dataclass(frozen=True)
class Settings:
    """What one run simulates (validated on construction).

    Attributes:
        out: the output folder.
        trials: noise draws per ball position (>= 1).
        seed: seeds the noise of both models.
        pixel_sigma: the ball's pixel noise of the head-camera model [px].
        pose_sigma, heading_sigma: the error of a robot's belief about its position [m] and
            heading [rad].
        sway_sigma: the gait's tilt sway that the robot does not know of [rad] (the first
            table's head camera).
        seeds: independent seeds of the noise-model table (1..100), for the spread of its
            ratios.
        robot: the humanoid robot preset whose gait sway and camera the noise model (d)
            takes (a name of :data:`soccer_env.presets.ROBOTS` of kind ``"humanoid"``).
    """

    out: Path
    trials: int = 20
    seed: int = 0
    pixel_sigma: float = 2.0
    pose_sigma: float = 0.03
    heading_sigma: float = math.radians(1.0)
    sway_sigma: float = math.radians(2.0)
    seeds: int = 5
    robot: str = "humanoid-2012"

    def __post_init__(self) -> None:
        trials = self.trials
        if isinstance(trials, bool) or int(trials) != trials or trials < 1:
            raise ValueError(f"trials must be an integer >= 1, got {trials!r}")
        check_count("seeds", self.seeds, 1, 100)
        humanoids = [k for k, v in ROBOTS.items() if isinstance(v, HumanoidRobotSpec)]
        if self.robot not in humanoids:
            raise ValueError(f"robot must be a humanoid robot preset, one of {humanoids}, got "
                             f"{self.robot!r}")
        for name in ("pixel_sigma", "pose_sigma", "heading_sigma", "sway_sigma"):
            v = getattr(self, name)
            if not (math.isfinite(v) and v >= 0.0):
                raise ValueError(f"{name} must be >= 0, got {v!r}")


def run(out: str | Path = "paper_output", trials: int = 20, seed: int = 0,
        pixel_sigma: float = 2.0, pose_sigma: float = 0.03,
        heading_sigma: float = math.radians(1.0), sway_sigma: float = math.radians(2.0),
        seeds: int = 5, robot: str = "humanoid-2012") -> dict[str, Any]:
    """Run both noise models of the first table and the noise models that bound the paper's
    claim; write ``paper_hough.md``, ``.csv``, ``.json``, ``.png``."""
    s = Settings(Path(out), trials, seed, pixel_sigma, pose_sigma, heading_sigma, sway_sigma,
                 seeds, robot)
    t0 = time.perf_counter()
    s.out.mkdir(parents=True, exist_ok=True)
    cam, paper = simulate(s)
    models = simulate_models(s)
    text, rows = report.tables(s, cam, paper)
    text2, rows2 = report.model_tables(s, models)
    text = text + "\n\n" + text2
    files = write_report(s.out, "paper_hough", text, rows + rows2, {
        "trials": s.trials, "seed": s.seed, "pixel_sigma": s.pixel_sigma,
        "pose_sigma": s.pose_sigma, "heading_sigma": s.heading_sigma,
        "sway_sigma": s.sway_sigma, "seeds": s.seeds, "robot": s.robot, "camera": cam,
        "paper_reading": paper, "noise_models": models, "paper": PAPER,
        "hardware_baseline_readings": HARDWARE_BASELINE_READINGS})
    files.append(report.plot(s, cam, paper))
    return {"text": text, "files": files, "seconds": time.perf_counter() - t0,
            "camera": cam, "paper_reading": paper, "noise_models": models}
