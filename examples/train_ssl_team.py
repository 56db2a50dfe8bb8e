"""Train the shipped SSL match team: 2 vs 2, PPO with parameter sharing, a correction to the
scripted team, self-play against a pool of past copies and the scripted team.

    python examples/train_ssl_team.py --out runs/ssl-team          # the shipped team's run
    python examples/train_ssl_team.py --setting perceived-game --out runs/ssl-team-perceived \
        --init agents/baselines/ssl_team_2v2.npz               # from the truth-trained team
    python examples/train_ssl_team.py --setting humanoid-game --out runs/humanoid-team
    python examples/train_ssl_team.py --tiny                       # seconds: what CI runs

``--setting truth`` (the default) trains on true observations under the simple referee;
``--setting perceived-game`` trains on what each team's ``ssl-2012`` cameras and filters
give it (its own robots predicted through the commands it sent, as SSL teams do to bridge
the vision's delay), under the SSL game flow (stops, ball placements, free kicks, fouls and
cards): each side perceives through its own pipeline, the matches run one by one in each worker (the
batched match plays the simple referee only), the correction applies in open play only (the
scripted team plays the restarts, :mod:`agents.scripted.residual`), and the idle team joins
the scripted team in the league from the start, so that the team learns to score past a
keeper that stands still as well as past one that moves (``--no-idle``: it does not).
``--setting humanoid-game`` trains a humanoid team the same way: 2 vs 2 ``humanoid-2012``
robots, each team on its own ``kidsize-2012`` head cameras with team fusion, under the laws'
game flow, the correction applied to the scripted humanoid team
(:class:`~agents.scripted.HumanoidTeam`).

Every blue robot of every match is one entry of stable-baselines3's batch
(:func:`agents.vec.factories.make_match_vec_env`, the matches stepped as one batch in each of two
worker processes), so one policy plays both robots, whichever role it takes. The robots act
through the ``"team-residual"`` map (:mod:`agents.scripted.residual`): the learner's action is a
correction to the scripted team's command from the same observation, so training starts from
a team that already plays, and the exploration noise starts small (``log_std_init=-2``: a
standard deviation of 0.14 on each command entry).

Opponents: the scripted team (and the fixed members of the league) for the first
``--warmup`` steps; then, every ``--copy-every`` steps, a frozen copy of the learner joins a
pool of the last ``--pool`` copies, and each match, when it restarts, draws its yellow team
from the copies, the fixed members and the scripted team, the scripted team as often as all
the others together.

``--init FILE`` starts the learner from a team file instead of a zero correction: the
truth-trained team, whose observation lacks the game block's referee entries, starts with
zero weights on them (:func:`agents.sb3.warm_start.load_actor`), so it plays as it did until
training moves them; its network is held for the first ``--freeze-actor`` steps while the
fresh critic learns its value (:class:`agents.sb3.warm_start.FreezeActor`), and the team as it
started (written to ``OUT/start_team.npz``) joins the league's fixed members.
``--hold-statistics`` keeps the observation statistics of the team's own entries as the file
has them (:class:`agents.sb3.warm_start.HeldRunningMeanStd`): by default they follow the new
setting's observations, which changes what the network computes from the same observation.

Under the game flow the map plays the scripted command at every restart, whatever the
correction; those steps' advantages are zeroed before each update
(:class:`agents.sb3.masking.IgnoredActions`, PPO's ``normalize_advantage`` off: the callback
normalises the rest), so that only open play moves the policy (``--keep-ignored``: as
before, every step).

Rewards: +1 for a goal scored, -1 for a goal conceded (shared by the team), and
``ball_progress`` shaping of 0.2 per metre the ball moves towards the opponent goal
(zero-sum). Matches of 30 s at 30 commands a second.

Each copy is written to ``OUT/checkpoints/team_<steps>.npz`` (a numpy policy with the map and
the observation statistics: arrays only), and the last one to ``OUT/final_team.npz``; with
``--eval N`` each copy also plays N seeded matches against the scripted team
(:func:`agents.studies.matches.head_to_head`), and the line is printed and appended to
``OUT/progress.jsonl``.
"""

from __future__ import annotations

import argparse
import json
import os
import shlex
import sys
import time
from pathlib import Path
from typing import Any

import torch
from stable_baselines3 import PPO
from stable_baselines3.common.vec_env import VecNormalize

import soccer_env
from agents.policies.numpy_policy import NumpyPolicy
from agents.sb3.masking import IgnoredActions
from agents.sb3.policies import numpy_copy
from agents.sb3.warm_start import FreezeActor, load_actor
from agents.scripted import team_residual_params
from agents.studies.matches import Side, head_to_head
from agents.vec.factories import make_match_vec_env
from agents.vec.self_play import SelfPlayCallback
from agents.vec.team_residual import TeamResidualVecEnv

#: The training match: 2 vs 2 SSL robots, Division B, truth observations, the simple referee.
TRAIN_KWARGS: dict[str, Any] = {"blue": 2, "yellow": 2, "match_duration": 30.0,
                                "control_dt": 1.0 / 30.0, "shaping": {"ball_progress": 0.2}}
#: The match the copies are evaluated in (and the shipped team's figures measured in).
EVAL_KWARGS: dict[str, Any] = {"blue": 2, "yellow": 2, "match_duration": 60.0,
                               "control_dt": 1.0 / 30.0}
#: What ``--setting perceived-game`` adds to both: each team's ``ssl-2012`` cameras and
#: filters, the ball tracked by the kick-aware tracker (``ball_filter="kick"``: under
#: ``ssl-2012`` the default EKF errs by about 60 mm on a ball at rest and loses matches to raw
#: detections, docs/results/ablation.md; the attackers that line up behind where they
#: believe the ball is circle it), its own robots predicted through the commands it sent
#: (``robot_prediction``), the SSL game flow (Division B rules).
PERCEIVED_GAME: dict[str, Any] = {"obs_mode": "perceived",
                                  "perception": {"vision": "ssl-2012", "ball_filter": "kick",
                                                 "robot_prediction": "commands"},
                                  "game": True}
#: What ``--setting humanoid-game`` trains instead: 2 vs 2 ``humanoid-2012`` robots, each team
#: perceiving through its head cameras (``kidsize-2012``, team fusion), the laws' game flow.
HUMANOID_GAME: dict[str, Any] = {"robot": "humanoid-2012", "obs_mode": "perceived",
                                 "perception": {"camera": "kidsize-2012"}, "game": True}
#: The settings of ``--setting``: what each adds to the training match (the robots and the
#: game flow go to the evaluation match too; the observation mode and the perception to
#: both sides of it).
SETTINGS: dict[str, dict[str, Any]] = {"truth": {}, "perceived-game": PERCEIVED_GAME,
                                       "humanoid-game": HUMANOID_GAME}
#: PPO's settings.
PPO_KWARGS: dict[str, Any] = {"n_steps": 128, "batch_size": 4096, "n_epochs": 5,
                              "gamma": 0.995, "learning_rate": 3e-4, "ent_coef": 0.0,
                              "policy_kwargs": {"net_arch": [128, 128], "log_std_init": -2.0}}


class PoolSelfPlay(SelfPlayCallback):
    """:class:`~agents.vec.self_play.SelfPlayCallback` whose pool keeps the scripted team beside
    the copies (as often as all of them together), after ``warmup`` steps against the scripted
    team alone; each copy saved as a numpy policy file and, with ``eval_matches``, played
    against the scripted team."""

    def __init__(self, out: Path, update_every: int, pool_size: int, warmup: int,
                 eval_matches: int, workers: int, league: list[str] | None = None,
                 eval_kwargs: dict[str, Any] | None = None, obs_mode: str = "truth",
                 perception: dict[str, Any] | None = None) -> None:
        super().__init__(update_every=update_every, pool_size=pool_size, copy_at_start=False)
        self.out = out
        self.warmup = int(warmup)
        self.eval_matches = int(eval_matches)
        self.workers = int(workers)
        #: The fixed members of the league besides the copies (the scripted team counts as
        #: many times as there are copies).
        self.league = list(league or [])
        self.eval_kwargs = dict(EVAL_KWARGS if eval_kwargs is None else eval_kwargs)
        self.obs_mode, self.perception = obs_mode, perception
        self.t0 = time.perf_counter()

    def _on_step(self) -> bool:
        if self.num_timesteps < self.warmup:
            self._last_update = self.num_timesteps
            return True
        return super()._on_step()

    def update_opponent(self) -> None:
        copy = self.snapshot()
        self.pool.append(copy)
        self._venv.set_opponent_pool(["scripted"] * (len(self.pool) + len(self.league))
                                     + self.league
                                     + list(self.pool))
        self.n_updates += 1
        path = copy.save(self.out / "checkpoints" / f"team_{self.num_timesteps}.npz")
        line: dict[str, Any] = {"steps": int(self.num_timesteps),
                                "seconds": round(time.perf_counter() - self.t0, 1),
                                "checkpoint": path.name}
        if self.eval_matches:
            h = head_to_head(Side(str(path), self.obs_mode, self.perception),
                             Side("scripted", self.obs_mode, self.perception),
                             self.eval_matches, start_seed=10_000, env_kwargs=self.eval_kwargs,
                             workers=self.workers)
            gd = h.goal_difference()
            line.update(wins=h.wins, draws=h.draws, losses=h.losses,
                        goals_for=h.goals_for, goals_against=h.goals_against,
                        goal_difference=round(gd[0], 3))
        print(json.dumps(line), flush=True)
        with open(self.out / "progress.jsonl", "a") as f:
            f.write(json.dumps(line) + "\n")


def init_team(path: str, params: dict[str, Any]) -> NumpyPolicy:
    """The team of ``--init``: a ``team-residual`` numpy team whose observation is the start of
    the training match's (``params``, the map's parameters in the training match)."""
    team = NumpyPolicy.load(path)
    kind = (team.action_map or {}).get("kind")
    if kind != "team-residual":
        raise SystemExit(f"--init must be a team-residual team file, got a {kind!r} policy "
                         f"({path})")
    names, ours = list(team.action_map["params"]["names"]), list(params["names"])
    if ours[:len(names)] != names:
        raise SystemExit(f"--init {path}: its observation is not the start of the training "
                         "match's")
    return team


def start_from(model: PPO, norm: VecNormalize, team: NumpyPolicy, params: dict[str, Any],
               hold: bool = False) -> NumpyPolicy:
    """Set the learner's actor and observation statistics to ``team``'s (the game block's
    referee entries, which a team trained without the game flow lacks, start with zero
    weights: :func:`agents.sb3.warm_start.load_actor`), and return the learner's copy: the
    team as it plays the training match, for the league. ``hold``: the team's observation
    statistics stay as they are while training runs."""
    load_actor(model, team, norm, hold=hold)
    return numpy_copy(model, {"init": team.meta.get("command", "")}, norm,
                      action_map={"kind": "team-residual", "params": params})


def parse_args(argv: list[str] | None) -> argparse.Namespace:
    """The command line's arguments."""
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--tiny", action="store_true",
                   default=os.environ.get("SOCCER_EXAMPLES_TINY") == "1",
                   help="4 matches of 1 s, a few hundred steps (what the tests run)")
    p.add_argument("--out", default="runs/ssl-team", help="run folder (default runs/ssl-team)")
    p.add_argument("--steps", type=int, default=60_000_000,
                   help="agent steps (default 60,000,000)")
    p.add_argument("--matches", type=int, default=256, help="matches stepped at once (256)")
    p.add_argument("--workers", type=int, default=2, help="worker processes (2)")
    p.add_argument("--warmup", type=int, default=10_000_000,
                   help="steps against the scripted team alone (10,000,000)")
    p.add_argument("--copy-every", type=int, default=5_000_000,
                   help="steps between copies of the learner (5,000,000)")
    p.add_argument("--pool", type=int, default=4, help="copies kept in the pool (4)")
    p.add_argument("--eval", type=int, default=40,
                   help="matches each copy plays against the scripted team (40; 0: none)")
    p.add_argument("--seed", type=int, default=0, help="seed of the matches and of PPO (0)")
    p.add_argument("--init", default=None,
                   help="a numpy team file to start the learner from (e.g. the shipped "
                        "truth-trained team); it also joins the league")
    p.add_argument("--freeze-actor", type=int, default=None,
                   help="with --init: steps for which the network's actor is held while the "
                        "critic learns (default 1,000,000)")
    p.add_argument("--hold-statistics", action="store_true",
                   help="with --init: keep the team's observation statistics as the file has "
                        "them (default: they follow the training's observations)")
    p.add_argument("--learning-rate", type=float, default=PPO_KWARGS["learning_rate"],
                   help="PPO's learning rate (3e-4)")
    p.add_argument("--clip-range", type=float, default=0.2,
                   help="PPO's clip range (0.2; smaller keeps each update nearer the team "
                        "it starts from)")
    p.add_argument("--no-idle", action="store_true",
                   help="leave the idle team out of the perceived settings' league")
    p.add_argument("--keep-ignored", action="store_true",
                   help="under the game flow, let the steps whose correction the map ignored "
                        "(restarts) into the policy's update, as before (default: zeroed)")
    p.add_argument("--setting", choices=list(SETTINGS), default="truth",
                   help="truth observations and the simple referee; each team's ssl-2012 "
                        "perception and the SSL game flow; or humanoids on their head "
                        "cameras under the laws' game flow (default: truth)")
    return p.parse_args(argv)


def main(argv: list[str] | None = None) -> int:
    args = parse_args(argv)
    torch.set_num_threads(1)
    train, ppo = dict(TRAIN_KWARGS), dict(PPO_KWARGS)
    eval_kwargs = dict(EVAL_KWARGS)
    setting = SETTINGS[args.setting]
    perceived = args.setting != "truth"
    obs_mode, perception = setting.get("obs_mode", "truth"), setting.get("perception")
    train.update(setting)
    eval_kwargs.update({k: setting[k] for k in ("robot", "game") if k in setting})
    if args.tiny:
        train["match_duration"] = 1.0
        args.matches, args.steps, args.warmup, args.copy_every, args.eval = 4, 512, 128, 128, 2
        ppo.update(n_steps=16, batch_size=64, n_epochs=1)
    out = Path(args.out)
    (out / "checkpoints").mkdir(parents=True, exist_ok=True)
    env = soccer_env.parallel_env(**train)
    params = team_residual_params(env, "blue")
    env.close()
    init = init_team(args.init, params) if args.init else None
    venv = make_match_vec_env(train, n_matches=args.matches, learner="blue",
                              opponent="scripted", seed=args.seed, workers=args.workers,
                              batched=not perceived)
    league: list[Any] = ["idle"] if perceived and not args.no_idle else []
    ppo.update(learning_rate=args.learning_rate, clip_range=args.clip_range)
    callbacks: list[Any] = []
    if train.get("game") and not args.keep_ignored:
        ppo["normalize_advantage"] = False
        callbacks.append(IgnoredActions())
    norm = VecNormalize(TeamResidualVecEnv(venv, params), gamma=ppo["gamma"])
    model = PPO("MlpPolicy", norm, seed=args.seed, verbose=0, **ppo)
    if init is not None:
        league.append(start_from(model, norm, init, params, args.hold_statistics))
        league[-1].save(out / "start_team.npz")  # the team as it starts, in the league
        freeze = 1_000_000 if args.freeze_actor is None else args.freeze_actor
        callbacks.append(FreezeActor(128 if args.tiny else freeze))
    if league:
        venv.set_opponent_pool(["scripted"] * len(league) + league)
    callback = PoolSelfPlay(out, args.copy_every, args.pool, args.warmup, args.eval,
                            args.workers, league, eval_kwargs, obs_mode, perception)
    t0 = time.perf_counter()
    model.learn(args.steps, callback=[*callbacks, callback])
    minutes = (time.perf_counter() - t0) / 60
    final = callback.snapshot()
    command = "python examples/train_ssl_team.py " + shlex.join(
        sys.argv[1:] if argv is None else argv)
    final.meta.update(steps=int(model.num_timesteps), minutes=round(minutes, 1),
                      command=command.strip(), train_kwargs=train, eval_kwargs=eval_kwargs,
                      ppo=ppo)
    path = final.save(out / "final_team.npz")
    norm.close()
    print(f"trained {model.num_timesteps:,} agent steps in {minutes:.1f} min; "
          f"{callback.n_updates} copies; the team: {path}")
    h = head_to_head(Side(str(path), obs_mode, perception),
                     Side("scripted", obs_mode, perception), args.eval or 2,
                     start_seed=20_000, env_kwargs=eval_kwargs, workers=args.workers)
    print(h.summary())
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
