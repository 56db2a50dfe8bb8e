"""The feature-restricted mean-shift particle filter of Li, Wu and Kong (2010) on fast
robots seen from above.

``soccer-env paper meanshift``: robots of both teams manoeuvre sharply on a small field and an
overhead camera films them; every robot is tracked in the images by three trackers, which all
read the same frames:

* ``ms-pf-20``: Li et al.'s (2010) :class:`estimators.MeanShiftParticleFilter` with 20
  particles (AR(2) motion, mean shift on every particle, the feature restriction, lost-track
  handling by a global search) and an identity check by the robot's player dots (below);
* ``pf-20`` and ``pf-200``: the plain :class:`estimators.ParticleFilterTracker`
  (the paper's baseline: same motion model and likelihood, no mean shift, no restriction, no
  lost-track handling) with 20 and 200 particles.

**Scene.** Field: a MiroSot middle-league-sized override of the ``ssl-2012`` preset (2.2 m x 1.8
m, goals 0.4 m wide, penalty areas 0.8 m x 0.35 m, centre circle 0.25 m; a 0.16 m strip to the
walls, the least that holds the 0.15 m deep goals). Why not a SSL field: the world's robots are
SSL bodies (0.18 m across, 2.4 times a 7.5 cm MiroSot cube), and on this field a 640 x 480 image
has 4.4 mm per pixel, so a robot is about 41 px across, its team patch about 11 px and a robot
at 3 m/s moves about 23 px per frame: the pixel sizes and speeds of a MiroSot robot (7.5 cm, 2-3
m/s) on a 640 x 480 image of a 1.5-2.2 m field. On the 6.1 m ``ssl-2012`` field the team patch
would be under 5 px across. Robots: ``n`` blue and ``n`` yellow (3 + 3 by default, Li et al.'s
(2010) figure 5 shows a 3 vs 3 game) of the ``ssl`` preset (3 m/s, 3 m/s^2, 10 rad/s), team-mates
sharing the team colour (the paper's "similar colours" difficulty), each team's robots numbered
0, 1, 2, ... by their player dots (:class:`soccer_env.sensors.images.patterns.PatchPattern`).
Every 0.2-0.5 s (uniform, seeded) each robot draws a new manoeuvre: a body-frame velocity in a
uniform random direction at 80-100 % of its top speed and a turn rate uniform in +-5 rad/s (half
its top rate); a robot within 0.3 m of a wall that is heading for it draws a new manoeuvre at
once, pointing within 60 degrees of the direction to the field's centre. Robots collide with
each other, the walls and the ball (at rest at the start, placed away from the robots).
:class:`~soccer_env.sim.world.World` steps at 1/60 s; the camera (``mirosot`` preset of
:data:`soccer_env.presets.OVERHEAD_FRAMES`: 640 x 480 at 30 Hz, Li et al.'s (2010) 33 ms cycle;
1/60 s exposure, so motion blur; 5 % gain flicker, up to 20 % brightness ramp and 5 grey levels of
noise) renders every second step, starting with the robots at rest at time 0.

**Images.** A colour look-up table (:meth:`OverheadRenderer.colour_table
<soccer_env.sensors.images.overhead.OverheadRenderer.colour_table>`, built once, offline in the
paper's terms) gives per frame the probability images of blue, yellow, pink and green; a robot's
trackers read its team colour's image (so its team-mates are distractors of the same colour) and
the frame difference (:func:`estimators.image.colour.frame_difference`; none on the first
frame). The search window is a square of the team patch's diameter in pixels (odd, 13 px here).
Every tracker starts at the robot's true first position with zero velocity and uses the
estimators' default parameters (AR noise 4 px, likelihood sigma 0.15, motion weight up to 0.5 at
20 px/frame; mean shift 5 iterations; colour mass within +-30 % of the mass measured on the
first frame): nothing was tuned to this benchmark.

**Identity check** (the paper's step 5, our reading; the ``feature_check`` hook of the
mean-shift PF, applied to its particles' windows and to the global search's candidate). Box
filtered (5 x 5 px, about a dot's radius) pink and green probability images are read at the four
dot centres of the robot's layout (65 mm from the centre, body-frame angles +-57.4 and +-147.4
degrees) for 24 headings (15 degree steps) around the window's centre; a pattern's score at a
heading is the sum over its dots of ``P(dot's colour) - P(the other colour)``. The window is
accepted when the robot's own pattern scores above 0 at its best heading and strictly above
every team-mate's pattern at theirs. It costs two look-ups and two box filters per frame (shared
by all robots, counted as preprocessing) and 24 x 4 x 2 reads per particle.

**Measures** (pooled over every robot, frame after the first and episode): the tracker's
position error against the robot's true centre (median, 90th percentile and RMSE, in pixels and
in mm: pixels times the image's metres per pixel); the share of frames the tracker reports lost
(the mean-shift PF only; the plain PF has no lost test); the share of frames its estimate lies
farther than the robot's radius (90 mm, 20 px) from the truth ("off target"), and the share in
which it lies within a radius of a team-mate instead ("on a team-mate", identity swaps); the
time per frame and tracked robot of the tracker's update alone (rendering and the shared images
not included; these are timed separately per frame). Beside them: the robots' true speeds and
the AR(2) model's one-frame prediction error of the true track (how hard the motion is for the
model), and, for the mean-shift PF, how often the window on the true robot would fail its
colour-mass restriction or its identity check, its lost-track events, and the share of its lost
frames in which the true robot would have passed both (the global search missed it). The
``episodes`` seeded episodes (seeds ``seed`` .. ``seed + episodes - 1``; 10 of 10 s by default)
run in ``workers`` processes (default: all cores; 1 runs them here; the figures other than the
timings do not depend on it). Timings are taken inside each process; with all cores busy, or
other work on the machine, they include contention.

**Code.** :mod:`.scene` (the field, the robots' driver, the identity check), :mod:`.episode`
(one episode: simulate, render, track, measure), :mod:`.report` (the measures pooled, the text,
the figure); :func:`run` checks the :class:`Settings`, runs the episodes and writes the
report."""

from __future__ import annotations

import dataclasses
import math
import os
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from soccer_lab.papers.common import check_count, map_jobs, write_report
from soccer_lab.papers.meanshift import report
from soccer_lab.papers.meanshift.episode import run_episode
from soccer_lab.papers.meanshift.report import AIMS, CDF_EDGES_MM, PAPER
from soccer_lab.papers.meanshift.scene import DOT_BOX, FIELD, FRAME, KINDS, ROBOT

__all__ = ["run", "Settings", "PAPER", "AIMS", "KINDS", "FIELD", "FRAME", "ROBOT", "DOT_BOX",
           "CDF_EDGES_MM"]


@dataclass(frozen=True)
class Settings:
    """What one run simulates (validated on construction; the counts become ``int``).

    Attributes:
        out: the output folder.
        seed: the first episode's seed; episodes use ``seed .. seed + episodes - 1``.
        workers: processes (None: all cores).
        episodes: seeded episodes, in [1, 1000].
        duration: each episode's length [s], in [0.5, 600].
        robots_per_team: robots of each team, in [1, 6].
    """

    out: Path
    seed: int = 0
    workers: int | None = None
    episodes: int = 10
    duration: float = 10.0
    robots_per_team: int = 3

    def __post_init__(self) -> None:
        object.__setattr__(self, "seed", check_count("seed", self.seed, 0, 2**31 - 1))
        object.__setattr__(self, "episodes", check_count("episodes", self.episodes, 1, 1000))
        if self.workers is not None:
            object.__setattr__(self, "workers", check_count("workers", self.workers, 1, 1024))
        object.__setattr__(self, "robots_per_team",
                           check_count("robots_per_team", self.robots_per_team, 1, 6))
        duration = self.duration
        if isinstance(duration, bool) or not isinstance(duration, (int, float)) \
                or not (math.isfinite(duration) and 0.5 <= duration <= 600.0):
            raise ValueError(f"duration must be in [0.5, 600] s, got {duration!r}")


def run(out: str | Path = "paper_output", seed: int = 0, workers: int | None = None, *,
        episodes: int = 10, duration: float = 10.0, robots_per_team: int = 3) -> dict[str, Any]:
    """Run ``episodes`` seeded episodes of ``duration`` seconds with ``robots_per_team`` robots
    a team (module docstring), in ``workers`` processes (default: all cores; 1 runs them
    here); write ``paper_meanshift.md``, ``.csv``, ``.json`` and ``.png`` into ``out``."""
    s = Settings(Path(out), seed, workers, episodes, duration, robots_per_team)
    t0 = time.perf_counter()
    s.out.mkdir(parents=True, exist_ok=True)
    jobs = [(sd, float(s.duration), s.robots_per_team)
            for sd in range(s.seed, s.seed + s.episodes)]
    n_workers = min(s.workers or os.cpu_count() or 1, len(jobs))
    eps = map_jobs(run_episode, jobs, n_workers)
    summary, rows = report.summarise(eps)
    text = report.text(eps, summary, s.robots_per_team, s.duration, n_workers)
    ms = summary["ms-pf-20"]
    prep = report.prep_ms(eps)
    cycle = prep + 2 * s.robots_per_team * ms["ms_per_update"]
    aims = report.verdicts(summary)
    data = {"seed": s.seed, "episodes": s.episodes, "duration": s.duration,
            "robots_per_team": s.robots_per_team, "field": dataclasses.asdict(FIELD),
            "robot": ROBOT, "frame": FRAME, "metres_per_pixel": eps[0]["mpp"],
            "robot_radius_px": eps[0]["radius_px"], "window_px": eps[0]["window_px"],
            "kinds": KINDS, "summary": summary, "prep_ms_per_frame": prep, "cycle_ms": cycle,
            "motion": report.motion(eps), "ms_pf_diagnostics": report.diagnostics(eps),
            "cdf_edges_mm": CDF_EDGES_MM.tolist(), "aims": aims, "paper": PAPER,
            "per_episode": [r for r in rows if r["episode"] != "all"]}
    files = write_report(s.out, "paper_meanshift", text, rows, data)
    files.append(report.plot(eps, summary, s.out / "paper_meanshift.png"))
    return {"text": text, "files": files, "seconds": time.perf_counter() - t0,
            "summary": summary, "aims": aims, "prep_ms_per_frame": prep, "cycle_ms": cycle}
