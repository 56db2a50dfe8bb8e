"""Trained policies shipped with the package.

Each baseline is a :class:`~agents.policies.numpy_policy.NumpyPolicy` (``NAME.npz``: the
actor's weights and observation statistics, a few tens to a few hundred kB, run with numpy
alone) and, for those trained with stable-baselines3, the model it was copied from
(``NAME.zip``, with ``NAME_vecnormalize.npz``, its normalisation statistics, to fine-tune;
both load without unpickling, see :mod:`agents.sb3.model_files`); the DAgger keeper
(:data:`NUMPY_ONLY`) is its numpy policy alone. The ``.npz`` carries the training
configuration, the command that trained it and its evaluation in ``policy.meta``;
:func:`make_baseline_env` builds the environment it was trained for.

>>> from agents.baselines import load_baseline, make_baseline_env
>>> keeper = load_baseline("keeper-ppo-ssl2012")
>>> env = make_baseline_env("keeper-ppo-ssl2012")
>>> obs, info = env.reset(seed=0)
>>> keeper(obs).shape
(6,)

The shipped SSL match team (:data:`SSL_TEAM_2V2`, :func:`load_team`) is a numpy policy of the
same kind that plays every robot of a team of two in
:class:`~soccer_env.envs.match.SoccerParallelEnv`: it acts through the ``"team-residual"``
map (:mod:`agents.scripted.residual`) and takes the observations of the whole team at once, robots
in order (``team(np.stack([obs["blue_0"], obs["blue_1"]]))``), as
:func:`agents.studies.matches.head_to_head` calls it. Its earlier copies from the same training
run lie in ``ssl_team_2v2_checkpoints/``.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from agents.policies import NumpyPolicy
from soccer_env.envs.registration import GOALKEEPER_ID

__all__ = ["BASELINES", "NUMPY_ONLY", "load_baseline", "baseline_path", "baseline_env_kwargs",
           "make_baseline_env", "SSL_TEAM_2V2", "SSL_TEAM_CHECKPOINTS", "load_team", "TEAMS",
           "team_path"]

_HERE = Path(__file__).parent

#: The shipped SSL match team, 2 vs 2 (``examples/train_ssl_team.py`` trained it; its
#: ``meta`` holds the training match, the steps and the minutes).
SSL_TEAM_2V2 = _HERE / "ssl_team_2v2.npz"
#: The copies of the team its training saved on the way, ``team_<steps>.npz``.
SSL_TEAM_CHECKPOINTS = _HERE / "ssl_team_2v2_checkpoints"


def load_team() -> NumpyPolicy:
    """The shipped SSL match team (:data:`SSL_TEAM_2V2`): call it on the observations of
    both robots of a team, in order, of a 2 vs 2 match made with
    ``soccer_env.parallel_env(**load_team().meta["eval_kwargs"])``."""
    return NumpyPolicy.load(SSL_TEAM_2V2)


#: Shipped SSL match teams: name -> (file, description).
TEAMS: dict[str, tuple[Path, str]] = {
    "ssl-team-2v2": (
        SSL_TEAM_2V2,
        "2 vs 2 team correcting the scripted team (team-residual), trained by self-play on "
        "true observations under the simple referee (25 M agent steps)"),
}


def team_path(name: str) -> Path:
    """The numpy policy file of the shipped team ``name`` (:data:`TEAMS`)."""
    if name not in TEAMS:
        raise ValueError(f"unknown team {name!r}; shipped: {sorted(TEAMS)}")
    return TEAMS[name][0]

#: Shipped baselines: name -> (file stem, description).
BASELINES: dict[str, tuple[str, str]] = {
    "keeper-ppo-ssl2012": (
        "keeper_ppo_ssl2012",
        "PPO keeper choosing where to stand on its guard line 25 times a second, trained on "
        "true observations (1 M steps) and then on perceived ones (ssl-2012 vision, EKF; 5 M "
        "steps)"),
    "keeper-ppo-residual-ssl2012": (
        "keeper_ppo_residual_ssl2012",
        "PPO keeper correcting the scripted keeper's point on its guard line (guard-residual "
        "actions) 25 times a second, trained on perceived observations (ssl-2012 vision, EKF; "
        "2 M steps, 18 minutes on 2 cores)"),
    "keeper-ppo-residual-realistic": (
        "keeper_ppo_residual_realistic",
        "the same residual keeper trained on perceived realistic observations (ER-Force's "
        "realism preset, EKF; 2 M steps, 21 minutes on 2 cores)"),
    "keeper-ppo-truth": (
        "keeper_ppo_truth",
        "the same PPO keeper trained on true observations only (1 M steps, ssl-2012 actuation "
        "latency), to be evaluated on perceived ones"),
    "keeper-dagger-humanoid2012": (
        "keeper_dagger_humanoid2012",
        "humanoid keeper (humanoid-2012 with three team-mates) correcting the ball velocity "
        "the scripted keeper believes (ball-residual actions, 60 times a second) from its last "
        "8 perceived observations (kidsize-2012 head cameras, the kick tracker, belief "
        "features), trained by DAgger on the true velocity (3 rounds of 3,000 shots)"),
}


#: Baselines trained without stable-baselines3 (:mod:`agents.runs.imitation`'s DAgger): the
#: numpy policy is all that ships, with no ``.zip`` model or statistics beside it.
NUMPY_ONLY: frozenset[str] = frozenset({"keeper-dagger-humanoid2012"})


def baseline_path(name: str, kind: str = "npz") -> Path:
    """The file of baseline ``name``: ``kind="npz"`` (numpy policy), ``"zip"`` (the
    stable-baselines3 model) or ``"stats"`` (its ``VecNormalize`` statistics, an ``.npz``
    for :func:`agents.sb3.normalization.read_vecnormalize`); the baselines of
    :data:`NUMPY_ONLY` have the ``"npz"`` only."""
    if name not in BASELINES:
        raise ValueError(f"unknown baseline {name!r}; shipped: {sorted(BASELINES)}")
    if kind not in ("npz", "zip", "stats"):
        raise ValueError(f"kind must be 'npz', 'zip' or 'stats', got {kind!r}")
    if kind != "npz" and name in NUMPY_ONLY:
        raise ValueError(f"baseline {name!r} was trained without stable-baselines3 and ships "
                         "as a numpy policy only: kind must be 'npz'")
    stem = BASELINES[name][0]
    return _HERE / (f"{stem}_vecnormalize.npz" if kind == "stats" else f"{stem}.{kind}")


def load_baseline(name: str) -> NumpyPolicy:
    """The shipped policy ``name`` (see :data:`BASELINES`), ready to call on observations of
    the plain Goalkeeper-v0 (it returns the native 6-number command)."""
    return NumpyPolicy.load(baseline_path(name))


def baseline_env_kwargs(name: str, evaluation: bool = True) -> dict[str, Any]:
    """The Goalkeeper-v0 keyword arguments baseline ``name`` was trained with; with
    ``evaluation`` the reward shaping (a training aid) is left out."""
    kwargs = dict(load_baseline(name).meta["env_kwargs"])
    if evaluation:
        kwargs.pop("shaping", None)
    return kwargs


def make_baseline_env(name: str, **overrides: Any):
    """``gymnasium.make("soccer_env/Goalkeeper-v0", ...)`` with the arguments baseline
    ``name`` was trained with (no shaping), updated by ``overrides`` (e.g.
    ``obs_mode="perceived"`` for the truth-trained keeper)."""
    import gymnasium as gym

    import soccer_env  # noqa: F401

    return gym.make(GOALKEEPER_ID, **{**baseline_env_kwargs(name), **overrides})
