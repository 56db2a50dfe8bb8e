"""One seeded episode of Li, Wu and Kong (2010)'s reproduction: simulate the robots,
render the overhead frames, track every robot with every tracker kind and measure them (see
:mod:`soccer_lab.papers.meanshift`)."""

from __future__ import annotations

import math
import time
from typing import Any

import numpy as np

from estimators import MeanShiftParticleFilter, ParticleFilterTracker, mean_shift
from soccer_env import presets
from soccer_lab.papers.meanshift.scene import (
    CONTROL_DT,
    DOT_BOX,
    FIELD,
    FRAME,
    KINDS,
    LOST_KINDS,
    ROBOT,
    Driver,
    IdentityCheck,
    start_poses,
)

__all__ = ["run_episode", "Episode"]


def run_episode(args: tuple[int, float, int]) -> dict[str, Any]:
    """One seeded episode ``(seed, duration, robots_per_team)``: simulate, render, track;
    per-kind errors and timings (module level, for a process pool)."""
    seed, duration, per_team = args
    ep = Episode(seed, duration, per_team)
    for f in range(ep.n_frames):
        if f > 0:  # frame 0 shows the robots at rest at time 0
            ep.advance()
        ep.frame(f)
    return ep.result()


class Episode:
    """The state of one episode: the world, the renderer and its colour table, the robots'
    driver, the trackers and their identity checks, and the measures per frame and robot."""

    def __init__(self, seed: int, duration: float, per_team: int) -> None:
        from soccer_env.sensors.images.overhead import OverheadRenderer
        from soccer_env.sensors.images.patterns import PATTERN, PATTERN_IDS
        from soccer_env.sim.world import World

        self.seed = seed
        rng = np.random.default_rng([seed, 3])
        robot = presets.robot(ROBOT)
        self.n = n = 2 * per_team
        world = World(FIELD, presets.ball(FIELD.ball), robot, per_team, per_team,
                      control_dt=CONTROL_DT)
        hx, hy = FIELD.half_length, FIELD.half_width
        poses, ball = start_poses(rng, n, hx, hy, robot.radius + 0.15)
        world.reset(poses, ball)
        self.world = world
        self.teams = [0] * per_team + [1] * per_team
        self.rend = rend = OverheadRenderer(FRAME, FIELD, robot, world.ball_spec, self.teams)
        self.table = rend.colour_table()
        self.mpp = mpp = rend.metres_per_pixel
        self.steps_per_frame = max(1, int(round(1.0 / (rend.spec.frame_rate * CONTROL_DT))))
        self.n_frames = int(round(duration * rend.spec.frame_rate)) + 1
        self.driver = Driver(rng, n, robot.max_speed, robot.max_angular_speed, hx, hy)
        self.img_rng = np.random.default_rng([seed, 4])
        # Window: a square of the team patch's diameter [px], odd.
        patch_r_px = PATTERN.centre_radius * robot.radius / PATTERN.reference_radius / mpp
        self.side = 2 * int(math.ceil(patch_r_px)) + 1
        dots_px = (np.array(PATTERN.dot_positions) * (robot.radius / PATTERN.reference_radius)
                   / mpp)
        team_ids = list(range(per_team))
        colours = {j: PATTERN_IDS[j] for j in team_ids}
        self.radius_px = robot.radius / mpp
        self.trackers: dict[str, list[Any]] = {k: [] for k in KINDS}
        self.checks = [IdentityCheck(i if i < per_team else i - per_team, team_ids, dots_px,
                                     colours) for i in range(n)]
        m = self.n_frames - 1
        self.err = {k: np.zeros((m, n)) for k in KINDS}
        self.mate = {k: np.zeros((m, n), bool) for k in KINDS}
        self.lost = {k: np.zeros((m, n), bool) for k in LOST_KINDS}
        self.true_area_ok = np.zeros((m, n), bool)
        self.true_id_ok = np.zeros((m, n), bool)
        self.upd_s = dict.fromkeys(KINDS, 0.0)
        self.prep_s = 0.0
        self.speeds = np.zeros((m, n))
        self.track = np.zeros((self.n_frames, n, 2))  # true positions [px]
        self.team_of = np.array(self.teams)
        self.prev: np.ndarray | None = None
        self.areas: list[float] = []

    def advance(self) -> None:
        """The world's steps of one frame period, the robots driven by :class:`Driver`."""
        world = self.world
        for _ in range(self.steps_per_frame):
            world.step(self.driver.commands(world.time, world.robot_array()))

    def truth_px(self, state: Any) -> np.ndarray:
        """The robots' true centres in estimator pixels (pixel centres at integers)."""
        u, v = self.rend.to_pixel(state.robots[:, 0], state.robots[:, 1])
        return np.column_stack([u - 0.5, v - 0.5])

    def frame(self, f: int) -> None:
        """Render frame ``f``, compute the shared images (timed), then start the trackers
        (frame 0) or measure and update them."""
        state = self.world.snapshot()
        frame = self.rend.render(state, self.img_rng)
        truth = self.truth_px(state)
        self.track[f] = truth
        col, motion = self._images(frame)
        if f == 0:  # the trackers start here
            self.areas = self._start_trackers(truth, col)
            return
        self.speeds[f - 1] = np.hypot(state.robots[:, 3], state.robots[:, 4])
        self._diagnose(f, truth, col)
        self._track(f, truth, col, motion)

    def _images(self, frame: np.ndarray) -> tuple[list[np.ndarray], np.ndarray | None]:
        """The team colours' probability images and the frame difference (none on the first
        frame); the box-filtered dot colours given to the identity checks. Timed as
        preprocessing."""
        import cv2

        from estimators.image.colour import frame_difference

        table = self.table
        t0 = time.perf_counter()
        col = [table.probability(frame, "blue"), table.probability(frame, "yellow")]
        pink = cv2.blur(table.probability(frame, "pink"), (DOT_BOX, DOT_BOX))
        green = cv2.blur(table.probability(frame, "green"), (DOT_BOX, DOT_BOX))
        motion = None if self.prev is None else frame_difference(self.prev, frame)
        self.prep_s += time.perf_counter() - t0
        self.prev = frame
        for c in self.checks:
            c.set_images(pink, green)
        return col, motion

    def _start_trackers(self, truth: np.ndarray, col: list[np.ndarray]) -> list[float]:
        """Every tracker at the robots' true first positions; the mean-shift PF's colour
        mass measured on the first image (colour-only mean shift from the truth)."""
        side, areas = self.side, []
        for i in range(self.n):
            x0, y0 = (int(round(c - 0.5 * (side - 1))) for c in truth[i])
            area = mean_shift(col[self.teams[i]], (x0, y0, side, side), max_iter=5, eps=0.5)[3]
            areas.append(area)
            for k, (cls, npart, options) in KINDS.items():
                ms = cls == "MeanShiftParticleFilter"
                # The same draws for the variants of one tracker (common random numbers).
                trng = np.random.default_rng([self.seed, 5, i, npart, int(ms)])
                if ms:
                    tr = MeanShiftParticleFilter(truth[i], (side, side), trng,
                                                 n_particles=npart, area=max(area, 1e-6),
                                                 feature_check=self.checks[i], **options)
                else:
                    tr = ParticleFilterTracker(truth[i], (side, side), trng,
                                               n_particles=npart)
                self.trackers[k].append(tr)
        return areas

    def _diagnose(self, f: int, truth: np.ndarray, col: list[np.ndarray]) -> None:
        """Untimed: would the true robot's window pass the mean-shift PF's restriction
        (colour mass within the tolerance) and its identity check?"""
        side = self.side
        H, W = col[0].shape
        for i in range(self.n):
            x0 = min(max(int(round(truth[i, 0] - 0.5 * (side - 1))), 0), W - side)
            y0 = min(max(int(round(truth[i, 1] - 0.5 * (side - 1))), 0), H - side)
            mass = float(col[self.teams[i]][y0:y0 + side, x0:x0 + side].sum())
            tr = self.trackers["ms-pf-20"][i]
            self.true_area_ok[f - 1, i] = abs(mass - tr.area) <= tr.area_tolerance * tr.area
            self.true_id_ok[f - 1, i] = self.checks[i](np.array([[x0, y0, side, side]]),
                                                       col[self.teams[i]])[0]

    def _track(self, f: int, truth: np.ndarray, col: list[np.ndarray],
               motion: np.ndarray | None) -> None:
        """Update every tracker (timed, each update alone) and measure its error, its lost
        report and whether it sits on a team-mate."""
        radius_px = self.radius_px
        for k in KINDS:
            est = np.empty((self.n, 2))
            for i, tr in enumerate(self.trackers[k]):
                t1 = time.perf_counter()
                e = tr.update(col[self.teams[i]], motion)
                self.upd_s[k] += time.perf_counter() - t1
                est[i] = e[:2]
                if k in self.lost:
                    self.lost[k][f - 1, i] = tr.lost
            d = np.hypot(*(est[:, None, :] - truth[None, :, :]).transpose(2, 0, 1))
            self.err[k][f - 1] = np.diag(d)
            same = self.team_of[:, None] == self.team_of[None, :]
            np.fill_diagonal(same, False)
            self.mate[k][f - 1] = (((d <= radius_px) & same).any(axis=1)
                                   & (np.diag(d) > radius_px))

    def result(self) -> dict[str, Any]:
        """The episode's measures (lists, to travel back from a worker process cheaply)."""
        n_frames, track = self.n_frames, self.track
        updates = (n_frames - 1) * self.n
        # The AR(2) model's one-frame prediction error of the truth, |p_t - 2 p_t-1 + p_t-2|
        # [px].
        residual = np.hypot(*(track[2:] - 2 * track[1:-1] + track[:-2]).transpose(2, 0, 1))
        rend = self.rend
        return {"seed": self.seed, "mpp": self.mpp, "radius_px": self.radius_px,
                "window_px": self.side, "frames": n_frames - 1, "robots": self.n,
                "err_px": {k: v.tolist() for k, v in self.err.items()},
                "mate": {k: v.tolist() for k, v in self.mate.items()},
                "lost": {k: v.tolist() for k, v in self.lost.items()},
                "speed": self.speeds.tolist(),
                "residual_px": residual.tolist(), "true_area_ok": self.true_area_ok.tolist(),
                "true_id_ok": self.true_id_ok.tolist(),
                "ms_per_update": {k: 1e3 * v / updates for k, v in self.upd_s.items()},
                "prep_ms_per_frame": 1e3 * self.prep_s / n_frames, "areas": self.areas,
                "image": [rend.spec.width, rend.spec.height]}
