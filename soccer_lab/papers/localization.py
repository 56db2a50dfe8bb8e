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
"""

from __future__ import annotations

import dataclasses
import math
import os
import time
from collections import deque
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from estimators import KLDConfig, KLDLocalizer, SightingMemory, seed_poses
from soccer_env import presets
from soccer_env.perception.brain import Brain, landmark_sightings
from soccer_env.perception.humanoid import HumanoidTeamPerception
from soccer_env.presets.sensors import RADIO_PRESETS, head_camera
from soccer_env.render.plots import pyplot, save_figure
from soccer_env.sim.heads import HeadController
from soccer_env.sim.world import World
from soccer_lab.papers.common import check_count, map_jobs, write_report

__all__ = ["run", "Settings", "PAPER", "AIMS"]

PAPER = ("Guo and Li (2013): KLD-sampling keeps many particles while uncertain and few once "
         "converged; errors are larger in turns (wheel slip); robot speed <= 0.5 m/s.")
AIMS = ("Our criteria (not the paper's): KLD-sampling using at least 3 times fewer particles "
        "while tracking than while globally localizing, with median position error under "
        "0.15 m while walking.")
ROBOT = "humanoid-2012"
FIELD = "humanoid-2012"
CAMERA = "kidsize-2012"
CONTROL_DT = 1.0 / 60.0
#: Forward speed of the route as a fraction of the robot's top speed.
CRUISE = 0.75
#: Turn rate of the route's turns, and of the turns back from the edges [rad/s].
TURN_RATE, EDGE_TURN_RATE = 0.3, 0.5
#: The route turns back once the robot is this close to a field line [m].
EDGE_MARGIN = 0.7
SETTLE = 5.0  # errors and tracking particles after this [s], and after the kidnapping
GLOBAL_WINDOW = 1.0  # the mean particles "in the first second" [s]
RECOVERED_M = 0.3  # localized: position error below this [m] ...
RECOVERED_HOLD = 1.0  # ... for this long [s]
KIDNAP_AT = 2.0 / 3.0  # fraction of the episode
#: An estimate within this distance [m] and angle [rad] of the mirrored true pose ``(-x, -y,
#: theta + pi)`` (and farther than this from the truth) counts as at the mirror pose.
MIRROR_M, MIRROR_RAD = 0.5, math.radians(30.0)
#: Frames captured while the gait turns faster than this [rad/s] count as "in turns".
TURNING = 0.1
#: The recovery seed's memory: the sightings of this many updates (frames with landmarks;
#: one to two seconds of the scanning head).
SEED_MEMORY = 25
#: The name of KLD-sampling with the triangulation recovery seed: the KLD row's plus this.
SEEDED = " + triangulation seed"
#: The suffix of KLD-sampling with Fox's binning of the predicted samples
#: (``KLDConfig(binning="predicted")``).
FOX = ", bins of the predicted samples (Fox)"
#: Triangulation alone (Xu et al. 2012, no filter): name -> the frames with landmarks whose
#: sightings it uses (this frame's only, or the seed's memory moved by the odometry).
TRIANGULATIONS = {"triangulation, this frame": 1,
                  f"triangulation, last {SEED_MEMORY} frames": SEED_MEMORY}
#: A triangulated pose farther than this from the truth [m] is a wrong assignment.
WRONG_M = 0.5
#: Triangulation outcomes per frame, in the table's order: a pose within WRONG_M of the
#: truth, a wrong assignment (ambiguous landmarks), or no pose for one of the reasons of
#: :data:`~estimators.fusion.triangulation.SEED_FAILURES`.
TRI_OUTCOMES = ("correct", "wrong", "too_few", "degenerate", "no_fit")


class BrainReplay:
    """A filter fed as :class:`~soccer_env.perception.humanoid`'s robot brain feeds its
    localization: the brain's own odometry bookkeeping (kept with time stamps, composed up to
    a frame's capture time, turned into the filter's mid-step convention) on this filter."""

    kind = "kld"
    odometry = Brain.odometry
    odometry_until = Brain.odometry_until
    move_localization = Brain.move_localization

    def __init__(self, loc: KLDLocalizer) -> None:
        self.loc = loc
        self.odo: deque[tuple[float, tuple[float, float, float]]] = deque()
        self.loc_estimate = loc.estimate()


def _route_command(pose: np.ndarray, t: float, segments: list[tuple[float, float]],
                   state: dict[str, Any], field: Any, vmax: float) -> tuple[float, float]:
    """Forward speed and turn rate of the scripted route at ``t`` for the true ``pose``."""
    x, y, th = float(pose[0]), float(pose[1]), float(pose[2])
    hx, hy = field.half_length - EDGE_MARGIN, field.half_width - EDGE_MARGIN
    to_centre = math.remainder(math.atan2(-y, -x) - th, 2.0 * math.pi)
    if abs(x) > hx or abs(y) > hy:
        if abs(to_centre) > math.radians(60.0):
            state["returning"] = True
    if state["returning"]:
        if abs(to_centre) < math.radians(20.0):
            state["returning"] = False
        else:
            return 0.4 * vmax, math.copysign(EDGE_TURN_RATE, to_centre)
    while state["segment"] + 1 < len(segments) and segments[state["segment"] + 1][0] <= t:
        state["segment"] += 1
    return CRUISE * vmax, segments[state["segment"]][1]


def _kidnap_pose(pose: np.ndarray, field: Any, rng: np.random.Generator) -> np.ndarray:
    """A pose inside the field at least 2 m from ``pose``, turned by 90 degrees or more."""
    hx, hy = field.half_length - EDGE_MARGIN, field.half_width - EDGE_MARGIN
    while True:
        cand = np.array([rng.uniform(-hx, hx), rng.uniform(-hy, hy), rng.uniform(-math.pi,
                                                                                 math.pi)])
        if (math.hypot(*(cand[:2] - pose[:2])) >= 2.0
                and abs(math.remainder(cand[2] - pose[2], 2.0 * math.pi)) >= 0.5 * math.pi):
            return cand


def _episode(duration: float, seed: int, kidnap: bool) -> dict[str, Any]:
    """Walk the route once: the events a robot brain gets (odometry per control step,
    frames' landmarks as delivered) and the truth per step."""
    rng = np.random.default_rng(seed)
    walk_rng, cam_rng, route_rng = rng.spawn(3)
    field = presets.field(FIELD)
    ball = presets.ball(field.ball)
    spec = presets.robot(ROBOT)
    world = World(field, ball, spec, 1, 0, CONTROL_DT)
    camera = head_camera(CAMERA)
    # The perception of one humanoid, for its camera, landmark table, bounds, KLD noise model
    # and scanning head; no brain runs (the filters are replayed below), so it needs no
    # perception config.
    team = HumanoidTeamPerception(None, field, ball, world.robot_specs, world.teams,
                                  world.names, [0], camera, RADIO_PRESETS["ideal"])
    head = HeadController(spec, camera.height, "scan")
    start = np.array([-1.5, 0.6, 0.3])
    world.reset(start[None, :], (0.0, -(field.half_width + 0.45)), walk_rng)
    n_steps = int(round(duration / CONTROL_DT))
    segments, t = [], 0.0
    while t < duration:
        segments.append((t, float(route_rng.choice([0.0, 0.0, 0.0, TURN_RATE, -TURN_RATE]))))
        t += float(route_rng.uniform(2.0, 5.0))
    route = {"returning": False, "segment": 0}
    kidnap_step = int(round(KIDNAP_AT * n_steps)) if kidnap else -1
    vmax = spec.max_forward_speed

    def frames_to_events(frames: list[Any]) -> None:
        for f in frames:  # the landmarks with a ground point, as the brain takes them
            events.append(("frame", f.t_capture, *landmark_sightings(f)))

    events: list[tuple] = []
    times, poses, omegas = [world.time], [world.robot_array()[0, 0:3].copy()], [0.0]
    frames_to_events(team.sensor.reset(world.snapshot(), world.head_state(), cam_rng))
    kidnap_time, kidnap_to = None, None
    falls = 0
    for k in range(n_steps):
        now = world.time
        pose = world.robot_array()[0, 0:3]
        vx, w = _route_command(pose, now, segments, route, field, vmax)
        pan, tilt = head.targets(now, pose, None, math.inf, math.inf)  # the scan
        world.step(np.array([[vx, 0.0, w, 0.0, pan, tilt]]))
        if k == kidnap_step:
            kidnap_to = _kidnap_pose(world.robot_array()[0, 0:3], field, route_rng)
            world.set_robot(0, *kidnap_to)
            kidnap_time = world.time
        state = world.snapshot()
        events.append(("odo", state.time, tuple(world.walk.odometry[0])))
        times.append(state.time)
        poses.append(state.robots[0, 0:3].copy())
        omegas.append(float(world.walk.gait[0][2]))
        frames_to_events(team.sensor.step(state, world.head_state()))
        falls = world.walk.falls[0]
    times_a, poses_a = np.array(times), np.array(poses)
    frame_t = np.array([ev[1] for ev in events if ev[0] == "frame"])
    # The truth at each frame's capture (a control step's time; the warm-up frame's, before
    # the start, is the start pose).
    at = np.minimum(np.searchsorted(times_a, frame_t - 1e-9), len(times_a) - 1)
    return {"events": events, "times": times_a, "poses": poses_a, "frame_t": frame_t,
            "frame_truth": poses_a[at], "frame_turning": np.abs(np.array(omegas)[at]) > TURNING,
            "team": team, "kidnap_time": kidnap_time, "kidnap_to": kidnap_to, "falls": falls,
            "start": start}


def _recovery(t: np.ndarray, err: np.ndarray, since: float, until: float) -> float | None:
    """Seconds from ``since`` until the error is below :data:`RECOVERED_M` and stays so for
    :data:`RECOVERED_HOLD` seconds (or until ``until``); None if never."""
    ok = err < RECOVERED_M
    idx = np.nonzero((t >= since) & (t < until))[0]
    for j in idx:
        if not ok[j]:
            continue
        window = idx[(t[idx] >= t[j]) & (t[idx] <= t[j] + RECOVERED_HOLD)]
        if ok[window].all():
            return float(t[j] - since)
    return None


def _replay(ep: dict[str, Any], rep: BrainReplay,
            frame: Callable[[tuple, np.ndarray, np.ndarray], Any]) -> tuple[list[Any], float]:
    """Feed the recorded episode to ``rep``: the odometry as it came, and at every frame the
    localization moved to the frame's capture time, then ``frame(kinds, ranges, bearings)``.
    Returns each frame's result and the seconds spent moving and in ``frame``."""
    out, seconds = [], 0.0
    for ev in ep["events"]:
        if ev[0] == "odo":
            rep.odometry(ev[1], ev[2], None)
            continue
        _, t_cap, kinds, ranges, bearings = ev
        t0 = time.perf_counter()
        rep.move_localization(rep.odometry_until(t_cap))
        res = frame(kinds, ranges, bearings)
        seconds += time.perf_counter() - t0
        out.append(res)
    return out, seconds


def _pose_errors(est: np.ndarray, truth: np.ndarray, wrong: float
                 ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Position [m] and heading [rad] errors of the poses ``est`` ((n, 3); NaN rows: no pose)
    against ``truth``, and whether each lies at the pose the field's 180-degree symmetry makes
    look the same (only the goal-post colours tell them apart), more than ``wrong`` [m] from
    the truth."""
    err = np.hypot(est[:, 0] - truth[:, 0], est[:, 1] - truth[:, 1])
    herr = np.abs(np.remainder(est[:, 2] - truth[:, 2] + math.pi, 2.0 * math.pi) - math.pi)
    mirror = ((np.hypot(est[:, 0] + truth[:, 0], est[:, 1] + truth[:, 1]) < MIRROR_M)
              & (np.abs(np.remainder(est[:, 2] - truth[:, 2], 2.0 * math.pi) - math.pi)
                 < MIRROR_RAD) & (err > wrong))
    return err, herr, mirror


def _run_filter(ep: dict[str, Any], config: KLDConfig, seed: int,
                recovery: str = "uniform") -> dict[str, Any]:
    """Replay the episode into a filter of ``config`` (with the ``recovery`` draws of
    :class:`~estimators.KLDLocalizer`) started global; its errors per frame (at the frame's
    capture time) and the summary figures."""
    team = ep["team"]
    table = team.landmark_table
    rep = BrainReplay(KLDLocalizer(team.bounds, np.random.default_rng(seed), config,
                                   recovery=recovery, seed_memory=SEED_MEMORY))
    loc = rep.loc
    initial = loc.n

    def frame(kinds: tuple, ranges: np.ndarray, bearings: np.ndarray) -> tuple[np.ndarray, int]:
        if kinds:
            loc.update_kinds(kinds, ranges, bearings, table)
        rep.loc_estimate = loc.estimate()
        return rep.loc_estimate, loc.n

    per_frame, seconds = _replay(ep, rep, frame)
    counts = [c for _, c in per_frame]
    t, truth = ep["frame_t"], ep["frame_truth"]
    e = np.array([est for est, _ in per_frame])
    err, herr, mirror = _pose_errors(e, truth, MIRROR_M)
    n = np.array(counts)
    tk = ep["kidnap_time"]
    end = float(ep["times"][-1]) + 1.0
    tracking = t >= SETTLE
    if tk is not None:
        tracking &= ~((t >= tk) & (t < tk + SETTLE))
    return {"pos_err": np.round(err, 4).tolist(), "head_err": np.round(herr, 4).tolist(),
            "counts": counts, "estimate": np.round(e, 3).tolist(),
            "median_pos_m": float(np.median(err[tracking])),
            "median_head_deg": float(np.degrees(np.median(herr[tracking]))),
            "median_pos_turning_m": _median(err[tracking & ep["frame_turning"]]),
            "median_pos_straight_m": _median(err[tracking & ~ep["frame_turning"]]),
            "initial_particles": int(initial),
            "first_second_particles": float(np.mean(n[t < GLOBAL_WINDOW])),
            "tracking_particles": float(np.mean(n[tracking])),
            "tracking_particles_median": float(np.median(n[tracking])),
            "ms_per_update": seconds / max(len(t), 1) * 1e3,
            "mirror_pct": float(100.0 * np.mean(mirror)),
            "localized_s": _recovery(t, err, float(t[0]), tk if tk is not None else end),
            "recovery_s": None if tk is None else _recovery(t, err, tk, end)}


class _TriangulationOnly:
    """No filter: the remembered sightings, moved by the odometry as the brain moves its
    localization (:class:`BrainReplay` calls :meth:`predict` and :meth:`estimate`)."""

    def __init__(self, frames: int) -> None:
        self.memory = SightingMemory(frames)

    def predict(self, odometry: tuple[float, float, float]) -> None:
        self.memory.move(odometry)

    def estimate(self) -> np.ndarray:
        return np.full(3, np.nan)


def _run_triangulation(ep: dict[str, Any], frames: int, config: KLDConfig) -> dict[str, Any]:
    """Xu et al.'s (2012) triangulation alone, at every frame, from the sightings of the last
    ``frames`` frames with landmarks (moved by the odometry), with the perception's noise
    model ``config`` (range and bearing sigmas): each frame's outcome (:data:`TRI_OUTCOMES`),
    the errors of its best pose, and the summary figures (shares of the frames [%], median
    errors of the poses found and of the correct ones)."""
    team = ep["team"]
    table = team.landmark_table
    tri = _TriangulationOnly(frames)
    rep = BrainReplay.__new__(BrainReplay)  # the brain's odometry bookkeeping, no filter
    rep.loc, rep.odo, rep.loc_estimate = tri, deque(), tri.estimate()

    def frame(kinds: tuple, ranges: np.ndarray, bearings: np.ndarray) -> Any:
        if kinds:
            tri.memory.add(kinds, ranges, bearings)
        k, pts = tri.memory.sightings()
        return None if len(k) < 3 else seed_poses(k, pts, table, config, team.bounds)

    hyps, seconds = _replay(ep, rep, frame)
    poses = np.array([hyp.poses[0] if hyp is not None and hyp.ok else np.full(3, np.nan)
                      for hyp in hyps]).reshape(-1, 3)
    e, h, mirror = _pose_errors(poses, ep["frame_truth"][:len(hyps)], WRONG_M)
    found = np.isfinite(e)
    outcome = [("correct" if err <= WRONG_M else "wrong") if ok
               else ("too_few" if hyp is None else hyp.reason)
               for hyp, err, ok in zip(hyps, e.tolist(), found.tolist())]
    out = np.array(outcome)
    right = out == "correct"
    n = max(len(out), 1)
    res: dict[str, Any] = {f"{o}_pct": float(100.0 * np.mean(out == o)) for o in TRI_OUTCOMES}
    res.update({
        "outcome": outcome, "pos_err": np.round(np.where(found, e, -1.0), 4).tolist(),
        "fix_pct": float(100.0 * np.mean(found)),
        "mirror_pct": float(100.0 * np.sum(mirror) / n),
        "median_pos_m": _median(e[found]), "median_head_deg": _deg(_median(h[found])),
        "median_pos_correct_m": _median(e[right]),
        "median_head_correct_deg": _deg(_median(h[right])),
        "ms_per_frame": seconds / n * 1e3})
    return res


def _deg(v: float | None) -> float | None:
    return None if v is None else math.degrees(v)


def _median(x: np.ndarray) -> float | None:
    return float(np.median(x)) if len(x) else None


def _fmt(v: float | None) -> str:
    return "never" if v is None else f"{v:.1f}"


def _fmt2(v: float | None) -> str:
    return "-" if v is None else f"{v:.3f}"


def _fmt_never(v: float | None, never: int) -> str:
    """A median time over episodes and, beside it, the episodes in which it never happened."""
    return _fmt(v) + (f" ({never} never)" if never else "")


#: Per-episode figures summarized by their median over the episodes (None where an episode
#: has none: left out; None if no episode has one).
MEDIAN_KEYS = ("median_pos_m", "median_head_deg", "median_pos_turning_m",
                "median_pos_straight_m", "initial_particles", "first_second_particles",
                "tracking_particles", "tracking_particles_median", "ms_per_update", "mirror_pct")
#: Times that may never happen (None): their median counts "never" as infinitely late.
_NEVER_KEYS = ("localized_s", "recovery_s")
#: The position aim while walking [m].
AIM_POS_M = 0.15
#: Per-episode figures of triangulation alone, summarized by their median over the episodes.
TRI_KEYS = (*(f"{o}_pct" for o in TRI_OUTCOMES), "fix_pct", "mirror_pct", "median_pos_m",
            "median_head_deg", "median_pos_correct_m", "median_head_correct_deg",
            "ms_per_frame")


def _kld_config(base: KLDConfig) -> KLDConfig:
    """The perception's KLD noise model with the default particle bounds."""
    default = KLDConfig()
    return dataclasses.replace(base, min_particles=default.min_particles,
                               max_particles=default.max_particles)


def _filter_name(cfg: KLDConfig) -> str:
    return f"KLD-sampling ({cfg.min_particles}-{cfg.max_particles})"


def _episode_results(job: tuple[int, float, bool, tuple[int, ...]]) -> dict[str, Any]:
    """One episode (seed, duration, kidnapping, fixed sizes): recorded once and replayed into
    KLD-sampling and every fixed-size filter (module level, for a process pool)."""
    seed, duration, kidnap, sizes = job
    ep = _episode(duration, seed, kidnap)
    base = ep["team"].kld_config  # the camera's noise model, as the perception uses it
    kld_cfg = _kld_config(base)
    kld_name = _filter_name(kld_cfg)
    results = {kld_name: _run_filter(ep, kld_cfg, seed + 1),
               kld_name + FOX: _run_filter(ep, dataclasses.replace(kld_cfg, binning="predicted"),
                                           seed + 1),
               kld_name + SEEDED: _run_filter(ep, kld_cfg, seed + 1, "triangulate")}
    for n in sizes:
        cfg = dataclasses.replace(base, min_particles=int(n), max_particles=int(n))
        results[f"fixed {int(n)}"] = _run_filter(ep, cfg, seed + 1)
    counts = np.array(results[kld_name]["counts"])
    tk = ep["kidnap_time"]
    return {"seed": seed, "kld_name": kld_name, "kld_config": dataclasses.asdict(kld_cfg),
            "frames": len(ep["frame_t"]),
            "frames_seen": sum(1 for ev in ep["events"] if ev[0] == "frame" and ev[2]),
            "kld_at_min_pct": float(100.0 * np.mean(counts <= kld_cfg.min_particles)),
            "kidnap_time": tk, "kidnap_to": None if tk is None else ep["kidnap_to"].tolist(),
            "falls": int(ep["falls"]), "frame_t": np.round(ep["frame_t"], 4).tolist(),
            "truth_t": np.round(ep["times"][::6], 4).tolist(),
            "truth_pose": np.round(ep["poses"][::6], 4).tolist(), "results": results,
            "triangulation": {name: _run_triangulation(ep, frames, base)
                              for name, frames in TRIANGULATIONS.items()}}


def _over_episodes(per: list[dict[str, Any]], kidnap: bool) -> dict[str, Any]:
    """One filter's figures over the episodes: the median of each episode's figure; for the
    times to localize and to recover, the median with "never" as infinitely late (None when
    that is the median) and the number of episodes in which it never happened."""
    out: dict[str, Any] = {"episodes": len(per)}
    for key in MEDIAN_KEYS:
        vals = [r[key] for r in per if r[key] is not None]
        out[key] = float(np.median(vals)) if vals else None
    for key in _NEVER_KEYS:
        never = sum(r[key] is None for r in per)
        if key == "recovery_s" and not kidnap:
            out[key], out["recovery_never"] = None, 0
            continue
        med = float(np.median([math.inf if r[key] is None else r[key] for r in per]))
        out[key] = med if math.isfinite(med) else None
        out[key.replace("_s", "_never")] = never
    out["pos_aim_episodes"] = sum(r["median_pos_m"] < AIM_POS_M for r in per)
    out["median_pos_m_per_episode"] = [r["median_pos_m"] for r in per]
    return out


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
    names = list(eps[0]["results"])
    per_episode = [{name: {k: v for k, v in ep["results"][name].items()
                           if not isinstance(v, list)} for name in names} for ep in eps]
    summary = {name: _over_episodes([pe[name] for pe in per_episode], bool(s.kidnap))
               for name in names}
    tri_per_episode = [{name: {k: v for k, v in ep["triangulation"][name].items()
                               if not isinstance(v, list)} for name in TRIANGULATIONS}
                       for ep in eps]
    tri_summary = {name: {"episodes": len(eps), **{
        key: _median(np.array([pe[name][key] for pe in tri_per_episode
                               if pe[name][key] is not None]))
        for key in TRI_KEYS}} for name in TRIANGULATIONS}
    text = _text(s, eps, summary, tri_summary)
    rows = [{"filter": name, "episode": "median",
             **{k: v for k, v in r.items() if not isinstance(v, list)}}
            for name, r in summary.items()]
    rows += [{"filter": name, "episode": sd, **pe[name]}
             for sd, pe in zip(s.seeds, per_episode) for name in names]
    rows += [{"filter": name, "episode": "median", **r} for name, r in tri_summary.items()]
    rows += [{"filter": name, "episode": sd, **pe[name]}
             for sd, pe in zip(s.seeds, tri_per_episode) for name in TRIANGULATIONS]
    files = write_report(s.out, "paper_localization", text, rows,
                         {"duration": s.duration, "seed": s.seed, "episodes": s.episodes,
                          "seeds": s.seeds, "kidnap_time": eps[0]["kidnap_time"],
                          "kld_config": eps[0]["kld_config"], "summary": summary,
                          "triangulation": tri_summary,
                          "per_episode": [{k: v for k, v in ep.items()
                                           if k not in ("kld_name", "kld_config")}
                                          for ep in eps]})
    files.append(_plot(s, eps))
    return {"text": text, "files": files, "seconds": time.perf_counter() - t0,
            "results": summary, "triangulation": tri_summary, "episodes": [
                {"seed": sd, "kidnap_time": ep["kidnap_time"], "kidnap_to": ep["kidnap_to"],
                 "falls": ep["falls"], "results": pe, "triangulation": tp}
                for sd, ep, pe, tp in zip(s.seeds, eps, per_episode, tri_per_episode)]}


def _walk_episodes(s: Settings) -> list[dict[str, Any]]:
    """Every episode recorded and replayed into every filter (:func:`_episode_results`),
    in seed order, over ``s.workers`` processes."""
    jobs = [(sd, float(s.duration), bool(s.kidnap), s.fixed_sizes) for sd in s.seeds]
    return map_jobs(_episode_results, jobs, min(s.workers or os.cpu_count() or 1, len(jobs)))


# ------------------------------------------------------------------------------------------
# Report
# ------------------------------------------------------------------------------------------

def _text(s: Settings, eps: list[dict[str, Any]], summary: dict[str, Any],
          tri_summary: dict[str, Any]) -> str:
    """The printed report: the setting, the filters' medians over the episodes, each
    episode's median position error, KLD-sampling against our criteria, the recovery seed's
    effect, triangulation alone, and the paper."""
    seeds, tk = s.seeds, eps[0]["kidnap_time"]
    spec = presets.robot(ROBOT)
    span = f"seed {seeds[0]}" if len(seeds) == 1 else f"seeds {seeds[0]}-{seeds[-1]}"
    frames = int(np.median([ep["frames"] for ep in eps]))
    seen = int(np.median([ep["frames_seen"] for ep in eps]))
    kid = ("no kidnapping" if tk is None else
           f"kidnapped at {tk:.1f} s (two thirds of each episode) to a pose drawn from the seed, "
           f"at least 2 m away and turned by 90 deg or more, unknown to the filters")
    lines = [
        f"Walking humanoid ({ROBOT}, {CRUISE * spec.max_forward_speed:.2f} m/s, turning now "
        f"and then and at the edges) in {s.episodes} episode(s) of {s.duration:g} s ({span}; "
        f"route, camera noise and kidnapping drawn from the seed) on the {FIELD} field "
        f"(6 m x 4 m), head scanning +-90 deg, {CAMERA} camera (51 deg, 25 Hz, landmarks by "
        f"kind within 4 m: median {frames} frames per episode, {seen} with landmarks); the walk "
        f"engine's odometry; global start; {kid}. Each episode is recorded once and replayed "
        f"into every filter. Errors and tracking particles after the first {SETTLE:g} s, "
        f"leaving out the {SETTLE:g} s after the kidnapping; localized / recovered: position "
        f"error below {RECOVERED_M:g} m for {RECOVERED_HOLD:g} s.", "",
        *_filter_table(s, summary)]
    if tk is not None:
        lines += ["", "Kidnapped to (x [m], y [m], heading [deg]): " + "; ".join(
            f"seed {ep['seed']} ({ep['kidnap_to'][0]:.2f}, {ep['kidnap_to'][1]:.2f}, "
            f"{math.degrees(ep['kidnap_to'][2]):.0f})" for ep in eps) + "."]
    lines += ["", *_kld_lines(s, eps, summary), "", *_fox_lines(s, eps, summary), "",
              *_seed_lines(s, eps, summary), "",
              *_triangulation_table(s, tri_summary), "",
              "Median position error while tracking, in turns / walking straight (medians "
              "over the episodes): "
              + "; ".join(f"{name} {_fmt2(r['median_pos_turning_m'])} / "
                          f"{_fmt2(r['median_pos_straight_m'])} m"
                          for name, r in summary.items()) + ".", "",
              "Landmarks are known by kind only (each particle takes the candidate of the kind "
              "that explains a sighting best); the field looks the same turned by 180 degrees "
              "except for the goal-post colours, so a filter can settle on the mirror pose "
              "until it sees a post (the last column).", "", AIMS, "", PAPER]
    fell = [(ep["seed"], ep["falls"]) for ep in eps if ep["falls"]]
    if fell:
        lines += ["", "The robot fell: " + "; ".join(f"seed {sd} {n} time(s)" for sd, n in fell)
                  + "."]
    return "\n".join(lines)


def _filter_table(s: Settings, summary: dict[str, Any]) -> list[str]:
    """The filters' medians over the episodes, and each episode's median position error."""
    lines = [
        f"Per filter, the median over the {s.episodes} episode(s) of each episode's figure "
        "(the times: \"never\" counts as infinitely late, the episodes in which it never "
        "happened in brackets):", "",
        "| filter | median position error [m] | median heading error [deg] | particles at the "
        "start (global) | mean particles in the first second | mean particles while tracking "
        "| median particles while tracking | ms per update | localized after [s] | recovered "
        "after the kidnapping [s] | frames at the mirror pose [%] |",
        "|---|---|---|---|---|---|---|---|---|---|---|"]
    for name, r in summary.items():
        rec = "-" if not s.kidnap else _fmt_never(r["recovery_s"], r["recovery_never"])
        lines.append(f"| {name} | {r['median_pos_m']:.3f} | {r['median_head_deg']:.1f} | "
                     f"{r['initial_particles']:.0f} | {r['first_second_particles']:.0f} | "
                     f"{r['tracking_particles']:.0f} | {r['tracking_particles_median']:.0f} | "
                     f"{r['ms_per_update']:.2f} | "
                     f"{_fmt_never(r['localized_s'], r['localized_never'])} | {rec} | "
                     f"{r['mirror_pct']:.0f} |")
    lines += ["", "Median position error while tracking per episode [m]:", "",
              "| filter | " + " | ".join(f"seed {sd}" for sd in s.seeds) + " |",
              "|---|" + "---|" * len(s.seeds)]
    for name, r in summary.items():
        lines.append(f"| {name} | "
                     + " | ".join(f"{v:.3f}" for v in r["median_pos_m_per_episode"]) + " |")
    return lines


def _kld_lines(s: Settings, eps: list[dict[str, Any]], summary: dict[str, Any]) -> list[str]:
    """KLD-sampling's particles and error against our criteria."""
    kld = summary[eps[0]["kld_name"]]
    kld_cfg = KLDConfig(**eps[0]["kld_config"])
    ratio = kld["initial_particles"] / max(kld["tracking_particles"], 1.0)
    met = ratio >= 3.0 and kld["median_pos_m"] < AIM_POS_M
    at_min = float(np.median([ep["kld_at_min_pct"] for ep in eps]))
    return [f"KLD-sampling, medians over the {s.episodes} episode(s): {ratio:.0f} times fewer "
            f"particles while tracking than while globally localizing (the start); median "
            f"position error {kld['median_pos_m']:.3f} m while walking, under "
            f"{AIM_POS_M:g} m in {kld['pos_aim_episodes']} of {s.episodes} episode(s): "
            f"{'criteria met' if met else 'criteria NOT met'}. It keeps its global set only "
            f"until the first frame with landmarks (mean "
            f"{kld['first_second_particles']:.0f} in the first second) and sits at its "
            f"minimum of {kld_cfg.min_particles} in "
            f"{at_min:.0f} % of the frames (median {kld['tracking_particles_median']:.0f} "
            f"while tracking)"
            + ("; the mean while tracking comes from the recovery's uniform draws, which "
               "grow it to thousands." if kld["tracking_particles"]
               > 1.5 * kld["tracking_particles_median"] else ".")]


def _fox_lines(s: Settings, eps: list[dict[str, Any]], summary: dict[str, Any]
               ) -> list[str]:
    """KLD-sampling binning the predicted samples (Fox 2003) against binning the resampled
    ones (ours)."""
    name = eps[0]["kld_name"]
    a, b = summary[name], summary[name + FOX]
    return [f"Where the bins are counted: on the resampled particles before the motion (ours,"
            f" the default) median position error {a['median_pos_m']:.3f} m, "
            f"{a['tracking_particles']:.0f} particles while tracking (median "
            f"{a['tracking_particles_median']:.0f}), {a['ms_per_update']:.2f} ms per update; "
            f"on the predicted samples, as Fox's KLD-sampling does: {b['median_pos_m']:.3f} m, "
            f"{b['tracking_particles']:.0f} (median {b['tracking_particles_median']:.0f}), "
            f"{b['ms_per_update']:.2f} ms; under {AIM_POS_M:g} m in "
            f"{a['pos_aim_episodes']} and {b['pos_aim_episodes']} of {s.episodes} "
            "episode(s)."]


def _seed_lines(s: Settings, eps: list[dict[str, Any]], summary: dict[str, Any]
                ) -> list[str]:
    """KLD-sampling with the triangulation recovery seed against its uniform recovery."""
    name = eps[0]["kld_name"]
    a, b = summary[name], summary[name + SEEDED]
    return [f"Recovery seed (Xu et al.'s 2012 triangulation from the sightings of the last "
            f"{SEED_MEMORY} frames with landmarks, half of the injected particles around the "
            f"poses that fit best): median position error {a['median_pos_m']:.3f} m with "
            f"uniform recovery, {b['median_pos_m']:.3f} m with the seed; under "
            f"{AIM_POS_M:g} m in {a['pos_aim_episodes']} and {b['pos_aim_episodes']} of "
            f"{s.episodes} episode(s); localized after "
            f"{_fmt_never(a['localized_s'], a['localized_never'])} and "
            f"{_fmt_never(b['localized_s'], b['localized_never'])} s"
            + ("" if not s.kidnap else
               f"; recovered after {_fmt_never(a['recovery_s'], a['recovery_never'])} and "
               f"{_fmt_never(b['recovery_s'], b['recovery_never'])} s")
            + f"; frames at the mirror pose {a['mirror_pct']:.0f} % and "
            f"{b['mirror_pct']:.0f} %."]


def _triangulation_table(s: Settings, tri: dict[str, Any]) -> list[str]:
    """Triangulation alone per frame: how often it gives a pose, how good, and why not."""
    lines = [
        f"Triangulation alone (Xu et al. 2012, no filter) at every frame, medians over the "
        f"{s.episodes} episode(s) of each episode's figure: the best pose of the candidate "
        f"assignments, a wrong assignment when it is more than {WRONG_M:g} m from the truth "
        "(the shares add up to 100 % of the frames; errors over the frames with a pose, and "
        "over the correct ones):", "",
        "| sightings | correct pose [%] | wrong assignment (ambiguous landmarks) [%] (at the "
        "mirror pose) | fewer than three landmarks [%] | degenerate geometry [%] | no "
        "assignment fits [%] | median position error [m] (correct ones) | median heading "
        "error [deg] (correct ones) | ms per frame |",
        "|---|---|---|---|---|---|---|---|---|"]
    for name, r in tri.items():
        lines.append(
            f"| {name} | {r['correct_pct']:.0f} | {r['wrong_pct']:.0f} "
            f"({r['mirror_pct']:.0f}) | {r['too_few_pct']:.0f} | {r['degenerate_pct']:.1f} | "
            f"{r['no_fit_pct']:.1f} | {_fmt2(r['median_pos_m'])} "
            f"({_fmt2(r['median_pos_correct_m'])}) | {_fmt1(r['median_head_deg'])} "
            f"({_fmt1(r['median_head_correct_deg'])}) | {r['ms_per_frame']:.2f} |")
    return lines


def _fmt1(v: float | None) -> str:
    return "-" if v is None else f"{v:.1f}"


def _plot(s: Settings, eps: list[dict[str, Any]]) -> str:
    """The first episode's position errors of every filter; every episode's KLD error and
    particle count."""
    import textwrap

    from soccer_env.render.plots import (
        LABEL_SIZE,
        TITLE_SIZE,
        legend_beside,
        style_key,
    )

    first, kld_name, tk = eps[0], eps[0]["kld_name"], eps[0]["kidnap_time"]
    plt = pyplot()
    fig, (ax1, ax2, ax3) = plt.subplots(3, 1, figsize=(11, 8.5), sharex=True)
    t = np.array(first["frame_t"])
    for name, r in first["results"].items():
        ax1.plot(t, np.maximum(r["pos_err"], 1e-3), lw=1,
                 label=textwrap.fill(name, 38, subsequent_indent="  "))
    ax1.set_ylabel("position error [m]", fontsize=LABEL_SIZE)
    ax1.set_yscale("log")
    ax1.set_title(f"Every filter, episode seed {s.seeds[0]}", fontsize=LABEL_SIZE, loc="left")
    for k, ep in enumerate(eps):
        r = ep["results"][kld_name]
        te = np.array(ep["frame_t"])
        ax2.plot(te, np.maximum(r["pos_err"], 1e-3), lw=0.9, color=f"C{k % 10}",
                 label=f"seed {ep['seed']}")
        ax3.plot(te, r["counts"], lw=0.9, color=f"C{k % 10}")
    ax2.set_ylabel("position error [m]", fontsize=LABEL_SIZE)
    ax2.set_yscale("log")
    ax2.set_title(f"{kld_name}, every episode", fontsize=LABEL_SIZE, loc="left")
    ax3.set(yscale="log")
    ax3.set_xlabel("time since the episode's start [s]", fontsize=LABEL_SIZE)
    ax3.set_ylabel("particles", fontsize=LABEL_SIZE)
    ax3.set_title(f"{kld_name}: particle count, every episode", fontsize=LABEL_SIZE,
                  loc="left")
    for ax in (ax1, ax2):
        ax.axhline(RECOVERED_M, color="0.4", ls=":", lw=1.2)
    for ax in (ax1, ax2, ax3):
        ax.grid(alpha=0.3)
        if tk is not None:
            ax.axvline(tk, color="r", ls="--", lw=1.2)
    field = presets.field(FIELD)
    kidnap = (f", picked up and put down elsewhere at {tk:.1f} s" if tk is not None
              else ", never kidnapped")
    fig.suptitle(f"Guo and Li (2013) localization: one walking {ROBOT} humanoid on the "
                 f"{FIELD} field ({field.length:g} m x {field.width:g} m)\nhead camera "
                 f"{CAMERA}, global start{kidnap}", fontsize=TITLE_SIZE)
    legend_beside(ax1, title="filter")
    keys = [style_key(f"{RECOVERED_M:g} m: localized below", ls=":", lw=1.2, color="0.4")]
    if tk is not None:
        keys.append(style_key("kidnapping", ls="--", lw=1.2, color="r"))
    seeds = legend_beside(ax2, title="colour: episode")
    legend_beside(ax2, keys, title="line style", below=seeds)
    return save_figure(fig, s.out / "paper_localization.png")
