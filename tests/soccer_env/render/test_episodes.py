"""Rendered episodes: the title card at the start, the outcome banner at the end, the follow
view, the belief's spread read from the filters, videos that hold the end, and episodes that
rendering leaves exactly as they are."""

from __future__ import annotations

import gymnasium as gym
import numpy as np
import pytest

pytest.importorskip("pygame")

import soccer_env  # noqa: E402
from soccer_env.envs.goalkeeper import GoalkeeperEnv  # noqa: E402
from soccer_env.envs.shootout import ShootoutEnv  # noqa: E402
from soccer_env.render import OVERLAY_COLOURS, TITLE_SECONDS  # noqa: E402

STILL = np.zeros(6, np.float32)


def _keeper(**kwargs):
    return gym.make("soccer_env/Goalkeeper-v0", render_mode="rgb_array", render_width=640,
                    **kwargs)


def _run_to_end(env, action=STILL):
    """Step until the episode ends; returns the frames before and after the last step and
    the last step's info and flags."""
    while True:
        before = env.render()
        _, _, term, trunc, info = env.step(action)
        if term or trunc:
            return before, env.render(), info, term, trunc


def test_title_card_on_the_first_frame_after_reset_and_not_later():
    env = _keeper(obs_mode="perceived", perception="realistic", shots={"delay": (2.0, 2.0)})
    env.reset(seed=3)
    first = env.render()
    r = env.unwrapped.renderer
    title = r.contents.title
    assert title[0] == "soccer_env/Goalkeeper-v0    seed 3"
    assert "blue: 1 ssl robot" in title[1]
    assert title[2] == "obs perceived: vision realistic, ball filter ekf"
    rows, w = r.contents.field_height, first.shape[1]

    def dark(frame):
        return (frame[5:rows // 8, w // 2 - 60:w // 2 + 60] < 50).all(axis=-1).mean()

    assert dark(first) > 0.4
    for _ in range(round(TITLE_SECONDS * 60) + 1):
        env.step(STILL)
    later = env.render()
    assert r.contents.title == () and dark(later) < 0.05
    # A reset without a seed continues the seeded generator: the card says so.
    env.reset()
    env.render()
    assert r.contents.title[0].endswith("seed 3 + 1 episodes")


def test_title_card_names_the_humanoid_pipeline_and_the_teams():
    env = GoalkeeperEnv(robot="humanoid-2012", obs_mode="perceived", mates=1,
                        render_mode="rgb_array", render_width=640)
    env.reset(seed=0)
    env.render()
    title = env.renderer.contents.title
    assert "blue: 2 humanoid-2012 robots" in title[1]
    assert title[2].startswith("obs perceived: camera ")
    assert "kld-triangulate localization, inverse fusion, mfbpf tracker" in title[2]
    match = soccer_env.parallel_env(blue=2, yellow=1, obs_mode={"blue": "perceived",
                                                                "yellow": "truth"},
                                    render_mode="rgb_array", render_width=640)
    match.reset(seed=5)
    match.render()
    title = match.renderer.contents.title
    assert title[0] == "soccer_env/Match-v0    seed 5"
    assert title[1] == "blue: 2 ssl robots,  yellow: 1 ssl robot"
    assert title[2:] == ("blue obs perceived: vision realistic, ball filter ekf",
                         "yellow obs truth (no sensors)")


def test_outcome_banner_on_the_frame_after_termination():
    """A keeper that stands still concedes or is saved by the post; the frame after the
    terminating step names the outcome, the frame before has no banner."""
    env = _keeper()
    env.reset(seed=0)
    before, after, info, term, _ = _run_to_end(env)
    assert term
    r = env.unwrapped.renderer
    assert r.contents.banner is not None
    head = {"goal": "GOAL"}.get(info["outcome"], "SAVED")
    assert r.contents.banner.text == head
    assert r.contents.banner.tone == ("bad" if info["outcome"] == "goal" else "good")
    rows = r.contents.field_height
    h, w = rows // 2, after.shape[1] // 2
    centre = after[h - 4:h + 4, w - 50:w + 50].reshape(-1, 3).astype(int)
    tone = 0 if info["outcome"] == "goal" else 1  # a red or a green box
    assert (centre[:, tone] > centre[:, 2] + 40).mean() > 0.3
    env.render()  # rendered again before the reset: still the banner
    assert r.contents.banner.text == head
    env.reset(seed=1)
    env.render()
    assert r.contents.banner is None
    assert not np.array_equal(before, after)


def test_shootout_and_match_banners():
    env = ShootoutEnv(render_mode="rgb_array", render_width=640)
    env.reset(seed=0)
    env.render()
    assert env.renderer.contents.banner is None
    kick = np.array([1.0, 0.0, 0.0, 1.0, 0.0, 0.0], np.float32)
    _, _, info, term, _ = _run_to_end(env, kick)
    assert term and env.renderer.contents.banner.text == ShootoutEnv.OUTCOME_TEXT[
        info["outcome"]][0]
    match = soccer_env.parallel_env(blue=1, yellow=1, render_mode="rgb_array",
                                    render_width=640, max_cycles=20)
    match.reset(seed=0)
    for _ in range(20):
        match.step({a: np.zeros(6) for a in match.agents})
    match.render()
    banner = match.renderer.contents.banner
    assert (banner.text, banner.detail) == ("TIME LIMIT", "blue 0 : 0 yellow")


def test_time_limit_banner_after_the_registered_limit():
    """A shot that never comes: gymnasium's TimeLimit truncates the episode at the registered
    max_episode_steps, and the frame after the last step says so."""
    from soccer_env.envs.registration import GYMNASIUM

    limit = GYMNASIUM["soccer_env/Goalkeeper-v0"].max_episode_steps
    env = _keeper(shots={"delay": (9.0, 9.0)})
    env.reset(seed=0)
    for _ in range(limit - 1):
        env.step(STILL)
    env.render()
    assert env.unwrapped.renderer.contents.banner is None
    *_, trunc, _ = env.step(STILL)
    env.render()
    assert trunc and env.unwrapped.renderer.contents.banner.text == "TIME LIMIT"


def _orange(frame: np.ndarray, rows: int) -> tuple[float, float]:
    ys, xs = np.nonzero(np.all(frame[:rows] == OVERLAY_COLOURS["ball"], axis=-1))
    return float(xs.mean()), float(ys.mean())


def test_follow_view_keeps_the_ball_at_the_centre_at_a_constant_size():
    env = _keeper(render_view="follow")
    env.reset(seed=1)
    field = _keeper()
    field.reset(seed=1)
    shapes, offsets = set(), []
    while True:
        frame = env.render()
        field.render()
        c = env.unwrapped.renderer.contents
        shapes.add(frame.shape)
        assert c.view == "follow" and c.scale >= 2 * field.unwrapped.renderer.contents.scale
        x0, x1, y0, y1 = c.window
        bx, by = env.unwrapped.world.snapshot().ball[0:2]
        assert x0 <= bx <= x1 and y0 <= by <= y1  # the ball is always in view
        fx, fy = _orange(frame, c.field_height)
        w, h = frame.shape[1], c.field_height
        if abs(0.5 * (x0 + x1) - bx) < 1e-6 and abs(0.5 * (y0 + y1) - by) < 1e-6:
            offsets.append(max(abs(fx - w / 2), abs(fy - h / 2)))
        _, _, term, trunc, _ = env.step(STILL)
        field.step(STILL)
        if term or trunc:
            break
    assert shapes == {field.render().shape}  # the frame keeps the field view's size
    assert len(offsets) > 10 and max(offsets) <= 8  # centred wherever the walls allow


def test_follow_view_of_a_kick_off_is_centred():
    match = soccer_env.parallel_env(blue=2, yellow=2, render_mode="rgb_array",
                                    render_width=640, render_view="follow")
    match.reset(seed=0)
    frame = match.render()
    c = match.renderer.contents
    fx, fy = _orange(frame, c.field_height)
    assert abs(fx - 320) <= 3 and abs(fy - c.field_height / 2) <= 3


@pytest.mark.parametrize("make", [
    lambda v: gym.make("soccer_env/Goalkeeper-v0", render_view=v),
    lambda v: ShootoutEnv(render_view=v),
    lambda v: soccer_env.parallel_env(blue=1, yellow=1, render_view=v),
])
@pytest.mark.parametrize("value", ["zoom", "", None, 3, ["follow"]])
def test_bad_render_view_is_refused_with_a_clear_error(make, value):
    with pytest.raises(ValueError, match=r"render_view must be one of \['field', 'follow'\]"):
        make(value)


def test_the_belief_is_drawn_with_its_spread_and_particles():
    """A humanoid keeper's frames draw its particle tracker's and its localization's clouds;
    an SSL keeper's, the filters' 2-sigma ellipses; truth, no belief at all."""
    env = GoalkeeperEnv(robot="humanoid-2012", obs_mode="perceived", mates=1,
                        render_mode="rgb_array", render_width=640)
    env.reset(seed=0)
    seen: set[str] = set()
    for _ in range(120):
        env.render()
        seen |= set(env.renderer.contents.overlays)
        spread = env._scene()[1].spread
        assert spread.robot == 0 and spread.pose_particles.shape[1] == 3
        assert np.isnan(spread.robots[1]).all() and np.isfinite(spread.robots[0]).all()
        if env.step(STILL)[2]:
            break
    assert {"ball_particles", "pose_particles", "camera", "belief_ball"} <= seen

    ssl = GoalkeeperEnv(obs_mode="perceived", render_mode="rgb_array", render_width=640)
    ssl.reset(seed=0)
    seen = set()
    while True:
        ssl.render()
        seen |= set(ssl.renderer.contents.overlays)
        spread = ssl._scene()[1].spread
        assert spread.ball.shape == (2, 2) and spread.robots.shape == (1, 2, 2)
        assert spread.ball_particles is None and spread.pose_particles is None
        if ssl.step(STILL)[2]:
            break
    assert {"ellipses", "belief_ball", "belief_velocity"} <= seen
    truth = GoalkeeperEnv(render_mode="rgb_array", render_width=640)
    truth.reset(seed=0)
    truth.render()
    assert truth.renderer.contents.overlays == ("team0", "ball")


def _episode(kwargs: dict, render: bool, steps: int = 70) -> list:
    env = GoalkeeperEnv(**kwargs, render_mode="rgb_array" if render else None,
                        render_width=480)
    out = [env.reset(seed=4)]
    for k in range(steps):
        if render:
            env.render()
            if k % 7 == 0:
                env.renderer.view = "follow" if env.renderer.view == "field" else "field"
        step = env.step(np.sin(np.arange(6) + k).astype(np.float32))
        out.append(step)
        if step[2]:
            out.append(env.reset())
    return out


def _same(a, b) -> bool:
    if isinstance(a, dict):
        return a.keys() == b.keys() and all(_same(a[k], b[k]) for k in a)
    if isinstance(a, (list, tuple)):
        return len(a) == len(b) and all(_same(x, y) for x, y in zip(a, b))
    if isinstance(a, np.ndarray):
        return np.array_equal(a, b, equal_nan=True)
    return a == b or (a != a and b != b)


@pytest.mark.parametrize("kwargs", [
    dict(obs_mode="perceived", belief_features=True),
    dict(obs_mode="raw"),
    dict(robot="humanoid-2012", obs_mode="perceived", mates=1, belief_features=True),
], ids=["ssl-perceived", "ssl-raw", "humanoid-perceived"])
def test_rendering_leaves_the_episode_unchanged(kwargs):
    """The same seeds give the same observations, rewards and infos with every frame drawn
    (the belief's covariances and particles read at each) as without."""
    assert _same(_episode(kwargs, True), _episode(kwargs, False))


def _runs(frames: list) -> list[int]:
    """Lengths of the runs of one frame object repeated."""
    runs, k = [], 0
    while k < len(frames):
        j = k
        while j + 1 < len(frames) and frames[j + 1] is frames[k]:
            j += 1
        runs.append(j - k + 1)
        k = j + 1
    return runs


def test_videos_hold_the_last_frame(tmp_path, monkeypatch):
    """record_video and the demo show each episode's last frame, with its banner, a second
    longer before the next episode's title card."""
    import soccer_env.render.video as video
    import soccer_lab.demo as demo
    from agents.runs.evaluation import record_video

    written = {}

    def capture(frames, path, fps):
        written["frames"], written["fps"] = list(frames), fps
        return path

    monkeypatch.setattr(video, "write_video", capture)
    record_video("scripted", tmp_path / "v.mp4", seeds=(0, 1), width=320)
    fps = written["fps"]
    runs = _runs(written["frames"])
    assert sorted(runs)[-3:] == [1, fps + 1, fps + 1] and runs[-1] == fps + 1

    monkeypatch.setattr(demo, "write_video", capture)
    monkeypatch.setattr(demo, "_figures", lambda *a, **k: {})
    demo.run_demo(tmp_path / "demo", episodes=2, seed=0)
    runs = _runs(written["frames"])
    assert sorted(runs)[-3:] == [1, fps + 1, fps + 1] and runs[-1] == fps + 1
