"""Behaviour regression: seeded episodes in every observation mode give exactly the recorded
observations, rewards and infos.

Each case runs a few seeded episodes with seeded random actions and digests (SHA-256) every
observation, reward, termination flag and info dict. ``tests/data/episode_digests.json``
holds one recording per machine fingerprint: floating-point results can differ in the last bit
with another numpy, numba, pymunk or OpenCV release or another CPU's SIMD paths (numpy's sine
and cosine on AVX-512 against AVX2, for one), so the comparison runs where a recording's
fingerprint matches this machine's (and is skipped, saying why, elsewhere). A change that is
meant to alter behaviour re-records the digests, which drops every other machine's recording
(they are stale), and says so in its commit message::

    python -m tests.test_regression --update     # from the repository's root

Where the digests pass on one machine, another machine's recording is added (or its own
replaced) with the same code, the others kept::

    python -m tests.test_regression --add
"""

from __future__ import annotations

import hashlib
import json
import platform
import struct
import sys
from collections.abc import Callable
from importlib import metadata
from pathlib import Path
from typing import Any

import gymnasium as gym
import numpy as np
import pytest

import soccer_env

DIGESTS = Path(__file__).resolve().parent / "data" / "episode_digests.json"
SEEDS = (0, 1)
GOALKEEPER_STEPS = 150
MATCH_STEPS = 120
VISION_PRESETS = ("ideal", "realistic", "ssl-2012", "harsh")
BALL_FILTERS = ("kf", "kf-comp", "ekf", "ekf-improved", "ekf-2phase", "ls", "kick", "imm")


def _feed(h: Any, obj: Any) -> None:
    """Feed a canonical byte form of ``obj`` (nested dicts, sequences, arrays, scalars) to
    the hash ``h``."""
    if isinstance(obj, dict):
        h.update(b"{")
        for key in sorted(obj, key=str):
            _feed(h, str(key))
            _feed(h, obj[key])
        h.update(b"}")
    elif isinstance(obj, (list, tuple)):
        h.update(b"[")
        for item in obj:
            _feed(h, item)
        h.update(b"]")
    elif isinstance(obj, np.ndarray):
        h.update(f"a{obj.dtype.str}{obj.shape}".encode())
        h.update(np.ascontiguousarray(obj).tobytes())
    elif isinstance(obj, (bool, np.bool_)):
        h.update(b"T" if obj else b"F")
    elif isinstance(obj, (int, np.integer)):
        h.update(b"i%d;" % int(obj))
    elif isinstance(obj, (float, np.floating)):
        h.update(b"f" + struct.pack("<d", float(obj)))
    elif obj is None:
        h.update(b"N")
    elif isinstance(obj, str):
        h.update(b"s" + obj.encode() + b"\0")
    else:
        raise TypeError(f"cannot digest {type(obj).__name__}")


def _goalkeeper(**kwargs: Any) -> Callable[[int], str]:
    return _gym("soccer_env/Goalkeeper-v0", **kwargs)


def _shootout(**kwargs: Any) -> Callable[[int], str]:
    return _gym("soccer_env/Shootout-v0", **kwargs)


def _gym(env_id: str, **kwargs: Any) -> Callable[[int], str]:
    def run(seed: int) -> str:
        env = gym.make(env_id, **kwargs)
        actions = np.random.default_rng(1000 + seed).uniform(-1.0, 1.0, (GOALKEEPER_STEPS, 6))
        h = hashlib.sha256()
        obs, info = env.reset(seed=seed)
        _feed(h, (obs, info))
        for a in actions:
            obs, reward, term, trunc, info = env.step(a.astype(np.float32))
            _feed(h, (obs, reward, term, trunc, info))
            if term or trunc:
                break
        env.close()
        return h.hexdigest()

    return run


def _match(**kwargs: Any) -> Callable[[int], str]:
    def run(seed: int) -> str:
        env = soccer_env.parallel_env(**kwargs)
        rng = np.random.default_rng(2000 + seed)
        h = hashlib.sha256()
        obs, infos = env.reset(seed=seed)
        _feed(h, (obs, infos))
        for _ in range(MATCH_STEPS):
            if not env.agents:
                break
            actions = {a: rng.uniform(-1.0, 1.0, 6).astype(np.float32) for a in env.agents}
            _feed(h, env.step(actions))
        env.close()
        return h.hexdigest()

    return run


CASES: dict[str, Callable[[int], str]] = {}
for _mode in ("truth", "raw", "perceived"):
    for _preset in VISION_PRESETS:
        CASES[f"goalkeeper-ssl-{_mode}-{_preset}"] = _goalkeeper(obs_mode=_mode,
                                                                 perception=_preset)
for _filter in BALL_FILTERS:
    CASES[f"goalkeeper-ssl-perceived-ssl-2012-{_filter}"] = _goalkeeper(
        obs_mode="perceived", perception={"vision": "ssl-2012", "ball_filter": _filter})
CASES.update({
    "goalkeeper-ssl2012-paper-setting": _goalkeeper(
        field="ssl-2012", robot="ssl-2012", control_dt=0.04, obs_mode="perceived",
        perception="ssl-2012"),
    "goalkeeper-ssl-shaping": _goalkeeper(
        obs_mode="perceived", shaping={"intercept": 2.0, "ball_distance": 0.5,
                                       "action_cost": 0.1, "outside_area": 1.0}),
    "goalkeeper-humanoid2012-truth": _goalkeeper(robot="humanoid-2012"),
    "goalkeeper-humanoid2012-raw": _goalkeeper(robot="humanoid-2012", obs_mode="raw"),
    "goalkeeper-humanoid2012-perceived": _goalkeeper(robot="humanoid-2012",
                                                     obs_mode="perceived"),
    "goalkeeper-humanoid-perceived-kidsize": _goalkeeper(robot="humanoid",
                                                         obs_mode="perceived"),
    "goalkeeper-humanoid-perceived-own-none-odometry": _goalkeeper(
        robot="humanoid", obs_mode="perceived",
        perception={"camera": "kidsize", "fusion": "own", "ball_tracker": "none",
                    "localization": "odometry"}),
    "goalkeeper-humanoid-perceived-equal-fbpf-scan": _goalkeeper(
        robot="humanoid-2012", obs_mode="perceived", head="scan",
        perception={"fusion": "equal", "ball_tracker": "fbpf", "radio": "ideal"}),
    "goalkeeper-humanoid-perceived-head-action-one-mate": _goalkeeper(
        robot="humanoid-2012", obs_mode="perceived", head="action", mates=1),
    "goalkeeper-humanoid-truth-localization-bootstrap": _goalkeeper(
        robot="humanoid-2012", obs_mode="perceived",
        perception={"localization": "truth", "ball_tracker": "bootstrap",
                    "fusion": "inverse_square"}),
    "shootout-ssl-truth": _shootout(),
    "shootout-ssl-perceived-realistic": _shootout(obs_mode="perceived", perception="realistic"),
    "shootout-ssl-raw-harsh": _shootout(obs_mode="raw", perception="harsh"),
    "shootout-humanoid2012-perceived": _shootout(robot="humanoid-2012", obs_mode="perceived"),
    "match-ssl-3v3-truth": _match(blue=3, yellow=3),
    "match-ssl-3v3-raw": _match(blue=3, yellow=3, obs_mode="raw", perception="harsh"),
    "match-ssl-3v3-perceived": _match(blue=3, yellow=3, obs_mode="perceived"),
    "match-ssl-3v3-perceived-per-team": _match(
        blue=3, yellow=3, obs_mode="perceived",
        perception={"blue": "ssl-2012", "yellow": "realistic"},
        shaping={"ball_progress": 1.0, "ball_distance": 0.1}),
    "match-ssl-6v6-perceived-div-a": _match(blue=6, yellow=6, field="ssl-div-a",
                                            obs_mode="perceived", max_cycles=100),
    "match-humanoid-3v3-perceived": _match(blue=3, yellow=3, robot="humanoid",
                                           obs_mode="perceived"),
    "match-humanoid-2v2-raw": _match(blue=2, yellow=2, robot="humanoid-2012", obs_mode="raw"),
    "match-mixed-2v2-perceived": _match(blue=2, yellow=2,
                                        robot={"blue": "ssl", "yellow": "humanoid"},
                                        field="humanoid-kid", obs_mode="perceived"),
})
PIXEL_CASES: dict[str, Callable[[int], str]] = {
    "goalkeeper-ssl-pixels": _goalkeeper(
        field="ssl-2012", obs_mode="perceived",
        perception={"vision": "ssl-2012", "detector": "pixels"}),
    "goalkeeper-humanoid-pixels": _goalkeeper(
        robot="humanoid-2012", obs_mode="perceived", perception={"detector": "pixels"}),
    "match-ssl-2v2-pixels": _match(blue=2, yellow=2, field="ssl-2012", obs_mode="perceived",
                                   perception={"vision": "ssl-2012", "detector": "pixels"}),
}


def fingerprint() -> dict[str, Any]:
    """What the digests depend on besides the code: library versions and the CPU features
    numpy dispatches its SIMD loops on."""
    def version(dist: str) -> str | None:
        try:
            return metadata.version(dist)
        except metadata.PackageNotFoundError:
            return None

    try:
        from numpy._core._multiarray_umath import __cpu_features__ as features
    except ImportError:  # pragma: no cover - other numpy layouts
        features = {}
    return {
        "python": ".".join(map(str, sys.version_info[:2])),
        "machine": platform.machine(),
        "numpy": np.__version__,
        "pymunk": version("pymunk"),
        "opencv": version("opencv-python-headless"),
        "numba": version("numba"),
        "cpu_features": sorted(k for k, v in features.items() if v),
    }


def _recordings() -> list[dict[str, Any]]:
    """Every recording: ``{"fingerprint": ..., "cases": {case: [digest per seed]}}``."""
    return json.loads(DIGESTS.read_text())["recordings"]


@pytest.fixture(scope="module")
def recorded() -> dict[str, Any]:
    here = fingerprint()
    data = _recordings()
    for rec in data:
        if rec["fingerprint"] == here:
            return rec["cases"]
    diffs = [{k: (rec["fingerprint"].get(k), v) for k, v in here.items()
              if rec["fingerprint"].get(k) != v} for rec in data]
    pytest.skip(f"no digests recorded under this environment (the recordings differ in "
                f"{diffs}); once they pass on a recorded machine, add this one with "
                "python -m tests.test_regression --add")


@pytest.mark.parametrize("case", sorted(CASES))
def test_episode_digests_unchanged(case, recorded):
    assert [CASES[case](s) for s in SEEDS] == recorded[case]


@pytest.mark.parametrize("case", sorted(PIXEL_CASES))
def test_pixel_episode_digests_unchanged(case, recorded):
    pytest.importorskip("cv2", reason="the pixels detector needs the 'pixels' extra (OpenCV)")
    assert [PIXEL_CASES[case](s) for s in SEEDS] == recorded[case]


def test_every_case_is_recorded_once_per_machine():
    data = _recordings()
    assert data, "no recording"
    for rec in data:
        assert sorted(rec["cases"]) == sorted({**CASES, **PIXEL_CASES})
    prints = [json.dumps(rec["fingerprint"], sort_keys=True) for rec in data]
    assert len(set(prints)) == len(prints)


def _record(keep_others: bool) -> None:
    """Record this machine's digests: alone (``--update``) or beside the other machines'
    recordings (``--add``)."""
    here = fingerprint()
    cases = {name: [run(s) for s in SEEDS]
             for name, run in sorted({**CASES, **PIXEL_CASES}.items())}
    others = ([rec for rec in _recordings() if rec["fingerprint"] != here]
              if keep_others and DIGESTS.exists() else [])
    DIGESTS.parent.mkdir(exist_ok=True)
    DIGESTS.write_text(json.dumps({"recordings": [*others, {"fingerprint": here,
                                                            "cases": cases}]}, indent=1)
                       + "\n")
    print(f"recorded {len(cases)} cases in {DIGESTS} ({len(others)} other recordings kept)")


if __name__ == "__main__":
    if sys.argv[1:] not in (["--update"], ["--add"]):
        sys.exit("usage: python -m tests.test_regression --update | --add")
    _record(keep_others=sys.argv[1] == "--add")
