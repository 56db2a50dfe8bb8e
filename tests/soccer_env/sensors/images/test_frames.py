"""Camera images drawn with OpenCV (soccer_env.sensors.images.overhead)."""

import math

import numpy as np
import pytest

pytest.importorskip("cv2", reason="rendered frames need the 'pixels' extra (OpenCV)")

from estimators.image.colour import (
    ColourTable,
    back_project,
    difference_image,
    frame_difference,
    grey,
    hue_histogram,
)
from soccer_env import presets
from soccer_env.presets.images import (
    CLASS_ALIASES,
    COLOURS,
    OVERHEAD_CLASSES,
    head_frame,
    overhead_frame,
)
from soccer_env.presets.sensors import head_camera
from soccer_env.sensors.images.head import HeadFrameRenderer
from soccer_env.sensors.images.overhead import OverheadRenderer
from soccer_env.sensors.images.patterns import PATTERN_IDS, PatchPattern, patch_pattern
from soccer_env.sensors.overhead import default_cameras
from soccer_env.state import (
    HeadState,
    WorldState,  # noqa: E402
)

FIELD = presets.field("ssl-div-b")
SSL = presets.robot("ssl")
BALL = presets.ball("ssl")
HFIELD = presets.field("humanoid-kid")
HUMANOID = presets.robot("humanoid")
HBALL = presets.ball("kidsize")
# 640 x 480 pixels over 0.64 x 0.48 m: 1 mm per pixel, on plain carpet (no line in view),
# centred on (CX, 0).
CX = 1.32
ZOOM = (CX - 0.32, CX + 0.32, -0.24, 0.24)


def world(robots, ball=(0.0, 0.0, 0.0, 0.0, 0.0, 0.0), teams=None):
    robots = np.array(robots, dtype=float).reshape(-1, 6)
    n = len(robots)
    teams = [0] * n if teams is None else teams
    return WorldState(0.0, np.array(ball, dtype=float), robots,
                      tuple(f"r{i}" for i in range(n)), np.array(teams))


def zoom_renderer(teams=(0,), robot=SSL, **overrides):
    spec = overhead_frame("clean", region=ZOOM, **overrides)
    return OverheadRenderer(spec, FIELD, robot, BALL, list(teams))


FAR = (-3.0, -2.0, 0.0, 0.0, 0.0, 0.0)  # a robot out of the zoomed view


def orange_alpha(img, background=COLOURS["carpet"]):
    """Coverage of the ball colour per pixel, from the mix of orange and the background
    (0 for colours off that mix)."""
    o, b = np.array(COLOURS["orange"], float), np.array(background, float)
    d = o - b
    x = img.astype(float) - b
    alpha = np.clip((x @ d) / (d @ d), 0.0, 1.0)
    off = np.linalg.norm(x - alpha[..., None] * d, axis=-1) > 20.0
    alpha[off] = 0.0
    return alpha


def blob(alpha):
    """Area, centroid (continuous pixel coordinates) and covariance of a coverage map."""
    v, u = np.mgrid[0:alpha.shape[0], 0:alpha.shape[1]]
    m = alpha.sum()
    cu, cv = (alpha * (u + 0.5)).sum() / m, (alpha * (v + 0.5)).sum() / m
    du, dv = u + 0.5 - cu, v + 0.5 - cv
    cov = np.array([[(alpha * du * du).sum(), (alpha * du * dv).sum()],
                    [(alpha * du * dv).sum(), (alpha * dv * dv).sum()]]) / m
    return m, (cu, cv), cov


def blob_near(alpha, u, v, half=40):
    """:func:`blob` of the window of ``alpha`` within ``half`` pixels of ``(u, v)``, in image
    coordinates (keeps anti-aliased edges of far lines out)."""
    u0, v0 = max(0, int(u) - half), max(0, int(v) - half)
    area, (cu, cv), cov = blob(alpha[v0:int(v) + half, u0:int(u) + half])
    return area, (cu + u0, cv + v0), cov


# ------------------------------------------------------------------------------ overhead


def test_pixel_mapping_round_trip_and_fit():
    r = OverheadRenderer("clean", FIELD, SSL, BALL, [0])
    rng = np.random.default_rng(0)
    x, y = rng.uniform(-5, 5, 100), rng.uniform(-3.5, 3.5, 100)
    u, v = r.to_pixel(x, y)
    x2, y2 = r.to_field(u, v)
    assert np.allclose(x, x2) and np.allclose(y, y2)
    # The walled area (9.6 x 6.6 m) fits the 640 x 480 image: 15 mm per pixel, centred.
    wx, wy = FIELD.half_length + FIELD.boundary, FIELD.half_width + FIELD.boundary
    assert r.metres_per_pixel == pytest.approx(2 * wx / 640)
    assert r.to_pixel(-wx, 0.0) == pytest.approx((0.0, 240.0))
    assert r.to_pixel(wx, 0.0) == pytest.approx((640.0, 240.0))
    assert r.to_pixel(0.0, wy)[1] == pytest.approx(240.0 - wy / r.metres_per_pixel)
    # A camera of vision's quadrant layout.
    cam = default_cameras(FIELD, 4.0, 0.3)[1]
    rc = OverheadRenderer("clean", FIELD, SSL, BALL, [0], camera=cam)
    assert rc.region == (cam.x_min, cam.x_max, cam.y_min, cam.y_max)
    assert rc.to_field(320.0, 240.0) == pytest.approx(
        (0.5 * (cam.x_min + cam.x_max), 0.5 * (cam.y_min + cam.y_max)))


def test_patch_pattern_scheme():
    assert len(set(PATTERN_IDS)) == 16
    assert all(PatchPattern.identify(ids) == k for k, ids in enumerate(PATTERN_IDS))
    assert PatchPattern.identify(("pink",) * 3) is None
    p = patch_pattern(1, 3)
    assert p[0][:2] == (0.0, 0.0) and p[0][3] == COLOURS["yellow"]
    assert [c for *_, c in p[1:]] == [COLOURS[n] for n in PATTERN_IDS[3]]
    # The heading shows in the layout: the front pair is wider apart than the rear pair.
    (fl, fr, rr, rl) = [(x, y) for x, y, *_ in p[1:]]
    assert fl[0] > 0 and fr[0] > 0 and rr[0] < 0 and rl[0] < 0
    assert fl[1] - fr[1] > rl[1] - rr[1] + 0.03
    # Everything stays on the robot's top (inside the flat front).
    assert all(x + r <= SSL.front_distance and math.hypot(x, y) + r <= SSL.radius
               for x, y, r, _ in p)
    # Scaled for a larger robot.
    big = patch_pattern(0, 3, robot_radius=0.18)
    assert big[1][0] == pytest.approx(2 * p[1][0]) and big[1][2] == pytest.approx(2 * p[1][2])
    with pytest.raises(ValueError, match="team"):
        patch_pattern(2, 0)
    with pytest.raises(ValueError, match="index"):
        patch_pattern(0, 16)


@pytest.mark.parametrize("robot", [SSL, HUMANOID], ids=["ssl", "humanoid"])
def test_patches_at_the_right_pixels(robot):
    r = zoom_renderer(teams=(1, 1), robot=robot)
    x, y, th = CX + 0.01, 0.03, 0.7
    img = r.render(world([FAR, (x, y, th, 0, 0, 0)]))
    c, s = math.cos(th), math.sin(th)

    def colour_at(bx, by):
        u, v = r.to_pixel(x + c * bx - s * by, y + s * bx + c * by)
        return tuple(img[int(v), int(u)].tolist())

    patches = patch_pattern(1, 1, robot_radius=robot.radius)  # second yellow robot
    for px, py, radius, rgb in patches:
        assert colour_at(px, py) == rgb
        # ... and over most of its disc.
        assert colour_at(px + 0.6 * radius, py) == rgb
    k = robot.radius / 0.09
    assert colour_at(-0.075 * k, 0.0) == COLOURS["body"]  # behind the centre, between dots
    assert colour_at(0.0, robot.radius + 0.01) == r.spec.carpet


def test_ball_centre_and_radius():
    r = zoom_renderer()
    bx, by = CX + 0.0234, -0.0567
    img = r.render(world([FAR], ball=(bx, by, 0, 0, 0, 0)))
    area, (cu, cv), _ = blob(orange_alpha(img))
    u, v = r.to_pixel(bx, by)
    assert abs(cu - u) < 1.0 and abs(cv - v) < 1.0
    assert math.sqrt(area / math.pi) == pytest.approx(BALL.radius / r.metres_per_pixel, abs=1.0)


def test_chipped_ball_is_offset_and_enlarged():
    r = zoom_renderer()  # camera 4 m above the region's centre (CX, 0)
    bx, by, bz = CX + 0.15, 0.1, 0.4
    img = r.render(world([FAR], ball=(bx, by, bz, 0, 0, 0)))
    area, (cu, cv), _ = blob(orange_alpha(img))
    h, rad = r.spec.camera_height, BALL.radius
    k = (h - rad) / (h - bz - rad)
    u, v = r.to_pixel(CX + (bx - CX) * k, by * k)
    assert abs(cu - u) < 1.0 and abs(cv - v) < 1.0
    assert math.sqrt(area / math.pi) == pytest.approx(k * rad / r.metres_per_pixel, abs=1.0)


def test_motion_blur_smears_along_the_velocity():
    r = zoom_renderer(exposure=0.01)
    still = orange_alpha(r.render(world([FAR], ball=(CX, 0.0, 0, 0, 0, 0))))
    m0, _, cov0 = blob(still)
    assert cov0[0, 0] == pytest.approx(cov0[1, 1], rel=0.05)  # round when still
    # 4 m/s along x for 10 ms: 40 mm = 40 px of smear (a disc of 21.5 px radius has a
    # variance of r^2 / 4 = 116 px^2 along each axis; the smear adds about 40^2 / 12 = 133).
    fast = orange_alpha(r.render(world([FAR], ball=(CX, 0.0, 0, 4.0, 0, 0))))
    m1, (cu, cv), cov1 = blob(fast)
    assert m1 == pytest.approx(m0, rel=0.05)  # the same ink, spread out
    assert cov1[0, 0] - cov1[1, 1] > 0.8 * 40**2 / 12
    assert cu == pytest.approx(r.to_pixel(CX, 0.0)[0], abs=1.0)  # exposure centred
    assert cov1[1, 1] == pytest.approx(cov0[1, 1], rel=0.1)
    # Diagonally: the long axis follows the image velocity (u right, v down).
    diag = orange_alpha(r.render(world([FAR], ball=(CX, 0.0, 0, 3.0, 3.0, 0))))
    _, _, cov2 = blob(diag)
    w, vecs = np.linalg.eigh(cov2)
    assert w[1] - w[0] > 0.8 * (0.01 * 3 * math.sqrt(2) * 1000) ** 2 / 12
    assert abs(vecs[:, 1] @ np.array([1.0, -1.0]) / math.sqrt(2)) > 0.98
    # A robot that moves is smeared too; one that stands is drawn as without blur.
    robot = (CX, 0.0, 0.3, 0.0, 0.0, 0.0)
    sharp = zoom_renderer().render(world([robot]))
    assert np.array_equal(r.render(world([robot])), sharp)
    moving = r.render(world([(CX, 0.0, 0.3, 2.0, 0.0, 0.0)]))
    assert not np.array_equal(moving, sharp)


def test_noise_statistics():
    clean = zoom_renderer()
    noisy = zoom_renderer(noise_sigma=4.0)
    state = world([FAR], ball=(-1.0, 0.0, 0, 0, 0, 0))
    base = clean.render(state).astype(float)
    rng = np.random.default_rng(3)
    d1 = noisy.render(state, rng).astype(float) - base
    d2 = noisy.render(state, rng).astype(float) - base
    assert abs(d1.mean()) < 0.1
    assert d1.std() == pytest.approx(4.0, rel=0.05)
    # Independent between neighbours and between frames.
    assert abs(np.corrcoef(d1[:, :-1].ravel(), d1[:, 1:].ravel())[0, 1]) < 0.02
    assert abs(np.corrcoef(d1.ravel(), d2.ravel())[0, 1]) < 0.02
    # Lighting: a global gain plus a ramp across the image.
    lit = zoom_renderer(gain_sigma=0.1, gradient=0.3)
    means = []
    for _ in range(5):
        img = lit.render(state, rng).astype(float)
        ratio = img[..., 1] / base[..., 1]  # green channel of the carpet
        means.append(ratio.mean())
        corners = [ratio[:20, :20].mean(), ratio[-20:, -20:].mean(), ratio[:20, -20:].mean(),
                   ratio[-20:, :20].mean()]
        assert 0.5 < min(corners) and max(corners) < 1.6
    assert np.std(means) > 0.01
    with pytest.raises(ValueError, match="rng"):
        noisy.render(state)


def test_same_seed_same_image():
    r = OverheadRenderer("realistic", FIELD, SSL, BALL, [0, 0, 1])
    state = world([(0, 0, 0, 1, 0, 2), (1, 1, 1, 0, 0, 0), (-1, 0.5, 2, 0, -2, 0)],
                  ball=(0.3, 0.2, 0, 5, 1, 0), teams=[0, 0, 1])
    a = r.render(state, np.random.default_rng(7))
    b = r.render(state, np.random.default_rng(7))
    c = r.render(state, np.random.default_rng(8))
    assert a.shape == (480, 640, 3) and a.dtype == np.uint8
    assert np.array_equal(a, b)
    assert not np.array_equal(a, c)


# ------------------------------------------------------------------------------ head camera


def head_renderer(camera="kidsize", robots=1, spec="clean", size=(320, 240)):
    return HeadFrameRenderer(head_camera(camera), HFIELD, HUMANOID, HBALL, [0] * robots, spec,
                             size)


def robot_frame(point, observer):
    """Robot-frame (x forward, y left) coordinates of a field point."""
    x, y, th = observer
    dx, dy = point[0] - x, point[1] - y
    c, s = math.cos(th), math.sin(th)
    return [c * dx + s * dy, -s * dx + c * dy] + list(point[2:])


def test_head_ball_straight_ahead():
    r = head_renderer()
    obs = (-3.0, 2.0, -0.5)
    d = 1.5
    bx, by = obs[0] + d * math.cos(obs[2]), obs[1] + d * math.sin(obs[2])
    h = r.camera.height
    tilt = math.atan2(h - HBALL.radius, d)  # ball centre on the optical axis
    img = r.render(world([obs + (0, 0, 0)], ball=(bx, by, 0, 0, 0, 0)),
                   HeadState.steady(1, 0.0, tilt), 0)
    assert img.shape == (240, 320, 3) and img.dtype == np.uint8
    area, (cu, cv), _ = blob_near(orange_alpha(img), 160, 120)
    assert cu == pytest.approx(160.0, abs=1.0) and cv == pytest.approx(120.0, abs=1.0)
    expected = r.camera.focal_px * HBALL.radius / math.hypot(d, h - HBALL.radius)
    assert math.sqrt(area / math.pi) == pytest.approx(expected, abs=1.0)


def test_head_goal_post_where_the_camera_model_projects_it():
    r = head_renderer("kidsize-2012")  # coloured goals: yellow at x = +L/2
    obs = (2.3, 0.2, -0.3)
    img = r.render(world([obs + (0, 0, 0)], ball=(-3, 0, 0, 0, 0, 0)),
                   HeadState.steady(1, 0.0, 0.0), 0)
    py = 0.5 * (HFIELD.goal_width + HFIELD.goal_wall_thickness)
    post = (HFIELD.half_length, -py)
    pts = np.array([robot_frame(post + (0.0,), obs), robot_frame(post + (HFIELD.goal_height,),
                                                                 obs)])
    (uf, vf), (ut, vt) = r.camera.project(pts, 0.0, 0.0)[0]
    assert abs(uf - ut) < 0.5  # vertical
    col = img[:, int(uf)]
    yellow = np.all(np.abs(col.astype(int) - COLOURS["yellow"]) < 30, axis=1)
    assert yellow[int(vt) + 3:int(vf) - 3].all()
    assert not yellow[int(vf) + 4] and not yellow[int(vt) - 4]


def test_head_horizon_row_matches_tilt():
    r = head_renderer()
    sky = np.array(r.spec.sky)
    for tilt in (0.25, 0.0, -0.15):
        img = r.render(world([(0.5, -0.3, 2.0, 0, 0, 0)], ball=(3, 0, 0, 0, 0, 0)),
                       HeadState.steady(1, 0.0, tilt), 0)
        row = 120.0 - r.camera.focal_px * math.tan(tilt)
        assert r.horizon_row(tilt) == pytest.approx(row)
        assert np.all(img[int(row) - 2] == sky)
        assert not np.any(np.all(img[int(row) + 2] == sky, axis=1))


def test_head_sway_shifts_the_image():
    r = head_renderer()
    obs = (-1.0, 0.5, 0.4)
    ball = (obs[0] + 1.2 * math.cos(0.4), obs[1] + 1.2 * math.sin(0.4), 0, 0, 0, 0)
    state = world([obs + (0, 0, 0)], ball=ball)
    tilt = 0.35
    point = np.array([robot_frame(ball[:2] + (HBALL.radius,), obs)])
    for sway_pan, sway_tilt in ((0.0, 0.0), (0.04, 0.0), (0.0, -0.03)):
        heads = HeadState(np.zeros(1), np.full(1, tilt), np.full(1, sway_pan),
                          np.full(1, sway_tilt), np.zeros(1, bool))
        (u, v), = r.camera.project(point, sway_pan, tilt + sway_tilt)[0]
        _, (cu, cv), _ = blob_near(orange_alpha(r.render(state, heads, 0)), u, v)
        assert cu == pytest.approx(u, abs=1.0) and cv == pytest.approx(v, abs=1.0)
    # 0.04 rad of pan sway moves the scene about f tan(0.04) = 13 px to the right.
    assert r.camera.project(point, 0.04, tilt)[0][0, 0] - r.camera.project(
        point, 0.0, tilt)[0][0, 0] > 10.0


def test_head_near_robot_hides_the_ball():
    r = HeadFrameRenderer(head_camera("kidsize"), HFIELD, HUMANOID, HBALL, [0, 1], "clean",
                          (320, 240))
    obs = (0.0, 1.0, 0.0, 0, 0, 0)
    heads = HeadState.steady(2, 0.0, 0.3)
    ball = (2.0, 1.0, 0, 0, 0, 0)
    seen = r.render(world([obs, (-2.0, -2.0, 0, 0, 0, 0)], ball, [0, 1]), heads, 0)
    hidden = r.render(world([obs, (1.0, 1.0, 0, 0, 0, 0)], ball, [0, 1]), heads, 0)
    def orange_pixels(img):
        return np.all(np.abs(img.astype(int) - COLOURS["orange"]) < 40, axis=2).sum()

    assert orange_pixels(seen) > 100
    assert orange_pixels(hidden) == 0
    # The robot in between shows its team colour (yellow) on top.
    assert np.any(np.all(hidden == COLOURS["yellow"], axis=2))


def test_head_realistic_spec_and_sizes():
    r = head_renderer(spec="realistic", size=None)
    assert (r.width, r.height) == (720, 625)
    assert r.camera.hfov == pytest.approx(head_camera("kidsize").hfov)
    state = world([(0, 0, 0, 0, 0, 0)], ball=(1, 0, 0, 0, 0, 0))
    heads = HeadState.steady(1, 0.0, 0.3)
    a = r.render(state, heads, 0, np.random.default_rng(1))
    assert a.shape == (625, 720, 3)
    assert np.array_equal(a, r.render(state, heads, 0, np.random.default_rng(1)))
    with pytest.raises(ValueError, match="observer"):
        r.render(state, heads, 1, np.random.default_rng(1))


# ------------------------------------------------------------------------------ helpers


def test_back_project_of_the_ball_hue():
    r = zoom_renderer(teams=(0,))
    img = r.render(world([(CX - 0.15, 0.1, 0.0, 0, 0, 0)], ball=(CX + 0.1, 0.0, 0, 0, 0, 0)))
    u, v = (int(c) for c in r.to_pixel(CX + 0.1, 0.0))
    hist = hue_histogram(img[v - 10:v + 10, u - 10:u + 10], bins=16)
    assert hist.shape == (16,) and hist.max() == pytest.approx(1.0)
    bp = back_project(img, hist)
    assert bp.dtype == np.float32 and bp.shape == img.shape[:2]
    assert bp[v, u] > 0.9
    assert bp[50:100, 500:600].max() < 0.05  # carpet
    bu, bv = (int(c) for c in r.to_pixel(CX - 0.15, 0.1))
    assert bp[bv, bu] < 0.05  # the robot's blue patch


def test_colour_table_classifies_the_nominal_colours():
    table = ColourTable(OVERHEAD_CLASSES, aliases=CLASS_ALIASES)
    assert table.table.shape == (6, 32, 32, 32)
    for name in list(OVERHEAD_CLASSES):
        for gain in (0.8, 1.0, 1.2):
            rgb = [min(255, round(gain * c)) for c in COLOURS[name]]
            p = table.lookup(rgb)
            assert max(p, key=p.get) == name and p[name] > 0.5, (name, gain, p)
    for name in ("white", "body"):
        assert max(table.lookup(COLOURS[name]).values()) < 0.5
    # On a rendered frame.
    r = zoom_renderer()
    img = r.render(world([(CX - 0.15, 0.1, 0.0, 0, 0, 0)], ball=(CX + 0.1, 0.0, 0, 0, 0, 0)))
    prob = table.probability(img, "ball")
    assert prob.dtype == np.float32 and prob.shape == img.shape[:2]
    u, v = (int(c) for c in r.to_pixel(CX + 0.1, 0.0))
    assert prob[v, u] > 0.8 and prob[50:100, 500:600].max() < 0.05
    assert table.probability(img, "carpet")[50:100, 500:600].min() > 0.8
    labels = table.classify(img)
    assert labels[v, u] == list(OVERHEAD_CLASSES).index("orange")
    bu, bv = (int(c) for c in r.to_pixel(CX - 0.15, 0.1))
    assert labels[bv, bu] == list(OVERHEAD_CLASSES).index("blue")
    assert isinstance(r.colour_table(), ColourTable)
    with pytest.raises(ValueError, match="unknown colour class"):
        table.probability(img, "purple")


def test_frame_difference():
    r = zoom_renderer()
    a = r.render(world([FAR], ball=(CX, 0.0, 0, 0, 0, 0)))
    b = r.render(world([FAR], ball=(CX + 0.05, 0.0, 0, 0, 0, 0)))
    assert not frame_difference(a, a).any()
    d = frame_difference(a, b)
    assert d.dtype == np.float32 and 0.0 <= d.min() and d.max() <= 1.0
    for x in (CX, CX + 0.05):
        u, v = (int(c) for c in r.to_pixel(x, 0.0))
        assert d[v, u] > 0.1
    assert d[:100].max() == 0.0


def test_difference_image_by_regions_is_the_frame_difference():
    r = zoom_renderer()
    a = r.render(world([FAR], ball=(CX, 0.0, 0, 0, 0, 0)))
    b = r.render(world([FAR], ball=(CX + 0.05, 0.0, 0, 0, 0, 0)))
    whole = frame_difference(a, b)
    lazy = difference_image(grey(a), grey(b))
    for box in ((0, 0, 50, 40), (100, 80, 300, 200), (-5, -5, 10_000, 10_000)):
        lazy.ensure(*box)
        x0, y0 = max(0, box[0]), max(0, box[1])
        np.testing.assert_array_equal(lazy.array[y0:box[3], x0:box[2]],
                                      whole[y0:box[3], x0:box[2]])
    with pytest.raises(ValueError, match="grey"):
        difference_image(a, b)


@pytest.mark.parametrize("lighting", [False, True])
def test_photometry_saturates_as_opencv_does(lighting):
    """Lighting and noise added in 16 bits and saturated to 0..255 once, exactly what
    OpenCV's saturating add into 8 bits gives (dark and bright pixels included)."""
    import cv2

    from soccer_env.sensors.images.common import Photometry

    photo = Photometry(64, 48, 0.2 if lighting else 0.0, 0.3 if lighting else 0.0, 6.0)
    img = np.random.default_rng(0).integers(0, 256, (48, 64, 3), dtype=np.uint8)
    img[:8], img[-8:] = 0, 255
    for seed in range(5):
        got = photo.apply(img, np.random.default_rng(seed))
        rng = np.random.default_rng(seed)  # the same draws, the former OpenCV formula
        z = float(rng.standard_normal())
        a_u, phi_u = rng.random(2).tolist()
        oy, ox = rng.integers(0, (49, 65)).tolist()
        out = img
        if lighting:
            gain = min(2.0, max(0.3, 1.0 + 0.2 * z))
            gx = gain * 0.3 * a_u * math.cos(2 * math.pi * phi_u)
            gy = gain * 0.3 * a_u * math.sin(2 * math.pi * phi_u)
            ramp = (gain + gx * photo._xn)[None, :] + (gy * photo._yn)[:, None]
            out = cv2.multiply(img, cv2.merge([ramp, ramp, ramp]), dtype=cv2.CV_16S)
        expected = cv2.add(out, photo._bank[oy:oy + 48, ox:ox + 64], dtype=cv2.CV_8U)
        assert got.dtype == np.uint8
        np.testing.assert_array_equal(got, expected)


# ------------------------------------------------------------------------------ validation


@pytest.mark.parametrize("field, value", [
    ("width", 0), ("height", 10.5), ("frame_rate", 0.0), ("exposure", -0.001),
    ("blur_samples", 1), ("gain_sigma", -0.1), ("gradient", 1.0), ("noise_sigma", math.nan),
    ("camera_height", 0.1), ("region", (1.0, 0.0, 0.0, 1.0)), ("carpet", (300, 0, 0)),
    ("line", (1, 2)), ("antialias", 1),
])
def test_bad_overhead_spec_values(field, value):
    with pytest.raises(ValueError, match=field):
        overhead_frame("clean", **{field: value})


@pytest.mark.parametrize("field, value", [
    ("noise_sigma", -1.0), ("gradient", 2.0), ("sky", (0, 0)), ("body", (0, 0, 256)),
])
def test_bad_head_spec_values(field, value):
    with pytest.raises(ValueError, match=field):
        head_frame("clean", **{field: value})


def test_bad_renderer_arguments():
    with pytest.raises(ValueError, match="unknown overhead_frame preset"):
        overhead_frame("nope")
    with pytest.raises(TypeError, match="unknown overhead_frame parameter"):
        overhead_frame("clean", colour=1)
    with pytest.raises(ValueError, match="teams"):
        OverheadRenderer("clean", FIELD, SSL, BALL, [0, 2])
    with pytest.raises(ValueError, match="robot_specs"):
        OverheadRenderer("clean", FIELD, [SSL], BALL, [0, 1])
    with pytest.raises(ValueError, match="size"):
        head_renderer(size=(4, 4))
    r = OverheadRenderer("clean", FIELD, SSL, BALL, [0, 1])
    with pytest.raises(ValueError, match="robots"):
        r.render(world([FAR]))
    assert set(presets.OVERHEAD_FRAMES) >= {"clean", "realistic"}
    assert presets.OVERHEAD_FRAMES["mirosot"].frame_rate == 30.0
