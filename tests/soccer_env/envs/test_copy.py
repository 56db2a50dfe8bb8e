"""Copyable environments: ``copy.deepcopy``, ``pickle`` and ``cloudpickle`` of every
environment at any point of an episode give an environment whose future under the same
actions is the original's, bit for bit (physics with its cached contacts, referee, sensors'
queues, filters, random generators, renderer). The batched environments too (the Goalkeeper's
and the Shootout's vector environments, the batched match): before their first reset, right
after it, and mid-episode after autoresets.

The property: step ``k`` times, copy, step both ``n`` more times with the same actions
(through episode ends and seeded resets), and compare everything each step returns, the
world's truth and, at the end, the whole state of both, attribute by attribute."""

from __future__ import annotations

import collections
import copy
import functools
import pickle
import types
from collections.abc import Callable
from typing import Any

import gymnasium as gym
import numpy as np
import pymunk
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import soccer_env  # noqa: F401  (registers the environments)
from soccer_env.envs.aec import env as aec_env
from soccer_env.envs.batched_match import MatchBatch, MatchStep
from soccer_env.envs.match import parallel_env

cloudpickle = pytest.importorskip("cloudpickle")

COPIERS: dict[str, Callable[[Any], Any]] = {
    "deepcopy": copy.deepcopy,
    "pickle": lambda e: pickle.loads(pickle.dumps(e)),
    "cloudpickle": lambda e: cloudpickle.loads(cloudpickle.dumps(e)),
}


def assert_same(a: Any, b: Any, where: str = "") -> None:
    """Exact equality of nested results (NaN equal to NaN, arrays compared bit for bit)."""
    if isinstance(a, dict):
        assert a.keys() == b.keys(), where
        for key in a:
            assert_same(a[key], b[key], f"{where}.{key}")
    elif isinstance(a, (list, tuple)):
        assert len(a) == len(b), where
        for i, (x, y) in enumerate(zip(a, b)):
            assert_same(x, y, f"{where}[{i}]")
    elif isinstance(a, np.ndarray):
        assert a.dtype == b.dtype and a.shape == b.shape, (where, a, b)
        if a.dtype == object:  # (the batched environments' outcomes, final observations)
            assert_same(a.tolist(), b.tolist(), where)
        else:
            np.testing.assert_array_equal(a, b, err_msg=where)
    elif isinstance(a, float) and a != a:
        assert b != b, where
    else:
        assert a == b, (where, a, b)


def assert_same_state(a: Any, b: Any, where: str = "env", seen: dict | None = None) -> None:
    """Walk two object graphs side by side and require equal values everywhere: every
    attribute of every object, numpy arrays by value, random generators by their state,
    pymunk objects by their pickled state (bodies, shapes, joints, cached contacts with
    their accumulated impulses). Raw Chipmunk pointers are skipped; they differ by nature."""
    seen = {} if seen is None else seen
    if isinstance(a, (type(None), bool, int, float, complex, str, bytes)):
        assert_same(a, b, where)
        return
    if (id(a), id(b)) in seen:
        return
    seen[id(a), id(b)] = (a, b)  # (kept alive: the ids of freed objects are reused)
    assert type(a) is type(b), (where, type(a), type(b))
    module = type(a).__module__
    module = module if isinstance(module, str) else ""
    if module.startswith(("_cffi_backend", "pygame")) or isinstance(a, functools.partial):
        return
    if isinstance(a, np.random.Generator):
        assert_same(a.bit_generator.state, b.bit_generator.state, where)
    elif isinstance(a, (np.ndarray, np.generic)):
        assert_same(np.asarray(a), np.asarray(b), where)
    elif isinstance(a, dict):
        assert len(a) == len(b), where
        if all(isinstance(k, (str, int, float, tuple)) for k in a):
            assert set(a) == set(b), where
            pairs = [(k, a[k], b[k]) for k in a]
        else:  # objects as keys: compare in insertion order
            pairs = [(f"#{i}", (ka, va), (kb, vb))
                     for i, ((ka, va), (kb, vb)) in enumerate(zip(a.items(), b.items()))]
        for key, va, vb in pairs:
            assert_same_state(va, vb, f"{where}[{key!r}]", seen)
    elif isinstance(a, (list, tuple, collections.deque)):
        assert len(a) == len(b), where
        for i, (x, y) in enumerate(zip(a, b)):
            assert_same_state(x, y, f"{where}[{i}]", seen)
    elif isinstance(a, (set, frozenset)):
        assert len(a) == len(b), where
    elif isinstance(a, types.MethodType):
        assert a.__func__ is b.__func__, where
        assert_same_state(a.__self__, b.__self__, f"{where}.__self__", seen)
    elif isinstance(a, types.ModuleType):
        assert a is b, where
    elif isinstance(a, (types.FunctionType, types.BuiltinFunctionType, type)):
        assert a is b or a.__qualname__ == b.__qualname__, where
    elif module.startswith("pymunk") and hasattr(a, "__getstate__"):
        assert_same_state(_pymunk_state(a), _pymunk_state(b), f"{where}<pymunk>", seen)
    elif hasattr(a, "__dict__") or hasattr(type(a), "__slots__"):
        slots = [n for c in type(a).__mro__ for n in getattr(c, "__slots__", ())
                 if isinstance(n, str) and hasattr(a, n)]
        state = {**{n: getattr(a, n) for n in slots}, **getattr(a, "__dict__", {})}
        state_b = {**{n: getattr(b, n) for n in slots}, **getattr(b, "__dict__", {})}
        assert_same_state(state, state_b, where, seen)
    else:
        assert a == b, (where, a, b)


def _pymunk_state(obj: Any) -> Any:
    """pymunk's pickled state of ``obj``; a space's cached contacts sorted by their shapes.

    Chipmunk files cached contacts in a hash set keyed by the shapes' addresses, so their
    order differs between copies (it is only used to look them up and to drop stale ones)."""
    state = obj.__getstate__()
    if isinstance(obj, pymunk.Space):
        index = {shape: i for i, shape in enumerate(obj.shapes)}
        state["special"] = [
            (key, sorted(value, key=lambda d: (index[d["a"]], index[d["b"]]))
             if key == "arbiters" else value) for key, value in state["special"]]
    return state


def _truth(env: Any) -> Any:
    snap = env.unwrapped.world.snapshot()
    return snap.time, snap.ball, snap.robots


GYM_CASES: dict[str, dict[str, Any]] = {
    "keeper-truth": {},
    "keeper-perceived-realistic": dict(obs_mode="perceived", perception={"vision": "realistic"}),
    "keeper-raw-rendered": dict(obs_mode="raw", render_mode="rgb_array", render_width=160),
    "keeper-humanoid-mates": dict(robot="humanoid", obs_mode="perceived", mates=3),
    "keeper-humanoid-kick-tracker": dict(robot="humanoid", obs_mode="perceived", mates=3,
                                         perception={"ball_tracker": "kick"}),
    "keeper-ssl-pixels": dict(field="ssl-2012", obs_mode="perceived",
                              perception={"vision": "ssl-2012", "detector": "pixels"}),
    "keeper-humanoid-pixels": dict(robot="humanoid-2012", obs_mode="perceived",
                                   perception={"detector": "pixels"}),
}


def _gym_run(kwargs: dict[str, Any], copier: str, k: int, n: int, seed: int,
             env_id: str = "soccer_env/Goalkeeper-v0") -> None:
    if "pixels" in str(kwargs):
        pytest.importorskip("cv2", reason="the pixels detector needs the 'pixels' extra")
    env = gym.make(env_id, **kwargs)
    env.reset(seed=seed)
    actions = np.random.default_rng(seed)
    low, high = env.action_space.low, env.action_space.high

    def act() -> np.ndarray:
        return actions.uniform(low, high).astype(env.action_space.dtype)

    for _ in range(k):
        if any(env.step(act())[2:4]):
            env.reset()
    twin = COPIERS[copier](env)
    if env.render_mode == "rgb_array":
        assert_same(env.render(), twin.render(), "render")
    for t in range(n):
        a = act()
        out, out_twin = env.step(a), twin.step(a)
        assert_same(out, out_twin, f"step {t}")
        assert_same(_truth(env), _truth(twin), f"truth {t}")
        if out[2] or out[3]:
            assert_same(env.reset(seed=seed + t), twin.reset(seed=seed + t), "reset")
    # Nothing else differs either.
    assert_same_state(env.unwrapped, twin.unwrapped)


@pytest.mark.parametrize("case", sorted(GYM_CASES))
@pytest.mark.parametrize("copier", sorted(COPIERS))
def test_goalkeeper_copy_has_the_same_future(case, copier):
    _gym_run(GYM_CASES[case], copier, k=37, n=90, seed=3)


@pytest.mark.parametrize("copier", sorted(COPIERS))
def test_shootout_copy_has_the_same_future(copier):
    _gym_run({"obs_mode": "perceived"}, copier, k=25, n=90, seed=5,
             env_id="soccer_env/Shootout-v0")


@settings(max_examples=6, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(k=st.integers(0, 400), n=st.integers(1, 60), seed=st.integers(0, 2**31 - 1),
       copier=st.sampled_from(sorted(COPIERS)))
def test_copy_at_any_point_of_an_episode(k, n, seed, copier):
    """Anywhere in an episode, also right after a reset and across episode ends."""
    _gym_run({"obs_mode": "perceived"}, copier, k=k, n=n, seed=seed)


MATCH_CASES: dict[str, dict[str, Any]] = {
    "ssl-6v6-perceived": dict(blue=6, yellow=6, obs_mode="perceived"),
    "ssl-2v2-raw-rendered": dict(blue=2, yellow=2, obs_mode="raw", render_mode="rgb_array",
                                 render_width=160),
    "humanoid-3v3-perceived": dict(blue=3, yellow=3, robot="humanoid", obs_mode="perceived"),
    "mixed-2v2-perceived": dict(blue=2, yellow=2, robot={"blue": "ssl", "yellow": "humanoid"},
                                obs_mode="perceived"),
}


@pytest.mark.parametrize("case", sorted(MATCH_CASES))
@pytest.mark.parametrize("copier", ["deepcopy", "pickle"])
def test_parallel_match_copy_has_the_same_future(case, copier):
    """Robots pushing each other and the ball (cached contacts) included: a 6 vs 6 match
    crowds robots together from the kick-off on."""
    env = parallel_env(**MATCH_CASES[case], max_cycles=300)
    env.reset(seed=11)
    rng = np.random.default_rng(0)

    def actions() -> dict[str, np.ndarray]:
        return {a: rng.uniform(env.action_space(a).low, env.action_space(a).high)
                .astype(np.float32) for a in env.agents}

    for _ in range(60):
        env.step(actions())
    twin = COPIERS[copier](env)
    for t in range(120):
        a = actions()
        assert_same(env.step(a), twin.step(a), f"step {t}")
        assert_same(env.state(), twin.state(), f"state {t}")
        assert_same(_truth(env), _truth(twin), f"truth {t}")
        if not env.agents:
            break
    if env.render_mode == "rgb_array":
        assert_same(env.render(), twin.render(), "render")
    assert_same_state(env, twin)


@pytest.mark.parametrize("copier", sorted(COPIERS))
def test_aec_match_copy_has_the_same_future(copier):
    env = aec_env(blue=2, yellow=2, obs_mode="perceived")
    env.reset(seed=2)
    rng = np.random.default_rng(1)

    def act() -> np.ndarray:
        space = env.action_space(env.agent_selection)
        return rng.uniform(space.low, space.high).astype(np.float32)

    for _ in range(41):  # mid-cycle: some agents have acted, the others not yet
        env.step(act())
    twin = COPIERS[copier](env)
    assert twin.agent_selection == env.agent_selection
    for t in range(200):
        a = act()
        env.step(a)
        twin.step(a)
        assert_same(env.last(), twin.last(), f"step {t}")
        assert_same(_truth(env), _truth(twin), f"truth {t}")
    assert_same_state(env, twin)


def test_copies_are_independent():
    """Stepping a copy leaves the original where it was (no shared world, queue or
    generator)."""
    env = gym.make("soccer_env/Goalkeeper-v0", obs_mode="perceived")
    env.reset(seed=0)
    before = _truth(env)
    twin = copy.deepcopy(env)
    for _ in range(30):
        twin.step(twin.action_space.high)
    assert_same(_truth(env), before, "original")
    assert not np.array_equal(_truth(twin)[2], before[2])


def test_copying_changes_the_original_only_in_the_last_bits():
    """What copying costs the original (documented in ``World.__getstate__``): its space is
    rebuilt as the copy's is, so its trajectory may move in the last bits, no more."""
    kw = dict(blue=6, yellow=6, max_cycles=300)
    plain, copied = parallel_env(**kw), parallel_env(**kw)
    plain.reset(seed=4)
    copied.reset(seed=4)
    rng = np.random.default_rng(0)
    for t in range(120):
        a = {n: rng.uniform(-1, 1, plain.action_space(n).shape).astype(np.float32)
             for n in plain.agents}
        plain.step(a)
        copied.step(a)
        if t == 30:
            copy.deepcopy(copied)
    np.testing.assert_allclose(_truth(copied)[2], _truth(plain)[2], atol=1e-6)


# ----------------------------------------------------------------------------------------
# Batched environments
# ----------------------------------------------------------------------------------------

#: The batched single-agent tasks; the Shootout's time limit is short so that its episodes
#: (which random actions rarely end otherwise) end and autoreset within the test.
VECTOR_CASES: dict[str, tuple[str, dict[str, Any]]] = {
    "goalkeeper-truth": ("soccer_env/Goalkeeper-v0", {}),
    "goalkeeper-perceived": ("soccer_env/Goalkeeper-v0", {"obs_mode": "perceived"}),
    "shootout-truth": ("soccer_env/Shootout-v0", {"max_episode_steps": 40}),
    "shootout-perceived": ("soccer_env/Shootout-v0",
                           {"obs_mode": "perceived", "max_episode_steps": 40}),
}
#: When the copy is taken: before the first reset (then both reset with the same seed),
#: right after it, or mid-episode, after an autoreset and at a step that ended an episode
#: (its environment resets at the next step while the others play on).
WHEN = ("before-reset", "after-reset", "mid-episode")


def _copy_batched(env: Any, when: str, copier: str, seed: int,
                  step: Callable[[Any], Any], ended: Callable[[Any], bool]) -> Any:
    """Bring ``env`` to the moment ``when`` (stepping with ``step(env)``, which returns what
    ``env.step`` returns, and ``ended`` of it) and return its copy, reset as ``env`` where
    the copy is taken before the first reset."""
    if when == "before-reset":
        twin = COPIERS[copier](env)
        assert_same(env.reset(seed=seed), twin.reset(seed=seed), "reset")
        return twin
    env.reset(seed=seed)
    if when == "mid-episode":
        ends = 0
        for _ in range(400):
            ends += ended(step(env))
            if ends >= 2:  # the first one's environment has autoreset since
                break
        assert ends >= 2, "no episode ended"
    return COPIERS[copier](env)


@pytest.mark.parametrize("when", WHEN)
@pytest.mark.parametrize("copier", sorted(COPIERS))
@pytest.mark.parametrize("case", sorted(VECTOR_CASES))
def test_batched_copy_has_the_same_future(case, copier, when):
    """The batched Goalkeeper and Shootout (``gymnasium.make_vec``, Gymnasium's
    ``NEXT_STEP`` autoreset): every step's observations, rewards, terminations, truncations
    and infos, the physics' state, and at the end the whole state of both."""
    env_id, kwargs = VECTOR_CASES[case]
    env = gym.make_vec(env_id, num_envs=3, vectorization_mode="vector_entry_point", **kwargs)
    rng = np.random.default_rng(7)

    def act() -> np.ndarray:
        return rng.uniform(-1.0, 1.0, env.action_space.shape).astype(np.float32)

    twin = _copy_batched(env, when, copier, 9, lambda e: e.step(act()),
                         lambda out: bool(np.any(out[2] | out[3])))
    ends = 0
    for t in range(200):
        a = act()
        out, out_twin = env.step(a), twin.step(a)
        assert_same(out, out_twin, f"step {t}")
        assert_same(env.batch.state, twin.batch.state, f"truth {t}")
        ends += int(np.any(out[2] | out[3]))
    assert ends > 0  # the copies' futures went through episode ends and autoresets
    assert_same_state(env, twin)


@pytest.mark.parametrize("when", WHEN)
@pytest.mark.parametrize("copier", sorted(COPIERS))
@pytest.mark.parametrize("obs_mode", ["truth", "perceived"])
def test_batched_match_copy_has_the_same_future(obs_mode, copier, when):
    """The batched match (2 vs 2, short matches so that they end and start over)."""
    batch = MatchBatch(3, blue=2, yellow=2, obs_mode=obs_mode, max_cycles=60)
    rng = np.random.default_rng(3)
    shape = (3, batch.n_robots, 6)

    def fields(out: MatchStep) -> dict[str, Any]:
        return {name: getattr(out, name) for name in MatchStep.__slots__}

    twin = _copy_batched(batch, when, copier, 4, lambda b: b.step(rng.uniform(-1, 1, shape)),
                         lambda out: bool(np.any(out.terminated | out.truncated)))
    for t in range(150):
        a = rng.uniform(-1.0, 1.0, shape)
        assert_same(fields(batch.step(a)), fields(twin.step(a)), f"step {t}")
        assert_same(batch.batch.state, twin.batch.state, f"truth {t}")
    assert_same_state(batch, twin)
