"""Paper 001's adaptive localization: KLD-sampling against fixed-size particle filters on a
walking humanoid, with a kidnapping.

``soccer-env paper localization``: one ``humanoid-2012`` robot (:mod:`soccer_env.humanoid`'s
walk engine in :class:`~soccer_env.physics.World`) walks a scripted route on the
``humanoid-2012`` field (6 m x 4 m) for ``duration`` seconds: forward at 75 % of its top speed,
turning now and then (segments of 2-5 s drawn from the seed), and turning back towards the
centre near the edges. Its head scans (:class:`~soccer_env.humanoid_perception.HeadController`
in ``"scan"`` mode: pan +-90 degrees, period 4 s) and its ``kidsize-2012`` head camera
(:class:`~soccer_env.headcam.HeadCameraSensor`: 51 degrees, 25 Hz, 40 ms latency, 2 px noise,
landmarks within 4 m, the gait's sway unknown to the robot) sees the field's landmarks by kind
only: ``"L"`` and ``"T"`` line corners, ``"X"`` centre-circle crossings, and goal posts told
apart only by their goal's colour (``"post_blue"``, ``"post_yellow"``). At two thirds of the
episode the robot is picked up and put down elsewhere (:meth:`World.set_robot
<soccer_env.physics.World.set_robot>`, at least 2 m away and turned by 90 degrees or more),
which no filter is told.

The episode is recorded once (the walk engine's odometry per control step, the frames as
delivered) and replayed into every filter, so all see the same data, as
:mod:`soccer_env.humanoid_perception`'s robot brain feeds them: odometry kept with its time
stamps, composed up to each frame's capture time (the brain's own code is used), landmarks
by kind to :meth:`~estimators.KLDLocalizer.update_kinds` with the noise model that the
perception derives from the camera. Every filter starts global (no prior): KLD-sampling with
the default bounds (50-5000 particles) and fixed sizes.

Reported per filter: median position and heading error after the first 5 s, leaving out the
5 s after the kidnapping; mean particles while globally localizing (the first second) and
while tracking (the same frames as the errors); time per update; time to localize from the
global start and to recover after the kidnapping (until the position error is below 0.3 m
and stays so for a second). The issue's aims and paper 001's claims are printed beside.
"""

from __future__ import annotations

import dataclasses
import math
import time
from collections import deque
from pathlib import Path
from typing import Any

import numpy as np

from estimators.localization import KLDConfig, KLDLocalizer

from .. import presets
from ..headcam import head_camera
from ..humanoid_perception import HumanoidTeamPerception, _Brain, head_state
from ..physics import World
from ..plots import pyplot, save_figure
from ..radio import RADIO_PRESETS
from ._io import write_report

__all__ = ["run", "PAPER", "AIMS"]

PAPER = ("Paper 001: KLD-sampling keeps many particles while uncertain and few once converged; "
         "errors are larger in turns (wheel slip); robot speed <= 0.5 m/s.")
AIMS = ("Issue aims: KLD-sampling using at least 3 times fewer particles while tracking than "
        "while globally localizing, with median position error under 0.15 m while walking.")
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
GLOBAL_WINDOW = 1.0  # "while globally localizing": the first second [s]
RECOVERED_M = 0.3  # localized: position error below this [m] ...
RECOVERED_HOLD = 1.0  # ... for this long [s]
KIDNAP_AT = 2.0 / 3.0  # fraction of the episode


class _Replay:
    """A filter fed as :class:`~soccer_env.humanoid_perception`'s robot brain feeds its
    localization: the brain's own odometry bookkeeping (kept with time stamps, composed up to
    a frame's capture time, turned into the filter's mid-step convention) on this filter."""

    kind = "kld"
    odometry = _Brain.odometry
    _odometry_until = _Brain._odometry_until
    _predict = _Brain._predict

    def __init__(self, loc: KLDLocalizer) -> None:
        self.loc = loc
        self.odo: deque[tuple[float, tuple[float, float, float]]] = deque()
        self._loc_estimate = loc.estimate()


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
                                  world.names, [0], camera, RADIO_PRESETS["ideal"],
                                  head_mode="scan")
    head = team.heads[0]
    start = np.array([-1.5, 0.6, 0.3])
    world.reset(start[None, :], (0.0, -(field.half_width + 0.45)), walk_rng)
    n_steps = int(round(duration / CONTROL_DT))
    segments, t = [], 0.0
    while t < duration:
        segments.append((t, float(route_rng.choice([0.0, 0.0, TURN_RATE, -TURN_RATE]))))
        t += float(route_rng.uniform(2.0, 5.0))
    route = {"returning": False, "segment": 0}
    kidnap_step = int(round(KIDNAP_AT * n_steps)) if kidnap else -1
    vmax = spec.max_forward_speed

    def frames_to_events(frames: list[Any]) -> None:
        for f in frames:  # the landmarks with a ground point, as the brain takes them
            kinds, ranges, bearings = [], [], []
            for kind, _u, _v, x, y, bearing in f.landmarks:
                r = math.hypot(x, y)
                if math.isfinite(r):
                    kinds.append(kind)
                    ranges.append(r)
                    bearings.append(bearing)
            events.append(("frame", f.t_capture, kinds, np.array(ranges), np.array(bearings)))

    events: list[tuple] = []
    times, poses = [world.time], [world.robot_array()[0, 0:3].copy()]
    frames_to_events(team.sensor.reset(world.snapshot(), head_state(world), cam_rng))
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
        frames_to_events(team.sensor.step(state, head_state(world)))
        falls = world.walk.falls[0]
    times_a, poses_a = np.array(times), np.array(poses)
    frame_t = np.array([ev[1] for ev in events if ev[0] == "frame"])
    # The truth at each frame's capture (a control step's time; the warm-up frame's, before
    # the start, is the start pose).
    at = np.minimum(np.searchsorted(times_a, frame_t - 1e-9), len(times_a) - 1)
    return {"events": events, "times": times_a, "poses": poses_a, "frame_t": frame_t,
            "frame_truth": poses_a[at],
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


def _run_filter(ep: dict[str, Any], config: KLDConfig, seed: int) -> dict[str, Any]:
    """Replay the episode into a filter of ``config`` started global; its errors per frame
    (at the frame's capture time) and the summary figures."""
    team = ep["team"]
    table = team.landmark_table
    rep = _Replay(KLDLocalizer(team.bounds, np.random.default_rng(seed), config))
    loc = rep.loc
    initial = loc.n
    est, counts = [], []
    seconds = 0.0
    for ev in ep["events"]:
        if ev[0] == "odo":
            rep.odometry(ev[1], ev[2], None)
            continue
        _, t_cap, kinds, ranges, bearings = ev
        t0 = time.perf_counter()
        rep._predict(rep._odometry_until(t_cap))
        if kinds:
            loc.update_kinds(kinds, ranges, bearings, table)
        rep._loc_estimate = loc.estimate()
        seconds += time.perf_counter() - t0
        est.append(rep._loc_estimate)
        counts.append(loc.n)
    t, truth = ep["frame_t"], ep["frame_truth"]
    e = np.array(est)
    err = np.hypot(e[:, 0] - truth[:, 0], e[:, 1] - truth[:, 1])
    herr = np.abs(np.remainder(e[:, 2] - truth[:, 2] + math.pi, 2.0 * math.pi) - math.pi)
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
            "initial_particles": int(initial),
            "first_second_particles": float(np.mean(n[t < GLOBAL_WINDOW])),
            "tracking_particles": float(np.mean(n[tracking])),
            "tracking_particles_median": float(np.median(n[tracking])),
            "ms_per_update": seconds / max(len(t), 1) * 1e3,
            "localized_s": _recovery(t, err, float(t[0]), tk if tk is not None else end),
            "recovery_s": None if tk is None else _recovery(t, err, tk, end)}


def _fmt(v: float | None) -> str:
    return "never" if v is None else f"{v:.1f}"


def run(out: str | Path = "paper_output", duration: float = 60.0, seed: int = 0,
        fixed_sizes: tuple[int, ...] = (100, 300, 1000, 3000), *,
        kidnap: bool = True) -> dict[str, Any]:
    """Record the walking episode once and replay it into KLD-sampling and into fixed-size
    filters; write ``paper_localization`` ``.md``, ``.csv``, ``.json`` and ``.png`` into
    ``out``. ``kidnap=False`` leaves the robot where it walks."""
    if not (isinstance(duration, (int, float)) and math.isfinite(duration)
            and 15.0 <= duration <= 3600.0):
        raise ValueError(f"duration must be in [15, 3600] s, got {duration!r}")
    sizes = tuple(fixed_sizes)
    if not all(isinstance(n, (int, np.integer)) and not isinstance(n, bool) and 1 <= n <= 100000
               for n in sizes):
        raise ValueError(f"fixed_sizes must be particle counts in [1, 100000], got {sizes!r}")
    if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) or seed < 0:
        raise ValueError(f"seed must be a non-negative integer, got {seed!r}")
    t0 = time.perf_counter()
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    ep = _episode(float(duration), int(seed), bool(kidnap))
    base = ep["team"].kld_config  # the camera's noise model, as the perception uses it
    default = KLDConfig()
    kld_cfg = dataclasses.replace(base, min_particles=default.min_particles,
                                  max_particles=default.max_particles)
    kld_name = f"KLD-sampling ({kld_cfg.min_particles}-{kld_cfg.max_particles})"
    results = {kld_name: _run_filter(ep, kld_cfg, seed + 1)}
    for n in sizes:
        cfg = dataclasses.replace(base, min_particles=int(n), max_particles=int(n))
        results[f"fixed {int(n)}"] = _run_filter(ep, cfg, seed + 1)
    kld = results[kld_name]
    tk = ep["kidnap_time"]
    spec = presets.robot(ROBOT)
    n_frames = len(kld["t"])
    seen = sum(1 for ev in ep["events"] if ev[0] == "frame" and ev[2])
    kid = ("no kidnapping" if tk is None else
           f"kidnapped at {tk:.1f} s to ({ep['kidnap_to'][0]:.2f}, {ep['kidnap_to'][1]:.2f}) m, "
           f"{math.degrees(ep['kidnap_to'][2]):.0f} deg, unknown to the filters")
    lines = [
        f"Walking humanoid ({ROBOT}, {CRUISE * spec.max_forward_speed:.2f} m/s, turning now "
        f"and then and at the edges) for {duration:g} s on the {FIELD} field (6 m x 4 m), head "
        f"scanning +-90 deg, {CAMERA} camera (51 deg, 25 Hz, landmarks by kind within 4 m: "
        f"{n_frames} frames, {seen} with landmarks); the walk engine's odometry; global start; "
        f"{kid}. Errors and tracking particles after the first {SETTLE:g} s, leaving out the "
        f"{SETTLE:g} s after the kidnapping.", "",
        "| filter | median position error [m] | median heading error [deg] | particles while "
        "globally localizing (first 1 s) | mean particles while tracking | ms per update | "
        "localized after [s] | recovered after the kidnapping [s] |",
        "|---|---|---|---|---|---|---|---|"]
    summary = {name: {k: v for k, v in r.items() if not isinstance(v, list)}
               for name, r in results.items()}
    for name, r in results.items():
        lines.append(f"| {name} | {r['median_pos_m']:.3f} | {r['median_head_deg']:.1f} | "
                     f"{r['global_particles']:.0f} | {r['tracking_particles']:.0f} | "
                     f"{r['ms_per_update']:.2f} | {_fmt(r['localized_s'])} | "
                     f"{_fmt(r['recovery_s'])} |")
    ratio = kld["global_particles"] / max(kld["tracking_particles"], 1.0)
    met = ratio >= 3.0 and kld["median_pos_m"] < 0.15
    lines += ["", f"KLD-sampling: {ratio:.1f} times fewer particles while tracking than while "
              f"globally localizing; median position error {kld['median_pos_m']:.3f} m while "
              f"walking ({'aims met' if met else 'aims NOT met'}).", "", AIMS, "", PAPER]
    if ep["falls"]:
        lines += ["", f"The robot fell {ep['falls']} time(s) during the episode."]
    text = "\n".join(lines)
    rows = [{"filter": name, **r} for name, r in summary.items()]
    files = write_report(out, "paper_localization", text, rows,
                         {"duration": duration, "seed": seed, "kidnap_time": tk,
                          "kidnap_to": None if tk is None else ep["kidnap_to"].tolist(),
                          "truth_t": ep["times"][::6].tolist(),
                          "truth_pose": ep["poses"][::6].tolist(), "results": results})
    plt = pyplot()
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(9, 6), sharex=True)
    for name, r in results.items():
        ax1.plot(r["t"], np.maximum(r["pos_err"], 1e-3), lw=1, label=name)
    ax1.axhline(RECOVERED_M, color="0.5", ls=":", lw=1)
    ax1.set(ylabel="position error [m]", yscale="log")
    ax1.legend(fontsize=7)
    ax2.plot(kld["t"], kld["counts"], "k-", lw=1)
    ax2.set(xlabel="time [s]", ylabel="particles (KLD)", yscale="log")
    if tk is not None:
        for ax in (ax1, ax2):
            ax.axvline(tk, color="r", ls="--", lw=1)
        ax1.text(tk, ax1.get_ylim()[1], " kidnapped", color="r", va="top", fontsize=8)
    files.append(save_figure(fig, out / "paper_localization.png"))
    return {"text": text, "files": files, "seconds": time.perf_counter() - t0,
            "results": summary}
