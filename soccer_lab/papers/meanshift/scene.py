"""The scene of Li, Wu and Kong (2010)'s reproduction: the field, robots and camera, the
robots' random sharp manoeuvres (:class:`Driver`) and the identity check by the player dots
(:class:`IdentityCheck`); see :mod:`soccer_lab.papers.meanshift`."""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from soccer_env import presets

__all__ = ["KINDS", "LOST_KINDS", "FRAME", "FIELD", "ROBOT", "CONTROL_DT", "INTERVAL", "SPEED",
           "TURN", "WALL_MARGIN", "INWARD_CONE", "HEADINGS", "DOT_BOX", "IdentityCheck",
           "start_poses", "Driver"]

#: Tracker kinds: name -> (class name, particles, keyword options). ``ms-pf-20-paper`` is
#: Li et al.'s (2010) step 4 as printed (unweighted mean of the restricted set, no resampling).
KINDS: dict[str, tuple[str, int, dict]] = {
    "ms-pf-20": ("MeanShiftParticleFilter", 20, {}),
    "ms-pf-20-paper": ("MeanShiftParticleFilter", 20, {"mean": "paper"}),
    "pf-20": ("ParticleFilterTracker", 20, {}),
    "pf-200": ("ParticleFilterTracker", 200, {})}
#: The kinds with a lost-track test (the mean-shift PFs).
LOST_KINDS = tuple(k for k, (cls, _, _) in KINDS.items() if cls == "MeanShiftParticleFilter")
#: The camera preset (Li et al.'s 2010 640 x 480 at 30 Hz, blur and noise).
FRAME = "mirosot"
#: MiroSot middle league (5 vs 5) dimensions on the ssl-2012 preset (see
#: :mod:`soccer_lab.papers.meanshift`).
FIELD = dataclasses.replace(
    presets.field("ssl-2012"), name="mirosot-middle", length=2.2, width=1.8, boundary=0.16,
    goal_width=0.4, goal_depth=0.15, goal_height=0.05, defense_width=0.8, defense_depth=0.35,
    center_circle_radius=0.25,
    source="MiroSot middle league (2.2 x 1.8 m, goal 0.4 m, penalty area 0.8 x 0.35 m, "
           "centre circle 0.25 m); 0.16 m to the walls (ours, holds the 0.15 m goals)")
ROBOT = "ssl"
CONTROL_DT = 1.0 / 60.0
#: Manoeuvres: interval [s], speed as a fraction of the top speed, turn rate as a fraction of
#: the top turn rate; wall margin [m] and the cone [rad] around the centre's direction.
INTERVAL = (0.2, 0.5)
SPEED = (0.8, 1.0)
TURN = 0.5
WALL_MARGIN = 0.3
INWARD_CONE = math.radians(60.0)
#: Identity check: headings tried, box filter [px].
HEADINGS = 24
DOT_BOX = 5


class IdentityCheck:
    """``feature_check`` of one robot (see :mod:`soccer_lab.papers.meanshift`): its own dot
    pattern must beat its team-mates'. :meth:`set_images` gives it the frame's box-filtered pink
    and green images."""

    def __init__(self, own: int, team_ids: list[int], dot_offsets_px: np.ndarray,
                 dot_colours: dict[int, tuple[str, ...]]) -> None:
        self.own = own
        self.others = [j for j in team_ids if j != own]
        h = np.linspace(0.0, 2.0 * math.pi, HEADINGS, endpoint=False)
        c, s = np.cos(h)[:, None], np.sin(h)[:, None]
        bx, by = dot_offsets_px[:, 0][None, :], dot_offsets_px[:, 1][None, :]
        # Image offsets (u right, v down) of the 4 dots at each heading: (HEADINGS, 4).
        self.du = c * bx - s * by
        self.dv = -(s * bx + c * by)
        # +1 where a pattern's dot is pink, -1 where green: (ids, 4).
        self.sign = {j: np.array([1.0 if col == "pink" else -1.0 for col in dot_colours[j]])
                     for j in team_ids}
        self.pink: np.ndarray | None = None
        self.green: np.ndarray | None = None

    def set_images(self, pink: np.ndarray, green: np.ndarray) -> None:
        """The frame's box-filtered pink and green probability images."""
        self.pink, self.green = pink, green

    def __call__(self, windows: np.ndarray, colour_image: np.ndarray) -> np.ndarray:
        """Per window ``(x, y, w, h)``: whether it shows this robot's dot pattern."""
        H, W = self.pink.shape
        cu = windows[:, 0] + 0.5 * (windows[:, 2] - 1)
        cv = windows[:, 1] + 0.5 * (windows[:, 3] - 1)
        u = np.clip(np.rint(cu[:, None, None] + self.du[None]), 0, W - 1).astype(np.intp)
        v = np.clip(np.rint(cv[:, None, None] + self.dv[None]), 0, H - 1).astype(np.intp)
        flat = v * W + u  # (N, HEADINGS, 4)
        diff = self.pink.ravel()[flat] - self.green.ravel()[flat]  # + pink, - green
        own = (diff * self.sign[self.own]).sum(axis=2).max(axis=1)
        ok = own > 0.0
        for j in self.others:
            ok &= own > (diff * self.sign[j]).sum(axis=2).max(axis=1)
        return ok


def start_poses(rng: np.random.Generator, n: int, hx: float, hy: float, margin: float
                ) -> tuple[np.ndarray, tuple[float, float]]:
    """``n`` robot poses at least 0.4 m apart and a ball position 0.2 m from every robot."""
    pts: list[tuple[float, float]] = []
    while len(pts) < n + 1:
        p = (float(rng.uniform(-hx + margin, hx - margin)),
             float(rng.uniform(-hy + margin, hy - margin)))
        need = 0.4 if len(pts) < n else 0.2
        if all(math.hypot(p[0] - q[0], p[1] - q[1]) >= need for q in pts):
            pts.append(p)
    poses = np.array([[x, y, rng.uniform(-math.pi, math.pi)] for x, y in pts[:n]])
    return poses, pts[n]


class Driver:
    """The robots' random sharp manoeuvres (:mod:`soccer_lab.papers.meanshift`)."""

    def __init__(self, rng: np.random.Generator, n: int, vmax: float, wmax: float,
                 hx: float, hy: float) -> None:
        self.rng, self.n, self.vmax, self.wmax, self.hx, self.hy = rng, n, vmax, wmax, hx, hy
        self.cmd = np.zeros((n, 6))
        self.until = np.zeros(n)

    def _draw(self, i: int, t: float, heading: float, inward: float | None) -> None:
        rng = self.rng
        speed = self.vmax * rng.uniform(*SPEED)
        if inward is None:
            a = rng.uniform(-math.pi, math.pi)  # body frame
        else:  # field direction within the cone around the centre's direction, to body frame
            a = inward + rng.uniform(-INWARD_CONE, INWARD_CONE) - heading
        self.cmd[i, 0], self.cmd[i, 1] = speed * math.cos(a), speed * math.sin(a)
        self.cmd[i, 2] = self.wmax * TURN * rng.uniform(-1.0, 1.0)
        self.until[i] = t + rng.uniform(*INTERVAL)

    def commands(self, t: float, robots: np.ndarray) -> np.ndarray:
        """Every robot's command at time ``t`` for the true ``robots`` (a new manoeuvre when
        its time is up or it heads for a near wall)."""
        for i in range(self.n):
            x, y, th = robots[i, 0:3]
            if t >= self.until[i]:
                self._draw(i, t, th, None)
            # Field-frame direction of the command; turn back from a near wall.
            c, s = math.cos(th), math.sin(th)
            fx = c * self.cmd[i, 0] - s * self.cmd[i, 1]
            fy = s * self.cmd[i, 0] + c * self.cmd[i, 1]
            near = ((x > self.hx - WALL_MARGIN and fx > 0) or (x < -self.hx + WALL_MARGIN
                                                               and fx < 0)
                    or (y > self.hy - WALL_MARGIN and fy > 0)
                    or (y < -self.hy + WALL_MARGIN and fy < 0))
            if near:
                self._draw(i, t, th, math.atan2(-y, -x))
        return self.cmd
