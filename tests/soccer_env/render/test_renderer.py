"""The renderer on synthetic scenes: 2-sigma ellipses drawn to scale, a legend of exactly what
is on screen, faint particle clouds, readable robot marks, and copies that draw alike."""

from __future__ import annotations

import copy
import math
import pickle

import numpy as np
import pytest

pytest.importorskip("pygame")

from soccer_env import presets  # noqa: E402
from soccer_env.render import OVERLAY_COLOURS, Banner, Renderer  # noqa: E402
from soccer_env.render.geometry import ellipse_axes  # noqa: E402
from soccer_env.state import Belief, BeliefSpread, WorldState  # noqa: E402

FIELD = presets.field("ssl-div-b")
ROBOT = presets.robot("ssl")
BALL = presets.ball("ssl")


def _state(robots=((-2.0, 1.0, 0.0), (2.0, -1.0, math.pi)), teams=(0, 1),
           ball=(1.0, 0.5, 0.0)) -> WorldState:
    rows = np.zeros((len(robots), 6))
    if len(robots):
        rows[:, 0:3] = robots
    names = tuple(f"{('blue', 'yellow')[t]}_{k}" for k, t in enumerate(teams))
    b = np.zeros(6)
    b[0:3] = ball
    return WorldState(0.0, b, rows, names, np.array(teams, dtype=np.int64))


def _renderer(width: int = 640, **kwargs) -> Renderer:
    return Renderer(FIELD, ROBOT, BALL, "rgb_array", width, **kwargs)


def _mask(frame: np.ndarray, colour, rows: int) -> np.ndarray:
    """Pixels of exactly ``colour`` in the field view (its first ``rows`` rows)."""
    return np.all(frame[:rows] == np.array(colour, dtype=np.uint8), axis=-1)


def _belief(state: WorldState, ball_cov=None, robot_covs=None, **spread) -> Belief:
    n = len(state.robots)
    covs = np.full((n, 2, 2), np.nan) if robot_covs is None else np.asarray(robot_covs)
    return Belief(0.0, state.ball.copy(), state.robots.copy(),
                  spread=BeliefSpread(ball_cov, covs, **spread))


def test_two_sigma_ellipse_is_drawn_to_scale():
    """A ball covariance diag(0.2^2, 0.1^2) m^2: the ellipse's half-extents are 2 sigma times
    the scale, 0.4 m and 0.2 m, within the line's width."""
    r = _renderer()
    state = _state(robots=(), teams=())
    frame = r.draw(state, belief=_belief(state, np.diag([0.2**2, 0.1**2])))
    assert "ellipses" in r.contents.legend
    ys, xs = np.nonzero(_mask(frame, OVERLAY_COLOURS["ellipses"], r.contents.field_height))
    cx, cy = r.pixel(1.0, 0.5)
    s = r.contents.scale
    assert abs(0.5 * (xs.max() - xs.min()) - 0.4 * s) <= 1.5
    assert abs(0.5 * (ys.max() - ys.min()) - 0.2 * s) <= 1.5
    assert abs(0.5 * (xs.max() + xs.min()) - cx) <= 1.0
    assert abs(0.5 * (ys.max() + ys.min()) - cy) <= 1.0


def test_rotated_ellipse_points_along_its_major_axis():
    """Eigenvalues 0.3^2 and 0.05^2 m^2, major axis at 30 degrees: the farthest ellipse pixel
    lies 2 * 0.3 m from the centre along +-30 degrees (image y points down)."""
    a = math.radians(30.0)
    rot = np.array([[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]])
    cov = rot @ np.diag([0.3**2, 0.05**2]) @ rot.T
    big, small, angle = ellipse_axes(cov)
    assert (big, small, angle) == pytest.approx((0.6, 0.1, a))
    r = _renderer(960)
    state = _state(robots=(), teams=())
    frame = r.draw(state, belief=_belief(state, cov))
    ys, xs = np.nonzero(_mask(frame, OVERLAY_COLOURS["ellipses"], r.contents.field_height))
    cx, cy = r.pixel(1.0, 0.5)
    d = np.hypot(xs - cx, ys - cy)
    far = np.argmax(d)
    s = r.contents.scale
    assert abs(d[far] - 0.6 * s) <= 2.0
    direction = math.atan2(-(ys[far] - cy), xs[far] - cx)
    assert abs(math.remainder(direction - a, math.pi)) < math.radians(4.0)


def test_a_scalar_sigma_is_a_circle_and_unknown_spreads_are_not_drawn():
    """A robot known to sigma per axis (sigma^2 I): a circle of radius 2 sigma; a NaN
    covariance (not modelled) and a spread hidden under the robot draw nothing."""
    r = _renderer()
    state = _state(robots=((-2.0, 1.0, 0.0), (2.0, -1.0, 0.0)))
    sigma = 0.15
    covs = [sigma**2 * np.eye(2), np.full((2, 2), np.nan)]
    frame = r.draw(state, belief=_belief(state, robot_covs=covs))
    ys, xs = np.nonzero(_mask(frame, OVERLAY_COLOURS["ellipses"], r.contents.field_height))
    cx, cy = r.pixel(-2.0, 1.0)
    d = np.hypot(xs - cx, ys - cy)
    assert len(d) and abs(np.median(d) - 2 * sigma * r.contents.scale) <= 1.0
    assert abs((xs.max() - xs.min()) - (ys.max() - ys.min())) <= 1  # a circle
    tiny = [1e-6 * np.eye(2), np.full((2, 2), np.nan)]
    r.draw(state, belief=_belief(state, robot_covs=tiny))
    assert "ellipses" not in r.contents.overlays


def test_the_legend_lists_exactly_what_is_drawn():
    r = _renderer()
    state = _state()
    frame = r.draw(state)
    rows = r.contents.field_height
    assert r.contents.legend == ("team0", "team1", "ball")
    assert r.contents.labels == ("blue team", "yellow team", "ball")
    assert not _mask(frame, OVERLAY_COLOURS["belief"], rows).any()
    assert _mask(frame, OVERLAY_COLOURS["ball"], rows).any()

    moving = Belief(0.0, np.array([1.0, 0.5, 0.0, 2.0, 0.0, 0.0]), state.robots.copy())
    frame = r.draw(state, belief=moving)
    assert r.contents.legend == ("team0", "team1", "ball", "belief_robots", "belief_ball",
                                 "belief_velocity")
    assert _mask(frame, OVERLAY_COLOURS["belief"], rows).sum() > 50

    r.show_overlays = False
    frame = r.draw(state, belief=moving)
    assert r.contents.legend == ("team0", "team1", "ball")
    assert not _mask(frame, OVERLAY_COLOURS["belief"], rows).any()

    r.show_overlays, r.show_legend = True, False
    frame_no_legend = r.draw(state, belief=moving)
    assert r.contents.legend == () and "belief_ball" in r.contents.overlays
    assert frame_no_legend.shape == frame.shape  # the frame keeps its size


def test_one_team_and_a_ball_in_flight():
    r = _renderer()
    state = _state(robots=((-4.0, 0.0, 0.0),), teams=(0,), ball=(0.0, 0.0, 0.3))
    r.draw(state)
    assert r.contents.legend == ("team0", "ball_flight")


def test_particle_clouds_are_faint_and_listed():
    """Particles are blended over the carpet: tinted towards their colour, not painted."""
    r = _renderer()
    state = _state(robots=((-4.0, 0.0, 0.0),), teams=(0,))
    rng = np.random.default_rng(0)
    ball = rng.normal((2.0, 1.5), 0.3, (100, 2))
    poses = np.column_stack([rng.normal((-4.0, 0.0), 0.25, (300, 2)), np.zeros(300)])
    frame = r.draw(state, belief=_belief(state, ball_particles=ball, pose_particles=poses))
    assert {"ball_particles", "pose_particles"} <= set(r.contents.legend)
    px, py = r.pixel(2.0, 1.5)
    patch = frame[py - 40:py + 40, px - 40:px + 40].reshape(-1, 3).astype(int)
    carpet = np.array([24, 120, 48])
    tinted = patch[np.abs(patch - carpet).sum(axis=1) > 30]
    assert len(tinted) > 50
    # Between the carpet and the particles' colour: faint.
    assert (tinted[:, 2] < 230).all() and (tinted[:, 2] > 100).all()


def test_robots_are_drawn_at_least_their_minimum_size_with_a_readable_number():
    r = _renderer(640)
    state = _state(robots=((1.5, 1.0, 0.0),), teams=(0,), ball=(3.0, 2.0, 0.0))
    frame = r.draw(state)
    cx, cy = r.pixel(1.5, 1.0)
    column = frame[:, cx].astype(int)  # across the robot, beside its flat front
    carpet = np.abs(column - (24, 120, 48)).sum(axis=1) < 10
    top, bottom = cy, cy
    while not carpet[top - 1]:
        top -= 1
    while not carpet[bottom + 1]:
        bottom += 1
    # At least 1/80 of the width in radius (to scale: 0.09 m x 66.7 px/m = 6 px).
    assert bottom - top + 1 >= 2 * 640 / 80 - 1
    # The number: white on a black outline beside the robot (a blue one's to its left).
    near = frame[cy - 30:cy + 5, cx - 30:cx].reshape(-1, 3)
    assert (near == 240).all(axis=1).sum() > 5 and (near == 0).all(axis=1).sum() > 5


def test_title_card_and_banner_and_their_pixels():
    r = _renderer()
    state = _state()
    plain = r.draw(state)
    titled = r.draw(state, title=["soccer_env/Goalkeeper-v0    seed 3", "robot ssl"])
    assert r.contents.title[0].endswith("seed 3")
    rows = r.contents.field_height
    w = plain.shape[1]

    def dark(frame):
        return (frame[5:rows // 8, w // 2 - 60:w // 2 + 60] < 50).all(axis=-1).mean()

    assert dark(plain) < 0.05 and dark(titled) > 0.4  # a dark box across the top
    banner = r.draw(state, banner=Banner("GOAL", "the shot went in", "bad"))
    assert r.contents.banner.text == "GOAL" and r.contents.title == ()
    h, w = rows // 2, plain.shape[1] // 2
    centre = banner[h - 5:h + 5, w - 60:w + 60].reshape(-1, 3).astype(int)
    assert (centre[:, 0] > centre[:, 1] + 40).mean() > 0.3  # a red box in the middle


def test_copies_draw_the_same_frames():
    """pickle and deepcopy rebuild pygame's parts and keep the toggles and the follow view's
    smoothing, so a copy draws what the original draws."""
    r = _renderer(view="follow")
    state = _state()
    r.draw(state)
    r.show_legend = False
    copiers = (copy.deepcopy, lambda x: pickle.loads(pickle.dumps(x)))
    for k, copier in enumerate(copiers):
        twin = copier(r)
        assert (twin.view, twin.show_legend) == ("follow", False)
        # The ball moved and the robots are farther: the window widens smoothly, alike.
        later = state._replace(time=0.5 + k, ball=np.array([2.0, 1.0, 0.0, 0.0, 0.0, 0.0]))
        assert np.array_equal(twin.draw(later), r.draw(later))
        assert twin.contents == r.contents


def test_rgb_array_needs_no_display_and_keeps_its_size():
    import pygame

    r = _renderer(960)
    a = r.draw(_state())
    b = r.draw(_state(robots=(), teams=()), title=["x"], banner=Banner("SAVED"))
    assert not pygame.display.get_init() or pygame.display.get_surface() is None
    assert a.shape == b.shape == (r.size[1], 960, 3) and a.dtype == np.uint8


def test_small_frames_have_no_info_bar():
    r = _renderer(160)
    frame = r.draw(_state(), hud=["t = 0.00 s"])
    assert frame.shape[:2] == (r.field_size[1], 160) and r.contents.legend == ()


def test_bad_view_is_refused():
    with pytest.raises(ValueError, match=r"render_view must be one of \['field', 'follow'\]"):
        _renderer(view="zoom")
