"""Seeded matches between two sides, each side a team policy and what that team perceives.

A :class:`Side` is who plays a team (``"scripted"``, ``"idle"``, a numpy policy file shared by
the team's robots, or a callable) and how the team perceives (its observation mode and
perception options, the sensor preset included). :func:`head_to_head` plays ``matches``
seeded matches of :class:`~soccer_env.envs.match.SoccerParallelEnv` between sides ``a`` and
``b``, swapping colours every other match: match ``k`` is reset with seed ``start_seed + k //
2`` and ``a`` plays blue when ``k`` is even, so each seed (the kick-off formation, the kick-off
team, the sensors' noise) is played once from each side and a field or kick-off advantage
cancels. The estimator match ablation (:mod:`agents.studies.match_ablation`) and playing-strength
ratings are built on it.

Each match is one job; jobs run over worker processes and come back in job order, so every
number but the timings is the same for any number of workers.

What a :class:`HeadToHead` reports, from ``a``'s side:

* goals for and against; wins, draws and losses with Wilson's 95 % intervals of their rates;
* the goal difference per match with a 95 % interval, the unit being the seed (the mean of
  its two matches), so the interval is the paired one;
* each side's ball-belief error: the distance between what the team believes about the ball
  at present time (``info[agent]["estimate"]``, one belief per SSL team, one per humanoid) and
  the true ball, over every robot-step (mean and RMS, metres; 0 for a team that sees the
  truth).
"""

from __future__ import annotations

import math
import os
import time
from collections.abc import Callable, Iterator, Mapping, Sequence
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

import soccer_env
from agents.common.checks import check_full_infos
from agents.common.processes import map_jobs
from agents.common.stats import mean_interval, wilson
from agents.policies.numpy_policy import NumpyPolicy, widen
from agents.scripted import TEAMS, scripted_team, team_residual_params
from soccer_env.perception.base import OBS_MODES

__all__ = ["Side", "MatchRecord", "HeadToHead", "head_to_head", "match_jobs",
           "run_match_jobs", "play_match", "match_steps", "team_policy", "TEAM_POLICIES",
           "SIDE_KEYS", "DISCIPLINE", "checkpoint_sides"]

#: What a :class:`MatchRecord` counts per side under the game flow.
DISCIPLINE = ("fouls", "yellow_cards", "red_cards")
#: Team policies given by name (besides a ``.npz`` numpy policy file or a callable).
TEAM_POLICIES = ("scripted", "idle")
#: Environment keyword arguments a side sets for its team (refused in the shared ones).
SIDE_KEYS = ("obs_mode", "perception")

_POLICY_HELP = ("'scripted', 'idle', a numpy policy file (.npz) shared by the team's robots, "
                "or a callable batch policy obs (k, obs_dim) -> actions (k, 6)")


@dataclass(frozen=True)
class Side:
    """One team's set-up: who plays it and what it perceives.

    Attributes:
        policy: ``"scripted"`` (:class:`~agents.scripted.team.ScriptedTeam` for SSL robots,
            :class:`~agents.scripted.humanoid.HumanoidTeam` for humanoids), ``"idle"`` (zero
            actions), a numpy policy file (``.npz``, :class:`NumpyPolicy`:
            arrays only, nothing unpickled) acting for every robot of the team on its own
            observation, or a callable taking observations ``(k, obs_dim)`` and returning
            actions ``(k, 6)`` (it must pickle to run in worker processes).
        obs_mode: the team's observation mode (:data:`~soccer_env.perception.base.OBS_MODES`).
        perception: the team's perception options (:class:`~soccer_env.perception.base.
            PerceptionConfig` keys, the sensor preset included), or None for the defaults.
        label: the side's name in tables (default: the policy, and the observation mode
            unless it is ``"perceived"``).
    """

    policy: Any = "scripted"
    obs_mode: str = "perceived"
    perception: Mapping[str, Any] | None = None
    label: str = ""

    def __post_init__(self) -> None:
        p = self.policy
        if isinstance(p, os.PathLike):
            p = os.fspath(p)
            object.__setattr__(self, "policy", p)
        if isinstance(p, str):
            if p not in TEAM_POLICIES and not p.endswith(".npz"):
                raise ValueError(f"policy must be {_POLICY_HELP}; got {p!r}")
        elif not callable(p):
            raise ValueError(f"policy must be {_POLICY_HELP}; got {type(p).__name__}")
        if self.obs_mode not in OBS_MODES:
            raise ValueError(f"obs_mode must be one of {list(OBS_MODES)}, got "
                             f"{self.obs_mode!r}")
        if self.perception is not None:
            if not isinstance(self.perception, Mapping):
                raise ValueError(f"perception must be a mapping of perception options or None, "
                                 f"got {type(self.perception).__name__}")
            object.__setattr__(self, "perception", dict(self.perception))
        if not self.label:
            name = p if isinstance(p, str) else getattr(p, "__name__", type(p).__name__)
            if isinstance(p, str) and p.endswith(".npz"):
                name = Path(p).stem
            object.__setattr__(self, "label", name if self.obs_mode == "perceived"
                               else f"{name} ({self.obs_mode})")

    def to_dict(self) -> dict[str, Any]:
        policy = self.policy if isinstance(self.policy, str) else self.label
        return {"label": self.label, "policy": policy, "obs_mode": self.obs_mode,
                "perception": self.perception}


def checkpoint_sides(folder: str | os.PathLike, obs_mode: str = "perceived",
                     perception: Mapping[str, Any] | None = None) -> list[Side]:
    """The copies of a team that a training run saved in ``folder``, ``team_<steps>.npz``
    (as ``examples/train_ssl_team.py`` names them), oldest first, as sides on ``obs_mode`` and
    ``perception`` labelled ``copy at <steps / 1e6> M steps`` (none if the folder is
    missing)."""
    folder = Path(folder)
    if not folder.is_dir():
        return []

    def steps(path: Path) -> int:
        return int(path.stem.rsplit("_", 1)[1])

    return [Side(str(c), obs_mode, perception, label=f"copy at {steps(c) / 1e6:.0f} M steps")
            for c in sorted(folder.glob("team_*.npz"), key=steps)]


def match_env_kwargs(base: Mapping[str, Any] | None, blue: Side, yellow: Side
                     ) -> dict[str, Any]:
    """The match's keyword arguments: ``base`` (shared by both teams) with each side's
    observation mode and perception for its team."""
    base = dict(base or {})
    clash = sorted(set(SIDE_KEYS) & set(base))
    if clash:
        raise ValueError(f"env_kwargs must not set {clash}: each side sets them for its team")
    check_full_infos(base, "a head-to-head")
    return {**base, "obs_mode": {"blue": blue.obs_mode, "yellow": yellow.obs_mode},
            "perception": {"blue": blue.perception, "yellow": yellow.perception}}


def widened_team(policy: NumpyPolicy, env: Any, team: str) -> NumpyPolicy:
    """``policy`` as a team of the match ``env`` whose observation adds entries at the end of
    the one it was trained on (the game flow's game block: a team trained without the game
    flow), if it is a ``"team-residual"`` team whose observation's entry names begin the
    match's; otherwise ``policy`` itself. The added entries weigh nothing
    (:func:`agents.policies.numpy_policy.widen`) and the map takes the match's parameters, so
    under the game flow the scripted team plays the restarts, as for every team under it."""
    amap = policy.action_map or {}
    if amap.get("kind") != "team-residual" or type(policy) is not NumpyPolicy \
            or policy.frame_stack != 1:
        return policy
    old = dict(amap["params"])
    params = team_residual_params(env, team, residual=float(old.get("residual", 1.0)))
    names = list(old.get("names", []))
    if not names or params["names"][:len(names)] != names or len(params["names"]) == len(names):
        return policy
    return widen(policy, len(params["names"]), {"kind": "team-residual", "params": params})


def team_policy(policy: Any, env: Any, team: str
                ) -> Callable[[Mapping[str, np.ndarray]], dict[str, np.ndarray]]:
    """A function from the match's observations to the actions of ``team``'s live agents,
    playing ``policy`` (a :class:`Side` policy) in ``env``."""
    if team not in TEAMS:
        raise ValueError(f"team must be one of {list(TEAMS)}, got {team!r}")
    u = getattr(env, "unwrapped", env)
    agents = [a for a in u.possible_agents if a.startswith(f"{team}_")]
    if policy == "scripted":
        return scripted_team(u, team)
    if policy == "idle":
        zero = np.zeros(6, dtype=np.float32)
        return lambda obs: {a: zero for a in agents if a in obs}
    if isinstance(policy, str):
        policy = NumpyPolicy.load(policy)
        if policy.stateful:
            raise ValueError("a team policy with memory (recurrent or frame-stacked) is not "
                             "supported in head-to-head matches")
    size = getattr(policy, "obs_size", None)
    obs_dim = u.observation_space(agents[0]).shape[0]
    if isinstance(policy, NumpyPolicy) and size is not None and size < obs_dim:
        policy = widened_team(policy, u, team)
        size = policy.obs_size
    if size is not None and size != obs_dim:
        raise ValueError(f"the {team} team's policy takes observations of size {size}, the "
                         f"match gives {obs_dim}")

    def act(obs: Mapping[str, np.ndarray]) -> dict[str, np.ndarray]:
        live = [a for a in agents if a in obs]
        if not live:
            return {}
        out = np.asarray(policy(np.stack([obs[a] for a in live])), dtype=np.float32)
        if out.shape != (len(live), 6):
            raise ValueError(f"the {team} team's policy returned actions of shape {out.shape} "
                             f"for {len(live)} robots; expected ({len(live)}, 6)")
        return dict(zip(live, out))

    return act


@dataclass(frozen=True)
class MatchRecord:
    """One match of a head-to-head, from side ``a``'s point of view.

    Attributes:
        seed: the match's reset seed.
        a_blue: whether ``a`` played blue.
        goals_a, goals_b: the final score.
        steps: parallel steps played.
        err_sum, err_sq_sum, err_count: per side (``a``, ``b``), the sums of the ball-belief
            error [m] and of its square over the side's beliefs and steps, and how many.
        seconds: wall time of the match [s].
        fouls, yellow_cards, red_cards: per side (``a``, ``b``), the fouls the game flow
            called on it and the cards it was shown (0 without the game flow).
    """

    seed: int
    a_blue: bool
    goals_a: int
    goals_b: int
    steps: int
    err_sum: tuple[float, float]
    err_sq_sum: tuple[float, float]
    err_count: tuple[int, int]
    seconds: float
    fouls: tuple[int, int] = (0, 0)
    yellow_cards: tuple[int, int] = (0, 0)
    red_cards: tuple[int, int] = (0, 0)

    @property
    def goal_difference(self) -> int:
        return self.goals_a - self.goals_b


def match_steps(env: Any, blue: Side, yellow: Side, seed: int
                ) -> Iterator[dict[str, dict[str, Any]]]:
    """Play the match ``env`` (a parallel match made with :func:`match_env_kwargs` of the
    sides) from ``reset(seed=seed)`` to its end, ``blue`` and ``yellow`` each playing its
    team: the agents' infos after every step."""
    obs, _ = env.reset(seed=seed)
    teams = [team_policy(blue.policy, env, "blue"), team_policy(yellow.policy, env, "yellow")]
    while env.agents:
        actions: dict[str, np.ndarray] = {}
        for team in teams:
            actions.update(team(obs))
        obs, _, _, _, infos = env.step(actions)
        yield infos


def play_match(env_kwargs: Mapping[str, Any], blue: Side, yellow: Side, seed: int
               ) -> dict[str, Any]:
    """Play one match reset with ``seed``: blue's and yellow's goals, the steps, each
    team's ball-belief error sums, and under the game flow each team's fouls and cards (see
    :class:`MatchRecord`)."""
    t0 = time.perf_counter()
    env = soccer_env.parallel_env(**match_env_kwargs(env_kwargs, blue, yellow))
    try:
        members = [[a for a in env.possible_agents if a.startswith(p)]
                   for p in ("blue_", "yellow_")]
        err = [0.0, 0.0]
        sq = [0.0, 0.0]
        count = [0, 0]
        cards = {"yellow_card": [0, 0], "red_card": [0, 0]}
        steps = 0
        for infos in match_steps(env, blue, yellow, seed):
            steps += 1
            info = next(iter(infos.values()))
            for e in info["game"]["events"] if "game" in info else ():
                if e["kind"] in cards and e["team"] in TEAMS:
                    cards[e["kind"]][TEAMS.index(e["team"])] += 1
            bx, by = info["truth"]["ball_position"][:2]
            for t, names in enumerate(members):
                seen: set[int] = set()  # an SSL team's robots share one belief
                for a in names:
                    est = infos[a]["estimate"]
                    if id(est) in seen:
                        continue
                    seen.add(id(est))
                    ex, ey = est["ball_position"][:2]
                    e = math.hypot(float(ex) - float(bx), float(ey) - float(by))
                    err[t] += e
                    sq[t] += e * e
                    count[t] += 1
        score = info["score"]
        game = info.get("game")
        fouls = (0, 0) if game is None else (int(game["blue"]["fouls"]),
                                             int(game["yellow"]["fouls"]))
    finally:
        env.close()
    return {"goals": (int(score["blue"]), int(score["yellow"])), "steps": steps,
            "err_sum": tuple(err), "err_sq_sum": tuple(sq), "err_count": tuple(count),
            "seconds": time.perf_counter() - t0, "fouls": fouls,
            "yellow_cards": tuple(cards["yellow_card"]), "red_cards": tuple(cards["red_card"])}


def _play_job(job: tuple) -> dict[str, Any]:
    env_kwargs, a, b, seed, a_blue = job
    return play_match(env_kwargs, a if a_blue else b, b if a_blue else a, seed)


def match_jobs(a: Side, b: Side, matches: int, start_seed: int = 0,
               env_kwargs: Mapping[str, Any] | None = None) -> list[tuple]:
    """The jobs of a head-to-head: match ``k`` with seed ``start_seed + k // 2``, ``a`` blue
    when ``k`` is even."""
    if isinstance(matches, bool) or int(matches) != matches or matches < 1:
        raise ValueError(f"matches must be an integer >= 1, got {matches!r}")
    base = dict(env_kwargs or {})
    match_env_kwargs(base, a, b)  # checks the shared keyword arguments
    return [(base, a, b, int(start_seed) + k // 2, k % 2 == 0) for k in range(int(matches))]


def _record(job: tuple, out: Mapping[str, Any]) -> MatchRecord:
    """The match's outcome from ``a``'s point of view."""
    _, _, _, seed, a_blue = job
    i, j = (0, 1) if a_blue else (1, 0)
    return MatchRecord(seed, a_blue, out["goals"][i], out["goals"][j], out["steps"],
                       (out["err_sum"][i], out["err_sum"][j]),
                       (out["err_sq_sum"][i], out["err_sq_sum"][j]),
                       (out["err_count"][i], out["err_count"][j]), out["seconds"],
                       *((out[k][i], out[k][j]) for k in DISCIPLINE))


def run_match_jobs(jobs: Sequence[tuple], workers: int | None = None,
                   progress: Callable[[int, int], None] | None = None) -> list[MatchRecord]:
    """Every job's :class:`MatchRecord`, in job order, over ``workers`` processes (None: all
    cores; one: here). ``progress(done, total)`` is called after each match."""
    outs = map_jobs(_play_job, jobs, workers, progress)
    return [_record(job, out) for job, out in zip(jobs, outs)]


@dataclass
class HeadToHead:
    """The matches between sides ``a`` and ``b`` (see the module docstring), from ``a``'s
    side.

    Attributes:
        a: one side (the results are from its point of view).
        b: the other side.
        records: one per match, in match order.
        env_kwargs: the keyword arguments shared by both teams.
    """

    a: Side
    b: Side
    records: list[MatchRecord]
    env_kwargs: dict[str, Any] = field(default_factory=dict)

    @property
    def matches(self) -> int:
        return len(self.records)

    @property
    def wins(self) -> int:
        return sum(r.goals_a > r.goals_b for r in self.records)

    @property
    def draws(self) -> int:
        return sum(r.goals_a == r.goals_b for r in self.records)

    @property
    def losses(self) -> int:
        return sum(r.goals_a < r.goals_b for r in self.records)

    def rate(self, outcome: str) -> tuple[float, float, float]:
        """The share of ``"wins"``, ``"draws"`` or ``"losses"`` with its Wilson 95 %
        interval: ``(rate, low, high)``."""
        if outcome not in ("wins", "draws", "losses"):
            raise ValueError(f"outcome must be 'wins', 'draws' or 'losses', got {outcome!r}")
        k = getattr(self, outcome)
        return (k / self.matches, *wilson(k, self.matches))

    @property
    def goals_for(self) -> int:
        return sum(r.goals_a for r in self.records)

    @property
    def goals_against(self) -> int:
        return sum(r.goals_b for r in self.records)

    def goal_difference(self) -> tuple[float, float, float]:
        """Mean goal difference per match (``a`` minus ``b``) and its 95 % interval
        ``(mean, low, high)``: the mean over seeds of each seed's mean difference, with a
        Student-t interval over seeds (a seed played from both sides is one paired unit).
        With one seed the interval is unbounded."""
        by_seed: dict[int, list[int]] = {}
        for r in self.records:
            by_seed.setdefault(r.seed, []).append(r.goal_difference)
        return mean_interval([np.mean(v) for v in by_seed.values()])

    def ball_error(self, side: int) -> tuple[float, float]:
        """Side ``0`` (``a``) or ``1`` (``b``)'s ball-belief error: ``(mean, rms)`` [m]."""
        n = sum(r.err_count[side] for r in self.records)
        if n == 0:
            return math.nan, math.nan
        s = sum(r.err_sum[side] for r in self.records)
        sq = sum(r.err_sq_sum[side] for r in self.records)
        return s / n, math.sqrt(sq / n)

    def per_match(self, what: str, side: int) -> tuple[float, float, float]:
        """Side ``0`` (``a``) or ``1`` (``b``)'s ``"fouls"``, ``"yellow_cards"`` or
        ``"red_cards"`` per match: ``(mean, low, high)``, a Student-t 95 % interval over
        matches."""
        if what not in DISCIPLINE or side not in (0, 1):
            raise ValueError(f"what must be one of {list(DISCIPLINE)} and side 0 or 1, got "
                             f"{what!r} and {side!r}")
        return mean_interval([getattr(r, what)[side] for r in self.records])

    @property
    def steps(self) -> int:
        return sum(r.steps for r in self.records)

    @property
    def seconds(self) -> float:
        return sum(r.seconds for r in self.records)

    def summary(self) -> str:
        """One line: W/D/L, goals and the goal difference with its interval."""
        gd, lo, hi = self.goal_difference()
        return (f"{self.a.label} vs {self.b.label}: {self.wins} W {self.draws} D "
                f"{self.losses} L in {self.matches} matches, goals {self.goals_for}:"
                f"{self.goals_against}, goal difference per match {gd:+.2f} "
                f"(95 % CI {lo:+.2f} to {hi:+.2f})")

    def to_dict(self) -> dict[str, Any]:
        gd = self.goal_difference()
        return {
            "a": self.a.to_dict(), "b": self.b.to_dict(), "matches": self.matches,
            "wins": self.wins, "draws": self.draws, "losses": self.losses,
            **{f"{o}_rate": list(self.rate(o)) for o in ("wins", "draws", "losses")},
            "goals_for": self.goals_for, "goals_against": self.goals_against,
            "goal_difference": [x if math.isfinite(x) else None for x in gd],
            "ball_error_m": {"a": list(self.ball_error(0)), "b": list(self.ball_error(1))},
            **{f"{w}_per_match": {"a": list(self.per_match(w, 0)), "b": list(self.per_match(w, 1))}
               for w in DISCIPLINE},
            "steps": self.steps, "seconds": self.seconds,
            "records": [asdict(r) for r in self.records],
        }


def head_to_head(a: Side, b: Side, matches: int = 20, start_seed: int = 0,
                 env_kwargs: Mapping[str, Any] | None = None, workers: int | None = None,
                 progress: Callable[[int, int], None] | None = None) -> HeadToHead:
    """Play ``matches`` seeded matches between ``a`` and ``b`` (colours swapped every other
    match; see the module docstring).

    Args:
        a: one side (the results are from its point of view).
        b: the other side.
        matches: how many (>= 1); an even number plays every seed from both sides.
        start_seed: the first seed.
        env_kwargs: keyword arguments of :func:`soccer_env.parallel_env` shared by both teams
            (team sizes, robots, field, ``match_duration``, ...); not ``obs_mode`` or
            ``perception``, which each side sets for its team.
        workers: processes (None: all cores); the numbers do not depend on it.
        progress: called as ``progress(done, total)`` after each match.
    """
    jobs = match_jobs(a, b, matches, start_seed, env_kwargs)
    return HeadToHead(a, b, run_match_jobs(jobs, workers, progress), dict(env_kwargs or {}))
