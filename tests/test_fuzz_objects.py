"""Fuzzing the estimators' constructors and methods, the ball model, the image trackers, the
particle filters and the environments' reset options (hypothesis, derandomized in CI by
``tests/conftest.py``): every call either returns finite numbers or raises ``ValueError`` /
``TypeError`` naming the argument, and an object that refused a call goes on working (its
next valid call returns finite numbers). An object built from an accepted value must do its
work: building it is not enough."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np
import pytest
from fuzzing import ANYTHING, FAST, NUMBERS, accepted, finite, named
from hypothesis import given
from hypothesis import strategies as st

import soccer_env
from estimators import (
    BallFilterConfig,
    BallTracker,
    FrictionBallModel,
    HeadCamera,
    KalmanFilter,
    KalmanMeanShift,
    KLDConfig,
    KLDLocalizer,
    LeastSquaresBall,
    MeanShiftParticleFilter,
    ParticleBallTracker,
    ParticleFilterTracker,
    PlainMeanShift,
    RobotTracker,
)
from estimators.particle.core import PARTICLE_FILTERS, ungm_model
from soccer_env.envs.goalkeeper import GoalkeeperEnv
from soccer_env.envs.shootout import ShootoutEnv
from soccer_env.validation import keyword_names

#: A weight image with the target (a 10 x 10 block of ones) at (35, 25) [px].
IMAGE = np.zeros((60, 80))
IMAGE[20:30, 30:40] = 1.0
BOUNDS = (-4.5, 4.5, -3.0, 3.0)


def _rng() -> np.random.Generator:
    return np.random.default_rng(0)


def _track_ball(tracker: Any, particles: bool = False) -> Any:
    for k in range(4):
        if particles:  # one position and its standard deviation [m]
            tracker.update(0.02 * k, np.array([0.1 * k, 0.5]), 0.01)
        else:
            tracker.update(0.02 * k, np.array([[0.1 * k, 0.5]]))
    return tracker.estimate(0.1)


def _track_robot(tracker: RobotTracker) -> Any:
    """Two poses ``(k, 3)`` of robot 0 (``index`` ``(k,)``, see ``RobotTracker.update``); a
    tracker of no robots (``n=0`` is allowed) only answers its estimate."""
    if tracker.n == 0:
        return tracker.estimate(0.05)
    tracker.update(0.0, [[0.0, 0.0, 0.1]], [0])
    tracker.update(0.02, [[0.01, 0.0, 0.1]], [0])
    return tracker.estimate(0.05)


def _localize(loc: KLDLocalizer) -> Any:
    loc.predict((0.05, 0.0, 0.01))
    loc.update(np.array([[0.0, 0.0], [1.0, 1.0]]), np.array([1.2, 0.8]))
    return loc.estimate()


def _look(cam: HeadCamera) -> Any:
    pixels, visible = cam.project(np.array([[2.0, 0.3]]), 0.1, 0.5)
    return pixels, cam.ground_point(np.array([[cam.width / 2, cam.height_px * 0.7]]), 0.1, 0.5)


#: Name -> (the constructor of ``**kwargs``, the arguments fuzzed (None: all its keywords),
#: what the built object must then do, returning numbers that must be finite).
CONSTRUCTORS: dict[str, tuple[Callable[..., Any], tuple[str, ...] | None,
                              Callable[[Any], Any]]] = {
    "BallFilterConfig": (lambda **kw: BallTracker(BallFilterConfig(**kw)),
                         tuple(BallFilterConfig.__dataclass_fields__), _track_ball),
    "LeastSquaresBall": (LeastSquaresBall, None, _track_ball),
    "ParticleBallTracker": (lambda **kw: ParticleBallTracker(_rng(), **kw), None,
                            lambda t: _track_ball(t, particles=True)),
    "RobotTracker": (lambda **kw: RobotTracker(**{"n": 2, **kw}), None, _track_robot),
    "KLDConfig": (lambda **kw: KLDLocalizer(BOUNDS, _rng(), KLDConfig(**kw)),
                  tuple(KLDConfig.__dataclass_fields__), _localize),
    "KLDLocalizer": (lambda **kw: KLDLocalizer(**{"bounds": BOUNDS, "rng": _rng(),
                                                  "config": KLDConfig(max_particles=500),
                                                  **kw}),
                     ("bounds", "pose", "pose_sigma", "recovery", "seed_fraction",
                      "seed_memory"), _localize),
    "HeadCamera": (HeadCamera, None, _look),
    "FrictionBallModel": (lambda **kw: FrictionBallModel(**{"deceleration": 0.4, **kw}),
                          ("deceleration",),
                          lambda m: m.predict(np.array([0.0, 0.0, 2.0, 1.0]), 0.5)),
    "PlainMeanShift": (lambda **kw: PlainMeanShift(**{"position": (35, 25),
                                                      "window_size": (10, 10), **kw}),
                       None, lambda t: t.update(IMAGE)),
    "KalmanMeanShift": (lambda **kw: KalmanMeanShift(**{
        "position": (35, 25), "window_size": (10, 10), "image_size": (80, 60),
        "fov": (1.0, 0.8), **kw}), None, lambda t: t.update(IMAGE, 0.01, 0.0)),
    # ``area`` given: with ``area=None`` the tracker measures it on its first frame and
    # refuses a start (``position``) off the target, as documented.
    "MeanShiftParticleFilter": (lambda **kw: MeanShiftParticleFilter(**{
        "position": (35, 25), "window_size": (10, 10), "rng": _rng(), "area": 100.0, **kw}),
        None, lambda t: t.update(IMAGE)),
    "ParticleFilterTracker": (lambda **kw: ParticleFilterTracker(**{
        "position": (35, 25), "window_size": (10, 10), "rng": _rng(), **kw}),
        None, lambda t: t.update(IMAGE)),
}

#: Frames of the test image (80 x 60) that a tracker built as asked refuses by design, naming
#: the image: kind -> (the keyword fuzzed, None: any; what the refusal says). The trackers
#: that learn the image's size from their frames take any window (scaled by
#: ``window_scale``), which the test image may be too small for; KalmanMeanShift takes frames
#: of its ``image_size`` only.
FRAME_REFUSALS: dict[str, tuple[str | None, str]] = {
    "PlainMeanShift": (None, "to hold the window"),
    "MeanShiftParticleFilter": (None, "to hold the window"),
    "ParticleFilterTracker": (None, "to hold the window"),
    "KalmanMeanShift": ("image_size", "weight_image must have shape"),
}

#: Keywords not fuzzed: generators and callables (their types are checked where used).
NOT_FUZZED = {"self", "rng", "feature_check", "config", "measurement", "filter"}


def _keywords(kind: str) -> list[str]:
    make, names, _ = CONSTRUCTORS[kind]
    if names is None:
        target = {"ParticleBallTracker": ParticleBallTracker, "RobotTracker": RobotTracker,
                  "LeastSquaresBall": LeastSquaresBall, "HeadCamera": HeadCamera,
                  "PlainMeanShift": PlainMeanShift, "KalmanMeanShift": KalmanMeanShift,
                  "MeanShiftParticleFilter": MeanShiftParticleFilter,
                  "ParticleFilterTracker": ParticleFilterTracker}[kind]
        names = tuple(keyword_names(target.__init__))
    return [n for n in names if n not in NOT_FUZZED]


@pytest.mark.parametrize("kind", list(CONSTRUCTORS))
@FAST
@given(data=st.data())
def test_estimator_constructors(kind, data):
    """One keyword set to anything: refused naming it, or the object does its work with
    finite results."""
    make, _, use = CONSTRUCTORS[kind]
    name = data.draw(st.sampled_from(_keywords(kind)), label="argument")
    value = data.draw(ANYTHING, label="value")
    try:
        obj = make(**{name: value})
    except (ValueError, TypeError) as err:
        assert named(err, name), f"{kind}({name}={value!r}): {err}"
        return
    try:
        out = use(obj)
    except ValueError as err:
        keyword, says = FRAME_REFUSALS.get(kind, ("", "\0"))
        if keyword not in (None, name) or says not in str(err):
            raise
        assert named(err, "weight_image", "colour_image"), f"{kind}({name}={value!r}): {err}"
        return
    assert accepted(finite(out)), f"{kind}({name}={value!r}) works to non-finite numbers"


#: Images a caller might pass: any size, values drawn from anything numeric, or the good
#: image with one patch overwritten.
IMAGES = st.one_of(
    st.tuples(st.integers(1, 90), st.integers(1, 90), NUMBERS).map(
        lambda a: np.full((a[0], a[1]), a[2], dtype=np.float64)),
    st.tuples(st.integers(0, 59), st.integers(0, 79), NUMBERS).map(
        lambda a: np.where((np.arange(60)[:, None] // 6 == a[0] // 6)
                           & (np.arange(80)[None, :] // 8 == a[1] // 8), a[2], IMAGE)),
    ANYTHING)

TRACKERS = ("PlainMeanShift", "KalmanMeanShift", "MeanShiftParticleFilter",
            "ParticleFilterTracker")


@pytest.mark.parametrize("kind", TRACKERS)
@FAST
@given(image=IMAGES)
def test_image_trackers_on_any_image(kind, image):
    """A frame of anything: finite estimates, or a refusal naming the image; the tracker's
    next frame on a good image is finite either way."""
    make, _, use = CONSTRUCTORS[kind]
    tracker = make(area=100.0) if kind == "MeanShiftParticleFilter" else make()
    use(tracker)
    try:
        out = tracker.update(image)
    except (ValueError, TypeError) as err:
        assert named(err, "weight_image", "colour_image"), f"{kind}: {err}"
    else:
        assert accepted(finite(out)), f"{kind}: non-finite estimate {out}"
    assert finite(use(tracker)), f"{kind} broken after {image!r}"


@FAST
@given(state=st.one_of(ANYTHING, st.lists(NUMBERS, min_size=4, max_size=4)),
       dt=st.one_of(NUMBERS, ANYTHING))
def test_friction_ball_model_predict(state, dt):
    model = FrictionBallModel(0.4)
    try:
        out = model.predict(state, dt)
    except (ValueError, TypeError) as err:
        assert named(err, "state", "dt"), f"predict({state!r}, {dt!r}): {err}"
        return
    assert accepted(finite(out)), f"predict({state!r}, {dt!r}) = {out}"


@pytest.mark.parametrize("name", ["bootstrap", "fbpf", "mfbpf"])
@FAST
@given(y=st.one_of(NUMBERS, ANYTHING))
def test_particle_filter_steps(name, y):
    transition, likelihood = ungm_model()
    rng = np.random.default_rng(1)
    pf = PARTICLE_FILTERS.get(name)(rng.normal(size=(32, 1)), transition, likelihood, rng)
    try:
        out = pf.step(y)
    except (ValueError, TypeError) as err:
        assert named(err, "y must", "y of shape"), f"step({y!r}): {err}"
    else:
        assert accepted(finite(out)), f"step({y!r}) = {out}"
    assert finite(pf.step(0.5)) and finite(pf.particles)


@FAST
@given(z=st.one_of(ANYTHING, st.lists(NUMBERS, min_size=2, max_size=2)),
       R=st.one_of(ANYTHING, st.lists(st.lists(NUMBERS, min_size=2, max_size=2),
                                      min_size=2, max_size=2)))
def test_kalman_filter_updates(z, R):
    kf = KalmanFilter(np.zeros(2), np.eye(2))
    try:
        kf.update(z, np.eye(2), R)
    except (ValueError, TypeError) as err:
        assert named(err, "z ", "z must", "R ", "R must", "R:", "z, H and R"), f"{z!r}: {err}"
    else:
        assert accepted(finite(kf.x) and finite(kf.P))
    kf.update(np.ones(2), np.eye(2), np.eye(2))
    assert finite(kf.x) and finite(kf.P)


ENVS: dict[str, Callable[[], Any]] = {
    "goalkeeper": GoalkeeperEnv, "shootout": ShootoutEnv,
    "match": lambda: soccer_env.parallel_env(blue=1, yellow=1),
}


@pytest.fixture(scope="module", params=list(ENVS))
def any_env(request):
    return request.param, ENVS[request.param]()


@FAST
@given(options=st.one_of(ANYTHING, st.dictionaries(st.text(max_size=8), ANYTHING,
                                                   max_size=2)))
def test_reset_options(any_env, options):
    """Options a task does not take are refused naming ``options``; the environment then
    resets and steps as before. (The match ignores unknown keys, as PettingZoo's API test
    passes some; it refuses options that are no dict.)"""
    kind, env = any_env
    try:
        out = env.reset(seed=0, options=options)
    except (ValueError, TypeError) as err:
        assert named(err, "options"), f"{kind} reset(options={options!r}): {err}"
        out = env.reset(seed=0)
    else:
        accepted(True)
    assert finite(out[0])
    if kind == "match":
        obs, rewards, *_ = env.step({a: np.zeros(6, np.float32) for a in env.agents})
        assert finite(obs) and finite(rewards)
    else:
        obs, reward, *_ = env.step(np.zeros(6, np.float32))
        assert finite(obs) and finite(reward)
