"""The ``human`` window's keys, with pygame's dummy video driver: key presses are posted as
events, as the window would receive them."""

from __future__ import annotations

import time

import numpy as np
import pytest

pygame = pytest.importorskip("pygame")

from soccer_env.envs.goalkeeper import GoalkeeperEnv  # noqa: E402
from soccer_env.render import KEYS_HELP  # noqa: E402

STILL = np.zeros(6, np.float32)


@pytest.fixture
def window(monkeypatch):
    monkeypatch.setenv("SDL_VIDEODRIVER", "dummy")
    env = GoalkeeperEnv(obs_mode="perceived", render_mode="human", render_width=480,
                        shots={"delay": (5.0, 5.0)})
    env.reset(seed=0)  # shows the first frame
    yield env
    env.close()


def press(*keys: int) -> None:
    for key in keys:
        pygame.event.post(pygame.event.Event(pygame.KEYDOWN, key=key, mod=0, unicode=""))


def test_the_window_names_its_keys(window):
    r = window.renderer
    assert r.frames_shown == 1
    assert KEYS_HELP in pygame.display.get_caption()[0]
    assert "space" in KEYS_HELP and "q or Esc" in KEYS_HELP


def test_pause_then_step_lets_exactly_one_frame_through(window):
    r = window.renderer
    press(pygame.K_SPACE, pygame.K_n)
    window.step(STILL)  # shown, then paused with one frame allowed: it returns
    assert r.paused and r.frames_shown == 2
    # Paused: the next step's frame is shown and held until a key lets it go (the right
    # arrow, 0.3 s later).
    pygame.time.set_timer(pygame.event.Event(pygame.KEYDOWN, key=pygame.K_RIGHT, mod=0,
                                             unicode=""), 300, loops=1)
    start = time.monotonic()
    window.step(STILL)
    assert time.monotonic() - start >= 0.25
    assert r.paused and r.frames_shown == 3
    press(pygame.K_SPACE)  # resume: steps run on
    start = time.monotonic()
    window.step(STILL)
    window.step(STILL)
    assert not r.paused and r.frames_shown == 5 and time.monotonic() - start < 0.25


def test_toggles_overlays_legend_and_zoom(window):
    r = window.renderer
    window.step(STILL)
    assert "belief_ball" in r.contents.overlays and r.contents.view == "field"
    press(pygame.K_o)
    window.step(STILL)
    assert not r.show_overlays
    window.step(STILL)
    assert not any(k.startswith("belief") for k in r.contents.overlays)
    assert r.contents.legend == ("team0", "ball")
    press(pygame.K_o, pygame.K_l, pygame.K_z)
    window.step(STILL)
    window.step(STILL)
    assert r.show_overlays and "belief_ball" in r.contents.overlays
    assert r.contents.legend == () and r.contents.view == "follow"


def test_q_closes_the_window_for_good(window):
    r = window.renderer
    press(pygame.K_q)
    window.step(STILL)
    shown = r.frames_shown
    assert not r.window_open
    window.step(STILL)
    assert window.render() is None and r.frames_shown == shown
