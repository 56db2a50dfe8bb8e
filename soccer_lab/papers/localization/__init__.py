"""The adaptive localization of Guo and Li (2013): KLD-sampling against fixed-size
particle filters on a walking humanoid, with a kidnapping.

``soccer-env paper localization``: one ``humanoid-2012`` robot (:mod:`soccer_env.sim.walk`'s
walk engine in :class:`~soccer_env.sim.world.World`) walks a scripted route on the
``humanoid-2012`` field (6 m x 4 m) for ``duration`` seconds: forward at 75 % of its top speed,
turning now and then (segments of 2-5 s drawn from the seed), and turning back towards the
centre near the edges. Its head scans (:class:`~soccer_env.sim.heads.HeadController` in
``"scan"`` mode: pan +-90 degrees, period 4 s) and its ``kidsize-2012`` head camera
(:class:`~soccer_env.sensors.headcam.HeadCameraSensor`: 51 degrees, 25 Hz, 40 ms latency, 2 px
noise, landmarks within 4 m, the gait's sway unknown to the robot) sees the field's landmarks by
kind only: ``"L"`` and ``"T"`` line corners, ``"X"`` centre-circle crossings, and goal posts
told apart only by their goal's colour (``"post_blue"``, ``"post_yellow"``). At two thirds of
the episode the robot is picked up and put down elsewhere (:meth:`World.set_robot
<soccer_env.sim.world.World.set_robot>`, at least 2 m away and turned by 90 degrees or more),
which no filter is told.

``episodes`` such episodes are walked (seeds ``seed`` .. ``seed + episodes - 1``: route, walk
noise, camera noise and kidnapping drawn from the seed; 5 by default, in a process pool with
``workers``), since one episode's figures swing a lot with the seed. Each episode is recorded
once (the walk engine's odometry per control step, the frames as delivered) and replayed into
every filter, so all see the same data, as :mod:`soccer_env.perception.humanoid`'s robot brain
feeds them: odometry kept with its time stamps, composed up to each frame's capture time (the
brain's own code is used), landmarks by kind to :meth:`~estimators.KLDLocalizer.update_kinds`
with the noise model that the perception derives from the camera. Every filter starts global (no
prior): KLD-sampling with the default bounds (50-5000 particles) and fixed sizes.

Reported per filter, each as the median over the episodes of the episode's figure: median
position and heading error after the first 5 s, leaving out the 5 s after the kidnapping;
particles at the start (the global set), their mean over the first second, their mean and median
while tracking (the same frames as the errors); time per update; time to localize from the
global start and to recover after the kidnapping (until the position error is below 0.3 m and
stays so for a second; "never" counts as infinitely late, and the episodes in which it never
happened are counted); the share of frames whose estimate sits at the mirror pose (the field
turned by 180 degrees, which only the goal posts' colours tell apart). Beside it, each episode's
median position error per filter. Our criteria (judged on these medians: the particles at
the start against the mean while tracking, and the median position error, with the number of
episodes in which the position criterion holds) and Guo and Li's (2013) claims are printed beside.

**Code.** :mod:`.episode` (the scripted walk, recorded once), :mod:`.filters` (the filters and
triangulation replayed on a recorded walk), :mod:`.measures` (errors, times to localize and to
recover, the figures over the episodes), :mod:`.report` (the text, rows, data and figure);
:func:`run` checks the :class:`Settings`, walks the episodes and writes the report.
"""

from __future__ import annotations

import math
import os
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from soccer_lab.papers.common import check_count, map_jobs, write_report
from soccer_lab.papers.localization import report
from soccer_lab.papers.localization.filters import (
    FOX,
    SEED_MEMORY,
    SEEDED,
    TRIANGULATIONS,
    BrainReplay,
    episode_results,
)
from soccer_lab.papers.localization.measures import (
    AIM_POS_M,
    MEDIAN_KEYS,
    TRI_KEYS,
    TRI_OUTCOMES,
    WRONG_M,
    summarise,
)
from soccer_lab.papers.localization.report import AIMS, PAPER

__all__ = ["run", "Settings", "PAPER", "AIMS", "AIM_POS_M", "BrainReplay", "TRIANGULATIONS",
           "TRI_OUTCOMES", "WRONG_M", "MEDIAN_KEYS", "TRI_KEYS", "SEED_MEMORY", "SEEDED", "FOX"]


@dataclass(frozen=True)
class Settings:
    """What one run simulates (validated on construction; the counts become ``int``).

    Attributes:
        out: the output folder.
        duration: each walk's length [s], in [15, 3600].
        seed: the first episode's seed (>= 0); episodes use ``seed .. seed + episodes - 1``.
        fixed_sizes: the particle counts of the fixed-size filters (each in [1, 100000]).
        episodes: walking episodes, in [1, 1000].
        workers: processes (None: all cores), in [1, 1024].
        kidnap: kidnap the robot at two thirds of each episode.
    """

    out: Path
    duration: float = 60.0
    seed: int = 0
    fixed_sizes: tuple[int, ...] = (100, 300, 1000, 3000)
    episodes: int = 5
    workers: int | None = None
    kidnap: bool = True

    def __post_init__(self) -> None:
        duration = self.duration
        if not (isinstance(duration, (int, float)) and math.isfinite(duration)
                and 15.0 <= duration <= 3600.0):
            raise ValueError(f"duration must be in [15, 3600] s, got {duration!r}")
        sizes = tuple(self.fixed_sizes)
        if not all(isinstance(n, (int, np.integer)) and not isinstance(n, bool)
                   and 1 <= n <= 100000 for n in sizes):
            raise ValueError(f"fixed_sizes must be particle counts in [1, 100000], got "
                             f"{sizes!r}")
        seed = self.seed
        if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) or seed < 0:
            raise ValueError(f"seed must be a non-negative integer, got {seed!r}")
        object.__setattr__(self, "fixed_sizes", sizes)
        object.__setattr__(self, "episodes", check_count("episodes", self.episodes, 1, 1000))
        if self.workers is not None:
            object.__setattr__(self, "workers", check_count("workers", self.workers, 1, 1024))

    @property
    def seeds(self) -> list[int]:
        """The episodes' seeds."""
        return list(range(int(self.seed), int(self.seed) + self.episodes))


def run(out: str | Path = "paper_output", duration: float = 60.0, seed: int = 0,
        fixed_sizes: tuple[int, ...] = (100, 300, 1000, 3000), *, episodes: int = 5,
        workers: int | None = None, kidnap: bool = True) -> dict[str, Any]:
    """Record ``episodes`` walking episodes (seeds ``seed`` .. ``seed + episodes - 1``), each
    once, and replay each into KLD-sampling and into fixed-size filters; report per filter the
    median over the episodes of each episode's figures, and each episode's median position
    error; write ``paper_localization`` ``.md``, ``.csv``, ``.json`` and ``.png`` into
    ``out``. ``workers`` processes share the episodes (default: all cores; 1 runs them here;
    the figures other than the timings do not depend on it). ``kidnap=False`` leaves the
    robot where it walks."""
    s = Settings(Path(out), duration, seed, fixed_sizes, episodes, workers, kidnap)
    t0 = time.perf_counter()
    s.out.mkdir(parents=True, exist_ok=True)
    eps = _walk_episodes(s)
    res = summarise(eps, bool(s.kidnap))
    text = report.text(s, eps, res.summary, res.tri_summary)
    files = write_report(s.out, "paper_localization", text, report.rows(s, res),
                         report.data(s, eps, res))
    files.append(report.plot(s, eps))
    return {"text": text, "files": files, "seconds": time.perf_counter() - t0,
            "results": res.summary, "triangulation": res.tri_summary, "episodes": [
                {"seed": sd, "kidnap_time": ep["kidnap_time"], "kidnap_to": ep["kidnap_to"],
                 "falls": ep["falls"], "results": pe, "triangulation": tp}
                for sd, ep, pe, tp in zip(s.seeds, eps, res.per_episode,
                                          res.tri_per_episode)]}


def _walk_episodes(s: Settings) -> list[dict[str, Any]]:
    """Every episode recorded and replayed into every filter
    (:func:`~soccer_lab.papers.localization.filters.episode_results`), in seed order, over
    ``s.workers`` processes."""
    jobs = [(sd, float(s.duration), bool(s.kidnap), s.fixed_sizes) for sd in s.seeds]
    return map_jobs(episode_results, jobs, min(s.workers or os.cpu_count() or 1, len(jobs)))
