"""The reproductions' settings: defaults that validate, counts normalised, bad values named."""

from __future__ import annotations

import importlib
from pathlib import Path

import pytest

from soccer_lab.papers import PAPERS


@pytest.mark.parametrize("name", list(PAPERS))
def test_default_settings_are_valid_and_frozen(name):
    settings_cls = importlib.import_module(f"soccer_lab.papers.{name}").Settings
    s = settings_cls(Path("out"))
    assert s.out == Path("out")
    with pytest.raises(AttributeError):
        s.out = Path("elsewhere")


def test_counts_and_sizes_are_normalised():
    from soccer_lab.papers import following, localization, meanshift

    s = following.Settings(Path("o"), episodes=2, size=[320, 240], window_scales=[1, 2])
    assert s.size == (320, 240) and s.window_scales == (1.0, 2.0) and s.episodes == 2
    assert localization.Settings(Path("o"), fixed_sizes=[10], episodes=3).seeds == [0, 1, 2]
    assert meanshift.Settings(Path("o"), robots_per_team=2).robots_per_team == 2


@pytest.mark.parametrize("name, kwargs, match", [
    ("ekf", {"episodes": 0}, "episodes"),
    ("ekf", {"workers": 0}, "workers"),
    ("ungm", {"particles": 1}, "particles"),
    ("hough", {"pose_sigma": -1.0}, "pose_sigma"),
    ("team", {"duration": 0.5}, "duration"),
    ("localization", {"fixed_sizes": (0,)}, "fixed_sizes"),
    ("meanshift", {"robots_per_team": 7}, "robots_per_team"),
    ("following", {"window_scales": (8.0,)}, "window_scales"),
])
def test_bad_settings_name_the_setting(name, kwargs, match):
    settings_cls = importlib.import_module(f"soccer_lab.papers.{name}").Settings
    with pytest.raises(ValueError, match=match):
        settings_cls(Path("out"), **kwargs)
