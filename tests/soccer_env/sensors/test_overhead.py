"""The overhead vision sensor: timing, noise, losses, occlusion, chip projection, overlap."""

import math

import numpy as np
import pytest
from worlds import make_world, park

from soccer_env.presets.sensors import vision
from soccer_env.sensors.overhead import Camera, OverheadVision, default_cameras
from soccer_env.sim.world import idle_commands
from soccer_env.state import WorldState


def static_states(world, steps):
    states = [world.snapshot()]
    for _ in range(steps):
        world.step(idle_commands(world.n_robots))
        states.append(world.snapshot())
    return states


def sensor(world, spec, cameras=None, seed=0, state=None):
    v = OverheadVision(spec, world.field, world.robot_spec, world.ball_spec, world.n_robots,
                       cameras)
    warm = v.reset(state or world.snapshot(), np.random.default_rng(seed))
    return v, warm


def run_frames(v, states):
    out = []
    for s in states:
        out.extend(v.step(s))
    return out


def test_frame_rate_timestamps_and_latency():
    w = park(make_world(field="ssl-2012", control_dt=0.04, physics_dt=0.01))
    spec = vision("ssl-2012")
    v, warm = sensor(w, spec)
    assert len(warm) == 1 and warm[0].t_capture == pytest.approx(-spec.latency)
    states = static_states(w, 100)  # 4 s
    frames = run_frames(v, states[1:])
    caps = np.array([f.t_capture for f in frames])
    assert len(frames) == pytest.approx(4.0 * 25 - 2, abs=2)  # minus the 80 ms in flight
    np.testing.assert_allclose(np.diff(caps), 1 / 25, atol=1e-9)
    for f in frames:
        assert f.t_delivered == pytest.approx(f.t_capture + spec.latency)


def test_ideal_vision_reports_the_truth_at_once():
    w = park(make_world(n_blue=2, n_yellow=1))
    w.set_ball(0.5, -0.5, 1.0, 0.0)
    v, _ = sensor(w, vision("ideal"))
    w.step(idle_commands(3))
    frames = v.step(w.snapshot())
    truth = w.snapshot()
    assert frames and all(f.t_capture == f.t_delivered == truth.time for f in frames)
    seen = {i for f in frames for i in f.robot_ids}
    assert seen == {0, 1, 2}
    for f in frames:
        for i, pose in zip(f.robot_ids, f.robots):
            np.testing.assert_allclose(pose, truth.robots[i, 0:3], atol=1e-12)
        for b in f.balls:
            np.testing.assert_allclose(b, truth.ball[0:2], atol=1e-12)


def test_noise_matches_the_shared_measurement_model():
    w = park(make_world(field="ssl-2012"))
    w.set_ball(1.0, 0.5)
    spec = vision("ssl-2012")
    v, _ = sensor(w, spec)
    state = w.snapshot()
    later = [WorldState(state.time + k * 0.04, state.ball, state.robots, state.names,
                        state.teams) for k in range(1, 2001)]
    balls = np.concatenate([np.reshape(f.balls, (-1, 2)) for f in run_frames(v, later)])
    err = balls - state.ball[0:2]
    assert np.std(err, axis=0) == pytest.approx([spec.ball_sigma] * 2, rel=0.1)
    assert np.abs(np.mean(err, axis=0)).max() < 0.003
    assert v.ball_model.sigma == spec.ball_sigma  # the filters' model, not a copy of numbers


def test_missed_detections_at_the_configured_rate():
    w = park(make_world(n_blue=3))
    w.set_ball(-2.0, 1.0)
    spec = vision("realistic", ball_detection=0.7, robot_detection=0.9, dribbler_false_rate=0.0)
    v, _ = sensor(w, spec, cameras=[Camera(0, 0, 4, -10, 10, -10, 10)])
    frames = run_frames(v, static_states(w, 600)[1:])
    assert np.mean([len(f.balls) for f in frames]) == pytest.approx(0.7, abs=0.05)
    assert np.mean([len(f.robot_ids) for f in frames]) / 3 == pytest.approx(0.9, abs=0.03)


def test_ball_hidden_behind_a_robot_but_not_in_front():
    """One camera above the centre; a robot at x = 2 m. Seen from the camera, a ball just
    beyond the robot is hidden, a ball on the camera's side of it is not."""
    w = park(make_world(), poses=[(2.0, 0.0, 0.0)])
    cam = [Camera(0.0, 0.0, 4.0, -10, 10, -10, 10)]
    spec = vision("realistic", ball_detection=1.0, robot_detection=1.0, ball_sigma=0.0,
                  dribbler_false_rate=0.0)
    gap = w.robot_spec.radius + w.ball_spec.radius + 0.002
    for x, visible in ((2.0 + gap, False), (2.0 - gap, True), (0.5, True)):
        w.set_ball(x, 0.0)
        v, warm = sensor(w, spec, cameras=cam)
        assert (len(warm[0].balls) == 1) == visible, x


def test_each_robot_hides_the_ball_with_its_own_footprint_and_height():
    """A humanoid (0.1 m radius, 0.6 m tall) casts a longer shadow from an overhead camera
    than an SSL robot (0.09 m, 0.15 m): camera 4 m above the origin, robot at x = 2 m, ball
    0.3 m beyond it. Behind the humanoid the ball is hidden; behind an SSL robot, and with the
    humanoid described as an SSL robot (the old behaviour), it is seen."""
    from soccer_env import presets

    humanoid, ssl = presets.robot("humanoid-2012"), presets.robot("ssl")
    w = park(make_world(), poses=[(2.0, 0.0, 0.0)])
    cam = [Camera(0.0, 0.0, 4.0, -10, 10, -10, 10)]
    spec = vision("realistic", ball_detection=1.0, robot_detection=1.0, ball_sigma=0.0,
                  dribbler_false_rate=0.0)
    r = w.ball_spec.radius
    # The humanoid's shadow in the ball's plane reaches 2 (4 - r) / (4 - 0.6) = 2.33 m.
    k = (4.0 - r) / (4.0 - humanoid.height)
    assert 2.0 * k + humanoid.radius * k > 2.3 + r
    w.set_ball(2.3, 0.0)
    seen = {}
    for name, body in (("humanoid", humanoid), ("ssl", ssl)):
        v = OverheadVision(spec, w.field, ssl, w.ball_spec, w.n_robots, cam, robots=[body])
        seen[name] = len(v.reset(w.snapshot(), np.random.default_rng(0))[0].balls) == 1
    assert seen == {"humanoid": False, "ssl": True}
    with pytest.raises(ValueError, match="robots must hold one spec per robot"):
        OverheadVision(spec, w.field, ssl, w.ball_spec, w.n_robots, cam, robots=[ssl, ssl])


def test_mixed_teams_hide_the_ball_behind_either_kind_of_robot():
    """Two groups of bodies in one world: a ball behind the humanoid is hidden and one behind
    the SSL robot (beyond its shorter shadow) is seen, in the same frames."""
    from soccer_env import presets

    humanoid, ssl = presets.robot("humanoid-2012"), presets.robot("ssl")
    w = park(make_world(n_blue=2), poses=[(2.0, 0.0, 0.0), (-2.0, 0.0, 0.0)])
    cam = [Camera(0.0, 0.0, 4.0, -10, 10, -10, 10)]
    spec = vision("realistic", ball_detection=1.0, robot_detection=1.0, ball_sigma=0.0,
                  dribbler_false_rate=0.0)
    for x, visible in ((2.3, False), (-2.3, True)):
        w.set_ball(x, 0.0)
        v = OverheadVision(spec, w.field, ssl, w.ball_spec, w.n_robots, cam,
                           robots=[humanoid, ssl])
        assert (len(v.reset(w.snapshot(), np.random.default_rng(0))[0].balls) == 1) == visible


def test_humanoids_have_no_dribbler_reflections():
    from soccer_env import presets

    humanoid, ssl = presets.robot("humanoid-2012"), presets.robot("ssl")
    w = park(make_world(n_blue=2), poses=[(-1.0, 0.0, 0.0), (1.0, 1.0, math.pi / 2)])
    w.set_ball(-3.0, -2.0)
    spec = vision("realistic", dribbler_false_rate=60.0, random_false_rate=0.0,
                  ball_detection=0.0)
    v = OverheadVision(spec, w.field, ssl, w.ball_spec, w.n_robots,
                       [Camera(0, 0, 4, -10, 10, -10, 10)], robots=[ssl, humanoid])
    v.reset(w.snapshot(), np.random.default_rng(0))
    balls = np.concatenate([np.reshape(fr.balls, (-1, 2))
                            for fr in run_frames(v, static_states(w, 60)[1:])])
    front = np.array([-1.0 + ssl.front_distance + w.ball_spec.radius, 0.0])
    assert len(balls) > 20
    assert np.hypot(*(balls - front).T).max() < 0.02  # all at the SSL robot's dribbler


def test_chipped_ball_seen_along_the_camera_ray():
    w = park(make_world())
    cam = [Camera(0.0, 0.0, 4.0, -10, 10, -10, 10)]
    spec = vision("ideal")
    r = w.ball_spec.radius
    w.set_ball(1.0, 0.0, 0.0, 0.0, z=1.0, vz=0.0)
    v, warm = sensor(w, spec, cameras=cam)
    seen = warm[0].balls[0]
    k = (4.0 - r) / (4.0 - (1.0 + r))
    np.testing.assert_allclose(seen, [1.0 * k, 0.0], atol=1e-12)
    assert seen[0] > 1.3  # a metre up, it appears a third of a metre further out


def test_overlapping_cameras_both_report_the_ball():
    w = park(make_world())  # Division B: four cameras
    f = w.field
    cams = default_cameras(f, 4.0, 1.0)
    assert len(cams) == 4
    w.set_ball(0.3, -0.2)  # near the centre: inside all four (overlapping) views
    _, warm = sensor(w, vision("ideal", camera_overlap=1.0))
    assert sum(len(fr.balls) for fr in warm) == 4
    w.set_ball(-3.5, -2.0)  # deep in one quadrant
    _, warm = sensor(w, vision("ideal", camera_overlap=1.0))
    assert sum(len(fr.balls) for fr in warm) == 1
    assert len(default_cameras(make_world(field="ssl-2012").field, 4.0, 0.3)) == 1


def test_spurious_balls_at_dribblers_and_anywhere():
    w = park(make_world(n_blue=2), poses=[(-1.0, 0.0, 0.0), (1.0, 1.0, math.pi / 2)])
    w.set_ball(-3.0, -2.0)
    spec = vision("realistic", dribbler_false_rate=60.0, random_false_rate=0.0,
                  ball_detection=0.0)
    v, _ = sensor(w, spec, cameras=[Camera(0, 0, 4, -10, 10, -10, 10)])
    balls = np.concatenate([np.reshape(fr.balls, (-1, 2))
                            for fr in run_frames(v, static_states(w, 60)[1:])])
    d = w.robot_spec.front_distance + w.ball_spec.radius
    fronts = np.array([[-1.0 + d, 0.0], [1.0, 1.0 + d]])
    near = np.min(np.hypot(*(balls[:, None, :] - fronts[None]).transpose(2, 0, 1)), axis=1)
    assert len(balls) > 40 and near.max() < 0.02
    spec = vision("realistic", dribbler_false_rate=0.0, random_false_rate=60.0,
                  ball_detection=0.0)
    v, _ = sensor(w, spec, cameras=[Camera(0, 0, 4, -2, 2, -1, 1)])
    frames = run_frames(v, static_states(w, 60)[1:])
    balls = np.concatenate([np.reshape(fr.balls, (-1, 2)) for fr in frames])
    # 60 per second at 60 frames per second: one in a frame with probability 1 - 1/e.
    assert len(balls) / len(frames) == pytest.approx(1 - math.exp(-1), abs=0.15)
    assert (np.abs(balls[:, 0]) <= 2).all() and (np.abs(balls[:, 1]) <= 1).all()


def test_latency_jitter_delivers_in_delivery_order_possibly_out_of_capture_order():
    w = park(make_world())
    spec = vision("harsh", latency_jitter=0.05)
    v, _ = sensor(w, spec)
    frames = run_frames(v, static_states(w, 300)[1:])
    delivered = [f.t_delivered for f in frames]
    captured = [f.t_capture for f in frames]
    assert delivered == sorted(delivered)
    assert captured != sorted(captured)  # some frames overtake others
    for f in frames:
        assert spec.latency <= f.t_delivered - f.t_capture <= spec.latency + 0.05 + 1e-12


def test_same_seed_same_frames():
    w = park(make_world(n_blue=2))
    w.set_ball(0.0, 0.0, 2.0, 1.0)
    states = static_states(w, 60)
    a, _ = sensor(w, vision("harsh"), seed=3, state=states[0])
    b, _ = sensor(w, vision("harsh"), seed=3, state=states[0])
    fa, fb = run_frames(a, states[1:]), run_frames(b, states[1:])
    assert len(fa) == len(fb)
    for x, y in zip(fa, fb):
        assert x.t_capture == y.t_capture
        assert x.balls == y.balls and x.robots == y.robots


def test_vision_preset_validation():
    with pytest.raises(ValueError, match=r"vision.latency must be in \[0.0, 2.0\], got -1"):
        vision("realistic", latency=-1.0)
    with pytest.raises(ValueError, match=r"vision.ball_detection must be in \[0.0, 1.0\]"):
        vision("realistic", ball_detection=1.5)
    with pytest.raises(TypeError, match=r"unknown vision parameter\(s\) \['fps'\]"):
        vision("realistic", fps=60)


def _truths(rng, n_robots, steps, dt, field):
    """A wandering scene: robots walking about, a ball rolling near them (so that they hide
    it now and then) and chipped now and then; ``(time, ball (6,), robots (N, 6))`` per
    step."""
    from soccer_env.presets import field as field_spec

    f = field_spec(field)
    robots = np.zeros((n_robots, 6))
    robots[:, 0] = rng.uniform(-f.half_length, f.half_length, n_robots)
    robots[:, 1] = rng.uniform(-f.half_width, f.half_width, n_robots)
    robots[:, 2] = rng.uniform(-math.pi, math.pi, n_robots)
    ball = np.zeros(6)
    ball[0:2] = robots[0, 0:2] + 0.12
    out = []
    for s in range(steps):
        robots[:, 0:2] += rng.normal(0, 0.03, (n_robots, 2))
        robots[:, 2] = np.remainder(robots[:, 2] + rng.normal(0, 0.4, n_robots) + math.pi,
                                    2 * math.pi) - math.pi
        near = robots[rng.integers(n_robots), 0:2]
        ball[0:2] = near + rng.normal(0, 0.15, 2) if rng.random() < 0.3 else ball[0:2] + 0.02
        ball[2] = max(0.0, rng.normal(0.0, 0.1)) if rng.random() < 0.2 else 0.0
        out.append(WorldState(s * dt, ball.copy(), robots.copy(), (), np.zeros(n_robots)))
    return out


@pytest.mark.parametrize("preset,field,n_robots,dt", [
    ("ssl-2012", "ssl-div-b", 3, 1 / 60),   # four cameras at 25 Hz
    ("realistic", "ssl-2012", 2, 1 / 60),   # misses, dribbler reflections, occlusion
    ("noisy", "ssl-div-b", 7, 1 / 30),      # many frames of many robots, spurious balls
    ("ideal", "ssl-2012", 2, 1 / 60),       # every camera every step
    ("blind", "ssl-div-b", 5, 1 / 60),      # occlusion threshold 0: no ball is ever seen
])
def test_batched_vision_equals_single_sensors_bit_for_bit(preset, field, n_robots, dt):
    """OverheadVisionBatch on m fields gives each field's single OverheadVision frames, bit
    for bit, from the same generators: warm-up frames, frames delivered step by step (with
    fields stepped on different steps and restarted), under every kind of event."""
    import dataclasses

    from soccer_env.presets import ball as ball_spec
    from soccer_env.presets import field as field_spec
    from soccer_env.presets import robot as robot_spec
    from soccer_env.sensors.overhead_batch import OverheadVisionBatch

    spec = (dataclasses.replace(vision("harsh"), latency_jitter=0.0, dribbler_false_rate=3.0,
                                random_false_rate=4.0, ball_detection=0.8, frame_rate=75.0)
            if preset == "noisy" else
            dataclasses.replace(vision("realistic"), occlusion_threshold=0.0)
            if preset == "blind" else vision(preset))
    f, rs, bs = field_spec(field), robot_spec("ssl"), ball_spec("ssl")
    m, steps = 4, 150
    rng = np.random.default_rng(11)
    scenes = [_truths(rng, n_robots, steps, dt, field) for _ in range(m)]
    singles = [OverheadVision(spec, f, rs, bs, n_robots) for _ in range(m)]
    batch = OverheadVisionBatch(spec, f, rs, bs, n_robots, m)

    def start(ks, s):
        warm_single = [singles[k].reset(scenes[k][s], np.random.default_rng((k, s)))
                       for k in ks]
        st = [scenes[k][s] for k in ks]
        warm = batch.reset(ks, [x.time for x in st],
                           [np.r_[x.ball[0:2], x.ball[2]] for x in st],
                           [x.robots[:, 0:3] for x in st],
                           [np.random.default_rng((k, s)) for k in ks])
        for k, frames in zip(ks, warm_single):
            assert warm.frames(k) == frames

    start(list(range(m)), 0)
    delivered = 0
    for s in range(1, steps):
        ks = [k for k in range(m) if (s + k) % 7]  # fields skip steps now and then
        if s == 80:
            start([1, 2], s)
            continue
        st = [scenes[k][s] for k in ks]
        got = batch.step(ks, [x.time for x in st], [np.r_[x.ball[0:2], x.ball[2]] for x in st],
                         [x.robots[:, 0:3] for x in st])
        for k in ks:
            frames = singles[k].step(scenes[k][s])
            assert got.frames(k) == frames, (k, s)
            delivered += len(frames)
    assert delivered > 50
