"""The Kalman-started mean shift of Yu, Wei and Zhang (2010) with ego-motion
compensation, on a turning humanoid's head-camera images.

``soccer-env paper following``: one ``humanoid-2012`` robot (the robot of Xu et al. (2012) (Xu, Xie,
Wang, Ni 2012): 0.6 rad/s top turn rate, 3 rad/s^2, 0.2 m/s forward;
:mod:`soccer_env.sim.walk`'s walk engine with its gait sway and odometry errors in
:class:`~soccer_env.sim.world.World`) on the ``humanoid-2012`` field (6 m x 4 m, orange ball of
33 mm radius) watches the ball through its ``kidsize-2012`` head camera (0.56 m, 51 degrees,
25 Hz). ``robot="humanoid"`` runs the current KidSize robot instead
(1 rad/s, ``humanoid-kid`` field, size-1 ball of 76 mm radius, ``kidsize`` camera at 30 Hz).
Frames are rendered at the camera's frame rate with
:class:`~soccer_env.sensors.images.head.HeadFrameRenderer` at ``size`` (320 x 240 by default,
for speed; the renderer keeps the camera's horizontal field of view, so the image jump of the
ball in ball radii does not depend on the size) with the ``"realistic"`` appearance (gain,
brightness ramp and pixel noise), from the TRUE head orientation, gait sway included. The world
steps four control steps per frame (100 Hz at 25 Hz), so frames are exactly one period apart.

Scene, per seeded episode: the head is fixed at pan 0 and at the tilt that puts the middle of
the depression angles of balls at 1 m and 3 m on the optical axis (about 19 degrees), set during
0.5 s of standing before the first frame. The robot sweeps its heading back and forth around the
line to the ball: each sweep turns at a rate drawn from [0.15, 1] times the top turn rate until
the heading is ``A`` (drawn from [0.15, 0.3] rad) past the ball's bearing, less the braking
overshoot, then reverses (so the turn rate changes all the time and the ball stays in view). Two
variants, each with ``episodes`` episodes of ``duration`` seconds:

* ``turn``: turning in place, the ball 1-3 m away;
* ``follow`` (Yu et al.'s 2010 person following): the robot also walks forward towards the ball
  (``vx = 0.4 (d - 1 m)``, clipped to its top speed; the gait's speed ellipsoid then slows the
  turning), starting 2.2-2.8 m away.

Even episodes leave the ball lying still; odd episodes roll it slowly: whenever it has stopped
(plus a wait of 0.3-1.5 s) it is given a speed of at most 0.5 m/s towards a point 1.2-2.8 m
(``follow``: 1.5-2.5 m) from the robot within 0.35 rad of its bearing. The scene's script reads
the truth; the trackers see only the images and the robot's odometry.

Trackers, on the same frames (the hue back-projection,
:func:`~estimators.image.colour.back_project`, of a 16-bin hue histogram of the first frame's
ball: the pixels within 0.8 of its apparent radius of its true centre, as an operator marking
the target would give), all started at the ball's true pixel of the first frame. The target
window is the ball's apparent diameter there (``2 round(r) + 1`` px); each tracker runs at each
of ``window_scales`` times it: 1 (the target size: the bandwidth of Yu et al.'s (2010) argument)
and 2 (the paper's back-projection region ``R``, twice the target). A tracker reports lost when the
mean weight in its converged window is below ``0.2 / scale^2`` (the estimators' default 0.2 for
a target-sized window, scaled so that the same amount of target must be in any window: a round
ball fills only ``pi / 16`` of a window twice its size, below 0.2). Otherwise the estimators'
defaults (flat kernel, 10 iterations; Kalman noise 2 px/frame^2 and 2 px):

* ``kalman``: :class:`estimators.KalmanMeanShift` (Yu et al. 2010) fed with the robot's
  own motion between frames: the rotation is the walk engine's odometry ``dtheta`` summed
  over the frame's control steps, the advance the odometry's displacement projected on the
  bearing of the tracked position (the paper's ``s`` towards the target). Odometry, not the
  truth: that is what the robot knows (it has the walk engine's 15 % rotation error per step
  and does not see the sway). The camera height above the ball's centre and the ball's
  diameter (``target_height_m``: depth from the apparent size each frame, the first frame's
  size-based depth to start) are given. When lost it only predicts (its velocity kept).
* ``plain``: :class:`estimators.PlainMeanShift`, mean shift from the last position;
  when lost it stays where it was.

Neither searches the whole image after a loss (Yu et al. 2010 has no such step).

Measured per tracker on the frames after the first in which the ball's centre is in the image
(frames with the ball out of view are counted apart): the share of frames in which it reports
lost; the share "off target", its position farther from the true pixel than the ball's apparent
radius (the lost-track rate the aim is judged on); the loss hazard, the share of frames off
target among those whose previous frame was on target (how often a held track is lost, apart
from how long it then stays lost); the pixel error (median over all these frames, RMSE over
those on target); losses and recoveries (on -> off and off -> on target); time per update (the
tracker only; the back-projection, shared, is timed apart); and the depth from the ball's known
size: the ball's apparent height in a region twice the target window around the tracker's
position (:func:`~estimators.apparent_height`), ``D = f 2 r / height``
(:func:`~estimators.depth_from_size`), turned into a ground distance with the pixel's
ray (``sqrt(R^2 - (h - r)^2)``, ``R`` the range along the ray) and compared with the true ground
distance (median relative and median signed error, frames on target and not reported lost). The
same rates by turn-rate bin (the true body turn rate over the frame period: slow below a third
of the top rate, medium, fast above two thirds: 0.2 and 0.4 rad/s for the 2012 robot), with the
ball's mean image jump between frames in its apparent radii, with and without the gait's sway
(the pixel the ball would have had with the servo angles alone), and by that jump (a window of
scale ``x`` has a half-width of about ``x`` radii), the quantity that Yu et al.'s (2010)
argument is about.

The paper's claim and the aim ("the Kalman-started tracker losing the ball at most half
as often as plain mean shift under fast turns") are printed beside ours, the aim judged per
window scale on the off-target share in the fast bin, both variants pooled (met if the Kalman
tracker's share is at most half the plain one's), with the readings by the lost reports and by
the loss hazard beside it.

**Code.** :mod:`.episode` (the scripted scene and the trackers on its frames), :mod:`.measures`
(which frames count, errors, losses, the bins), :mod:`.report` (the text, rows, data and
figure); :func:`run` checks the :class:`Settings`, runs the episodes and writes the report.
"""

from __future__ import annotations

import math
import os
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from soccer_lab.papers.common import check_count, map_jobs, write_report
from soccer_lab.papers.following import report
from soccer_lab.papers.following.episode import ROBOTS, TRACKERS, VARIANTS, run_episode
from soccer_lab.papers.following.measures import JUMP_BINS, TURN_BINS
from soccer_lab.papers.following.report import AIM, PAPER

__all__ = ["run", "Settings", "PAPER", "AIM", "ROBOTS", "VARIANTS", "TRACKERS", "TURN_BINS",
           "JUMP_BINS"]


@dataclass(frozen=True)
class Settings:
    """What one run simulates (validated on construction; counts become ``int``, ``size``
    ``(width, height)`` in pixels and ``window_scales`` floats).

    Attributes:
        out: the output folder.
        episodes: episodes per variant, in [1, 1000].
        duration: each episode's length [s], in [0.2, 600].
        seed: seeds every episode (with its variant and index), in [0, 2^31 - 1].
        workers: processes (None: all cores), in [1, 1024].
        robot: a robot of :data:`ROBOTS`.
        size: the rendered frames' size [px], width in [64, 4096], height in [48, 4096].
        appearance: a head-camera appearance of :data:`soccer_env.presets.images.HEAD_FRAMES`.
        window_scales: the mean-shift windows over the ball's apparent diameter, distinct, in
            [0.5, 4].
    """

    out: Path
    episodes: int = 10
    duration: float = 20.0
    seed: int = 0
    workers: int | None = None
    robot: str = "humanoid-2012"
    size: tuple[int, int] = (320, 240)
    appearance: str = "realistic"
    window_scales: tuple[float, ...] = (1.0, 2.0)

    def __post_init__(self) -> None:
        from soccer_env.presets.images import HEAD_FRAMES

        setattr_ = object.__setattr__
        setattr_(self, "episodes", check_count("episodes", self.episodes, 1, 1000))
        duration = self.duration
        if not (isinstance(duration, (int, float)) and not isinstance(duration, bool)
                and math.isfinite(duration) and 0.2 <= duration <= 600.0):
            raise ValueError(f"duration must be in [0.2, 600] s, got {duration!r}")
        setattr_(self, "seed", check_count("seed", self.seed, 0, 2**31 - 1))
        if self.workers is not None:
            setattr_(self, "workers", check_count("workers", self.workers, 1, 1024))
        if not isinstance(self.robot, str) or self.robot not in ROBOTS:
            raise ValueError(f"robot must be one of {list(ROBOTS)}, got {self.robot!r}")
        try:
            w, h = self.size
        except (TypeError, ValueError):
            raise ValueError(f"size must be (width, height) in pixels, got {self.size!r}"
                             ) from None
        setattr_(self, "size", (check_count("size[0] (width)", w, 64, 4096),
                                check_count("size[1] (height)", h, 48, 4096)))
        if not isinstance(self.appearance, str) or self.appearance not in HEAD_FRAMES:
            raise ValueError(f"appearance must be one of {list(HEAD_FRAMES)}, got "
                             f"{self.appearance!r}")
        setattr_(self, "window_scales", _scales(self.window_scales))


def _scales(window_scales: Any) -> tuple[float, ...]:
    try:
        scales = tuple(float(x) for x in window_scales)
    except (TypeError, ValueError):
        raise ValueError(f"window_scales must be numbers, got {window_scales!r}") from None
    if not scales or len(set(scales)) != len(scales) or not all(
            math.isfinite(x) and 0.5 <= x <= 4.0 for x in scales):
        raise ValueError(f"window_scales must be distinct numbers in [0.5, 4], got "
                         f"{window_scales!r}")
    return scales


def run(out: str | Path = "paper_output", episodes: int = 10, duration: float = 20.0,
        seed: int = 0, workers: int | None = None, *, robot: str = "humanoid-2012",
        size: tuple[int, int] = (320, 240), appearance: str = "realistic",
        window_scales: tuple[float, ...] = (1.0, 2.0)) -> dict[str, Any]:
    """Run ``episodes`` seeded episodes of ``duration`` seconds per variant (``turn``,
    ``follow``) with both trackers at each of ``window_scales`` (mean-shift window over the
    ball's apparent diameter: 1, the bandwidth of Yu et al.'s (2010) argument, and 2, its
    back-projection region R) on the same frames (module docstring); write
    ``paper_following.md``, ``.csv``, ``.json`` and ``.png`` into ``out``. ``workers``
    processes share the episodes (default: all cores; 1 runs them here; the figures other
    than the timings do not depend on it)."""
    from soccer_env import presets

    s = Settings(Path(out), episodes, duration, seed, workers, robot, size, appearance,
                 window_scales)
    t0 = time.perf_counter()
    s.out.mkdir(parents=True, exist_ok=True)
    jobs = [(s.robot, variant, k, s.seed, float(s.duration), s.size, s.appearance,
             s.window_scales) for variant in VARIANTS for k in range(s.episodes)]
    eps = map_jobs(run_episode, jobs, min(s.workers or os.cpu_count() or 1, len(jobs)))
    res = report.analyse(eps, s.window_scales)
    text = report.text(s, eps, res)
    files = write_report(s.out, "paper_following", text, report.rows(res, eps[0]["labels"]),
                         report.data(s, eps, res))
    files.append(report.plot(eps, res, presets.robot(s.robot).max_turn_speed,
                             s.out / "paper_following.png", robot=s.robot))
    return {"text": text, "files": files, "seconds": time.perf_counter() - t0,
            "summary": res["summary"], "turn_bins": res["turn_bins"],
            "jump_bins": res["jump_bins"], "verdicts": res["verdicts"]}
