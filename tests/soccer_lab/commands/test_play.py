"""``soccer-env play``: the keys' actions, the window's key state, and the loop run headless
(pygame's dummy video driver) on every task, with key presses posted as pygame events."""

from __future__ import annotations

import math
import sys

import gymnasium as gym
import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from soccer_env import presets
from soccer_lab.commands import play
from soccer_lab.commands.play import ACTION_KEYS, KEY_TURN_RATE, key_action, key_map, main

SSL = presets.ROBOTS["ssl"]
HUMANOID = presets.ROBOTS["humanoid"]
DT = 1.0 / 60.0  # the environments' control step [s]


def to_field(action: np.ndarray, heading: float) -> tuple[float, float]:
    """The body-frame command ``(vx, vy)`` of ``action`` in the field frame."""
    c, s = math.cos(heading), math.sin(heading)
    return c * action[0] - s * action[1], s * action[0] + c * action[1]


def ramp(steps: int, speed: float, acceleration: float) -> float:
    """The distance [m] from rest in ``steps`` control steps, accelerating at
    ``acceleration`` [m/s^2] up to ``speed`` [m/s]."""
    t, t1 = steps * DT, speed / acceleration
    return 0.5 * acceleration * t * t if t <= t1 else speed * (t - 0.5 * t1)


# ----------------------------------------------------------------------------------------
# Keys to actions
# ----------------------------------------------------------------------------------------


@pytest.mark.parametrize("heading", [0.0, 0.7, -2.0, math.pi])
def test_arrows_drive_an_ssl_robot_at_full_speed_the_way_they_point_on_the_screen(heading):
    # The frames draw +x (the goal blue attacks) to the right and +y up.
    for keys, want in ((("right",), (1.0, 0.0)), (("d",), (1.0, 0.0)),
                       (("left",), (-1.0, 0.0)), (("up",), (0.0, 1.0)), (("s",), (0.0, -1.0))):
        action = key_action(set(keys), SSL, heading)
        assert to_field(action, heading) == pytest.approx(want, abs=1e-6), keys
        assert action[2] == 0.0  # no turn
    # Diagonals at full speed, not faster: the command's norm is 1.
    action = key_action({"right", "up"}, SSL, heading)
    fx, fy = to_field(action, heading)
    assert (fx, fy) == pytest.approx((math.sqrt(0.5), math.sqrt(0.5)), abs=1e-6)


def test_opposite_keys_cancel():
    assert key_action({"left", "right"}, SSL)[0:3].tolist() == [0.0, 0.0, 0.0]
    assert key_action({"q", "e"}, SSL)[2] == 0.0
    assert to_field(key_action({"up", "w", "s", "right"}, SSL, 1.0), 1.0) == \
        pytest.approx((1.0, 0.0), abs=1e-6)
    assert key_action({"w", "s", "a", "d"}, HUMANOID)[0:2].tolist() == [0.0, 0.0]


def test_kick_chip_and_dribbler_keys():
    idle = key_action(set(), SSL)
    assert idle.tolist() == [0.0, 0.0, 0.0, 0.0, -1.0, -1.0]  # kicker disarmed, chip and
    # dribbler off
    kick = key_action({"space"}, SSL)
    assert kick[3] == 1.0 and kick[4] == -1.0
    chip = key_action({"space", "left shift"}, SSL)
    assert chip[3] == 1.0 and chip[4] == 1.0
    assert key_action({"left shift"}, SSL)[3:5].tolist() == [0.0, -1.0]  # shift alone: nothing
    assert key_action({"f"}, SSL)[5] == 1.0
    # A robot that cannot chip kicks flat; one without a dribbler keeps it off.
    flat = presets.robot("ssl", chip_max_speed=0.0)
    assert key_action({"space", "right shift"}, flat)[3:5].tolist() == [1.0, -1.0]
    bare = presets.robot("ssl", dribbler_force=0.0)
    assert key_action({"f"}, bare)[5] == -1.0


def test_q_and_e_turn_at_the_key_turn_rate_or_the_robots_top_rate():
    q = key_action({"q"}, SSL)
    assert q[2] * SSL.max_angular_speed == pytest.approx(KEY_TURN_RATE)  # counter-clockwise
    assert key_action({"e"}, SSL)[2] == -q[2]
    # A humanoid turns slower than the key rate: at its top rate.
    assert key_action({"q"}, HUMANOID)[2] == 1.0


@pytest.mark.parametrize("heading", [0.0, 2.5])
def test_a_humanoid_walks_in_its_body_frame_kicks_and_dives(heading):
    assert key_action({"up"}, HUMANOID, heading).tolist() == [1.0, 0.0, 0.0, 0.0, 0.0, 0.0]
    assert key_action({"down"}, HUMANOID, heading)[0] == -1.0
    assert key_action({"a"}, HUMANOID, heading)[1] == 1.0
    assert key_action({"space"}, HUMANOID, heading)[3] == 1.0  # kick
    # Shift and a side dive to that side (motion < -0.5, the side by the sign of vy).
    left = key_action({"left shift", "left"}, HUMANOID, heading)
    assert left[3] == -1.0 and left[1] > 0.0
    right = key_action({"right shift", "d"}, HUMANOID, heading)
    assert right[3] == -1.0 and right[1] < 0.0
    assert key_action({"left shift"}, HUMANOID, heading)[3] == 0.0  # no side: no dive
    assert key_action({"left shift", "left", "right"}, HUMANOID, heading)[3] == 0.0


@given(st.sets(st.sampled_from(sorted(ACTION_KEYS | {"x", "escape"}))),
       st.floats(-20.0, 20.0), st.sampled_from(sorted(presets.ROBOTS)))
def test_every_key_combination_gives_an_action_of_the_action_space(keys, heading, robot):
    action = key_action(keys, presets.ROBOTS[robot], heading)
    assert action.dtype == np.float32 and action.shape == (6,)
    assert action in gym.spaces.Box(-1.0, 1.0, (6,), np.float32)


def test_a_non_finite_heading_is_refused():
    with pytest.raises(ValueError, match="heading"):
        key_action({"up"}, SSL, math.nan)


def test_the_key_map_names_what_the_robot_can_do(capsys):
    ssl = dict(key_map(SSL))
    assert "chip kick" in ssl.values() and any("dribbler" in v for v in ssl.values())
    assert not any("chip" in v for v in dict(key_map(presets.robot("ssl", chip_max_speed=0.0)))
                   .values())
    humanoid = dict(key_map(HUMANOID))
    assert humanoid["shift + left / right"] == "dive to that side"
    assert "0.3" in humanoid["up / down, W / S"]  # its forward speed [m/s]
    assert main(["--keys", "--robot", "humanoid"]) == 0
    out = capsys.readouterr().out
    assert "dive to that side" in out and "chip" not in out
    with pytest.raises(SystemExit) as exit_:
        main(["--help"])
    assert exit_.value.code == 0
    out = capsys.readouterr().out
    assert "shift + space (hold)" in out and "dive to that side" in out  # both maps


def test_every_option_states_its_default():
    import argparse

    p = play.parser()
    options = [a for a in p._actions
               if a.option_strings and not isinstance(a, argparse._HelpAction)]
    assert {"--task", "--robot", "--team-size", "--seed", "--fps", "--width", "--obs-mode",
            "--perception", "--max-steps", "--keys"} <= {a.option_strings[0] for a in options}
    for action in options:
        text = " ".join(p._get_formatter()._expand_help(action).split())
        if action.nargs == 0:  # a flag
            assert "(default: " not in text, action.option_strings
        elif action.default != []:  # (a repeatable option adds nothing unless given)
            assert text.count("(default: ") == 1, text
            if action.default is not None:
                assert f"(default: {action.default})" in text, text


# ----------------------------------------------------------------------------------------
# The window's key state
# ----------------------------------------------------------------------------------------


def test_key_state_follows_the_window_events():
    pygame = pytest.importorskip("pygame")
    keys = play.KeyState(pygame)

    def press(key, up=False):
        keys.process_event(pygame.event.Event(pygame.KEYUP if up else pygame.KEYDOWN, key=key))

    press(pygame.K_UP)
    press(pygame.K_SPACE)
    press(pygame.K_x)  # not a key of the game
    assert keys.pressed == {"up", "space"}
    press(pygame.K_UP, up=True)
    assert keys.pressed == {"space"}
    keys.process_event(pygame.event.Event(pygame.WINDOWFOCUSLOST))
    assert keys.pressed == set()  # the key-ups go elsewhere
    press(pygame.K_p)
    assert keys.paused
    press(pygame.K_p)
    assert not keys.paused
    press(pygame.K_r)
    assert keys.restart and keys.running
    press(pygame.K_ESCAPE)
    assert not keys.running
    closed = play.KeyState(pygame)
    closed.process_event(pygame.event.Event(pygame.QUIT))
    assert not closed.running


# ----------------------------------------------------------------------------------------
# The loop, headless
# ----------------------------------------------------------------------------------------


@pytest.fixture
def headless(monkeypatch):
    """pygame on the dummy video driver, and the games ``main`` makes, each with its
    robot 0's pose at every reset."""
    monkeypatch.setenv("SDL_VIDEODRIVER", "dummy")
    monkeypatch.setenv("SDL_AUDIODRIVER", "dummy")
    pygame = pytest.importorskip("pygame")
    made = []
    make = play.make_game

    def recording(*args, **kwargs):
        game = make(*args, **kwargs)
        game.starts = []
        reset = game.reset

        def reset_and_record(seed):
            reset(seed)
            game.starts.append((seed, game.unwrapped.world.snapshot().robots[0, :3]))

        game.reset = reset_and_record
        made.append(game)
        return game

    monkeypatch.setattr(play, "make_game", recording)
    pygame.display.init()
    yield pygame, made
    pygame.display.quit()


def pose(game) -> np.ndarray:
    return game.unwrapped.world.snapshot().robots[0, :3]


# (task, robot, key held, steps, field-frame direction it drives robot 0 in, speed [m/s],
# acceleration [m/s^2]); the shootout's striker starts turned towards the ball, so its
# field-frame drive is rotated; a humanoid walks forward, and blue faces +x at kick-off.
DRIVES = [
    ("match", "ssl", "K_RIGHT", 30, (1.0, 0.0), SSL.max_speed, SSL.max_acceleration),
    ("shootout", "ssl", "K_LEFT", 30, (-1.0, 0.0), SSL.max_speed, SSL.max_acceleration),
    ("keeper", "ssl", "K_w", 30, (0.0, 1.0), SSL.max_speed, SSL.max_acceleration),
    ("match", "humanoid", "K_w", 60, (1.0, 0.0), HUMANOID.max_forward_speed,
     HUMANOID.max_acceleration),
]


@pytest.mark.parametrize("task, robot, key, steps, direction, speed, acceleration", DRIVES)
def test_holding_a_key_drives_robot_0_as_far_as_its_limits_allow(
        headless, capsys, task, robot, key, steps, direction, speed, acceleration):
    pygame, made = headless
    pygame.event.post(pygame.event.Event(pygame.KEYDOWN, key=getattr(pygame, key)))
    assert main(["--task", task, "--robot", robot, "--max-steps", str(steps), "--fps", "0",
                 "--seed", "0"]) == 0
    (game,) = made
    (seed, start), = game.starts
    assert seed == 0
    moved = pose(game)[0:2] - start[0:2]
    along = float(moved @ np.array(direction))
    across = direction[0] * moved[1] - direction[1] * moved[0]
    assert along == pytest.approx(ramp(steps, speed, acceleration), rel=0.05)
    assert abs(across) < 0.005
    assert pose(game)[2] == pytest.approx(start[2], abs=1e-6)  # no turn
    assert game.unwrapped.world.time == pytest.approx(steps * DT)
    out = capsys.readouterr().out
    assert f"{task} seed 0: stopped after {steps * DT:.2f} s" in out


def scripted_events(pygame, script):
    """A stand-in for ``pygame.event.get``: the events of each frame (by frame number) of
    ``script``, none on the others."""
    frame = [0]

    def get():
        keys = script.get(frame[0], ())
        frame[0] += 1
        return [pygame.event.Event(pygame.KEYDOWN, key=getattr(pygame, k)) for k in keys]

    return get


def test_pause_stops_the_steps_and_escape_quits(headless, monkeypatch, capsys):
    pygame, made = headless
    hold = round(play.START_HOLD / DT)  # frames showing the start before play
    # Right from the first frame: 10 steps, then P, then nothing moves until Esc.
    script = {0: ["K_RIGHT"], hold + 10: ["K_p"], hold + 70: ["K_ESCAPE"]}
    monkeypatch.setattr(pygame.event, "get", scripted_events(pygame, script))
    assert main(["--task", "keeper", "--fps", "0", "--max-steps", "1000"]) == 0
    (game,) = made
    assert game.unwrapped.world.time == pytest.approx(10 * DT)
    start = game.starts[0][1]
    assert pose(game)[0] - start[0] == pytest.approx(ramp(10, SSL.max_speed,
                                                              SSL.max_acceleration), rel=0.05)
    assert capsys.readouterr().out.strip() == "keeper seed 0: stopped after 0.17 s"


def test_r_restarts_the_episode_with_its_seed(headless, monkeypatch, capsys):
    pygame, made = headless
    hold = round(play.START_HOLD / DT)
    # Right from the first frame: 20 steps, R (that frame restarts), the start shown again
    # for ``hold`` frames, 10 steps, Esc.
    script = {0: ["K_RIGHT"], hold + 20: ["K_r"], 2 * hold + 31: ["K_ESCAPE"]}
    monkeypatch.setattr(pygame.event, "get", scripted_events(pygame, script))
    assert main(["--task", "shootout", "--seed", "4", "--fps", "0"]) == 0
    (game,) = made
    (seed_a, start_a), (seed_b, start_b) = game.starts
    assert seed_a == seed_b == 4 and np.array_equal(start_a, start_b)
    # After the restart, 10 steps: from the same start again.
    assert game.unwrapped.world.time == pytest.approx(10 * DT)
    assert pose(game)[0] - start_b[0] == pytest.approx(
        ramp(10, SSL.max_speed, SSL.max_acceleration), rel=0.05)
    assert capsys.readouterr().out.strip() == "shootout seed 4: stopped after 0.17 s"


def test_each_finished_episode_is_printed_and_the_next_seed_follows(headless, capsys):
    _, made = headless
    # No key: the keeper stands; the environment alone decides how the shot ends.
    assert main(["--task", "keeper", "--fps", "0", "--max-steps", "120"]) == 0
    env = gym.make("soccer_env/Goalkeeper-v0")
    env.reset(seed=0)
    steps, done = 0, False
    while not done:
        _, _, terminated, truncated, info = env.step(key_action(set(), SSL))
        steps, done = steps + 1, terminated or truncated
    assert steps < 120
    what = "goal" if info["outcome"] == "goal" else f"save ({info['outcome']})"
    lines = capsys.readouterr().out.splitlines()
    assert lines[0] == f"keeper seed 0: {what} after {steps * DT:.2f} s"
    assert lines[1].startswith("keeper seed 1: ")
    assert [seed for seed, _ in made[0].starts] == [0, 1]


def test_a_match_prints_its_score_when_it_ends(headless, capsys):
    assert main(["--env-kwarg", "match_duration=0.5", "--team-size", "2", "--fps", "0",
                 "--max-steps", "40"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[0] == "match seed 0: blue 0 : 0 yellow after 0.5 s, draw"
    assert lines[1] == "match seed 1: stopped after 0.17 s (blue 0 : 0 yellow)"


def test_the_window_shows_the_environments_frame_with_robot_0_ringed_and_the_keys(headless):
    pygame, _ = headless
    game = play.make_game("keeper", "ssl", render_width=400)
    try:
        game.reset(0)
        frame = game.env.render()
        window = play.Window(pygame, game)
        window.draw(game, "READY")
        screen = pygame.surfarray.array3d(window.screen).swapaxes(0, 1)
        h, w = frame.shape[:2]
        assert screen.shape == (max(h, play.PANEL_HEIGHT), w + play.PANEL_WIDTH, 3)
        shown = screen[:h, :w]
        ring = np.all(shown == 255, axis=-1) & np.any(frame != 255, axis=-1)
        # Everything but the ring is the environment's frame.
        assert np.array_equal(shown[~ring], frame[~ring])
        # The ring is round the keeper (robot 0, near its goal at x = -L/2, on the left).
        x, y = game.unwrapped.world.robot_array()[0, 0:2]
        f = game.unwrapped.field
        k = w / (2.0 * (f.half_length + f.boundary))
        cols, rows = np.nonzero(ring.T)
        assert cols.mean() == pytest.approx((x + f.half_length + f.boundary) * k, abs=2)
        assert rows.mean() == pytest.approx((f.half_width + f.boundary - y) * k, abs=2)
        assert cols.mean() < 0.1 * w
        # The panel has text in it.
        assert (screen[:, w:] != screen[0, -1]).any()
    finally:
        game.close()


# ----------------------------------------------------------------------------------------
# Missing pygame and bad input
# ----------------------------------------------------------------------------------------


def test_without_pygame_the_command_says_which_extra_to_install(monkeypatch, capsys):
    monkeypatch.setitem(sys.modules, "pygame", None)  # import pygame raises ImportError
    assert main(["--max-steps", "5"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("soccer-env play needs the render extra: pip install "
                          "'soccer-env[render]'")
    assert err.count("\n") == 1


@pytest.mark.parametrize("argv, message", [
    (["--team-size", "0"], "--team-size"),
    (["--team-size", "2", "--task", "keeper"], "--team-size"),
    (["--width", "20"], "--width"),
    (["--width", "5000"], "--width"),
    (["--fps", "-1"], "--fps"),
    (["--max-steps", "0"], "--max-steps"),
    (["--seed", "-1"], "--seed"),
    (["--task", "penalty"], "--task"),
    (["--robot", "humanoid", "--perception", "realistic"], "realistic"),
])
def test_bad_input_is_refused(argv, message, capsys):
    with pytest.raises(SystemExit) as exit_:
        main(argv)
    assert exit_.value.code == 2
    assert message in capsys.readouterr().err

