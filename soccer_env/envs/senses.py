"""What the batched environments keep beside their physics for each environment's perception,
command channels and head control (:class:`Senses`): what ``SoccerCore`` keeps for one
world, for the batched single-agent tasks (:mod:`soccer_env.envs.batched`) and the batched
matches (:mod:`soccer_env.envs.batched_match`) alike.

Perceived SSL observations run as one :class:`~soccer_env.perception.batched.
FilteredPerceptionBatch` where the configuration allows it
(:func:`~soccer_env.perception.batched.batch_refusal`), and the command channels of every
environment as one :class:`~soccer_env.sim.commands.CommandChannelBatch` per team unless the
latency and loss are drawn per episode; otherwise each environment keeps a single
environment's own :class:`~soccer_env.perception.match.MatchPerception` and
:class:`~soccer_env.sim.commands.CommandChannel` objects, fed with its world's state. Either
way each environment draws from its own sensor stream as a single environment does.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from soccer_env.perception.batched import FilteredPerceptionBatch, batch_refusal
from soccer_env.perception.match import MatchPerception
from soccer_env.sim.batch import WorldBatch
from soccer_env.sim.commands import CommandChannel, CommandChannelBatch
from soccer_env.sim.heads import HeadControl

__all__ = ["Senses"]


class Senses:
    """The perception, command channels and head control of ``n`` environments beside a
    :class:`~soccer_env.sim.batch.WorldBatch` (see the module docstring).

    Args:
        probe: a single environment built with the batch's arguments (its perception, channels
            and heads are the model).
        batch: the batch's physics.
        n: environments.

    Attributes:
        truth: truth observations (no sensors).
        plain: nothing to do at all (truth, no latency, no loss, no humanoids).
        vision: the batched perception, or None (each environment's own, in
            :attr:`perceptions`).
        perceptions: every environment's :class:`MatchPerception` (the probe's own, shared and
            unused, where :attr:`vision` runs them); absent when :attr:`plain`.
        seen: every environment's belief for its observation (robot 0's), when each
            environment perceives on its own.
        heads: every environment's head control (humanoids), or Nones.
        sensor_rngs: every environment's sensor stream (set by the environment at each
            episode's start).
    """

    def __init__(self, probe: Any, batch: WorldBatch, n: int) -> None:
        w0 = probe.world
        base = probe._perception
        self.batch = batch
        self.truth = probe.obs_mode == "truth"
        # Humanoids' heads follow their robots' attention, which the perception gives.
        self.plain = (self.truth and not any(base.delays) and not any(base.losses)
                      and not w0.humanoid_indices)
        self.reads_bodies = probe._reads_bodies
        self.heads: list[Any] = [None] * n
        self.sensor_rngs: list[np.random.Generator | None] = [None] * n
        self.seen: list[Any] = [None] * n
        self.vision: FilteredPerceptionBatch | None = None
        self._starting: list[int] = []  # environments whose batched perception starts
        self._stepped: np.ndarray | None = None  # and those whose update waits for flush
        self._team_channels: list[tuple[slice, int, CommandChannelBatch]] | None = None
        if not self.truth and batch_refusal(base, n) is None:
            self.vision = FilteredPerceptionBatch(base, n)
        if self.plain:
            return
        self.perceptions = ([base] * n if self.vision is not None else
                            [MatchPerception(probe.obs_mode, probe.perceptions, probe.field,
                                             probe.ball_spec, w0.robot_specs,
                                             w0.teams.tolist(), w0.names, w0.control_dt,
                                             probe.belief_features) for _ in range(n)])
        self._in_play = [(sl, t) for t, (sl, count) in
                         enumerate(zip(probe._slices, (w0.n_blue, w0.n_yellow))) if count]
        if not base._randomized:  # every environment's channels of a team as one batch
            self._team_channels = [
                (sl, t, CommandChannelBatch(n, probe._channels[t].n, base.delays[t],
                                            base.losses[t])) for sl, t in self._in_play]
        else:
            self._channels = [[CommandChannel(c.n, c.delay_steps, c.loss)
                               for c in probe._channels] for _ in range(n)]
        if probe._heads is not None:  # each environment's head control, as the probe's
            auto = probe._heads.robots
            self.heads = [HeadControl(w0.robot_specs, auto, [p.cameras[i].height for i in auto],
                                      probe.head) for p in self.perceptions]

    def body(self, k: int) -> Any:
        """Environment ``k``'s robots' bodies, if its perception reads them (humanoids)."""
        return self.batch.worlds[k].body_state() if self.reads_bodies else None

    def start(self, k: int) -> None:
        """Environment ``k``'s perception and command channels at the start of an episode
        (its world placed, its task begun, :attr:`sensor_rngs` set), as
        ``SoccerCore._start``. The batched perception starts with the others at the next
        :meth:`flush`; a channel draws nothing when it starts, so it may start first."""
        if self.plain:
            return
        rng = self.sensor_rngs[k]
        perception = self.perceptions[k]
        if self.vision is not None:
            self._starting.append(k)
        else:
            world = self.batch.worlds[k]
            self.seen[k] = perception.reset(world.snapshot(), rng, self.body(k))[0]
        if self._team_channels is not None:
            for _, _, channel in self._team_channels:
                channel.reset(k, rng)
            return
        for channel, delay, loss in zip(self._channels[k], perception.delays,
                                        perception.losses):
            channel.reset(rng, delay, loss)

    def send(self, commands: np.ndarray) -> np.ndarray:
        """Every environment's commands ``(n, N, 6)`` through its head control (humanoids)
        and its command channels; returns what the robots execute now."""
        if self.heads[0] is not None:  # each environment's heads, from its attention
            times = self.batch.times.tolist()
            for heads, p, c, now in zip(self.heads, self.perceptions, commands, times):
                heads.apply(c, now, p.attention)
        if self.plain:
            return commands
        if self.perceptions[0].driven:  # teams that predict their robots from their commands
            for p, c, now in zip(self.perceptions, commands, self.batch.times.tolist()):
                p.command(now, c)
        if self._team_channels is not None:
            commands = np.array(commands, dtype=np.float64)
            for sl, _, channel in self._team_channels:
                commands[:, sl] = channel.send(commands[:, sl])
            return commands
        return np.stack([np.concatenate([ch[t].send(c[sl]) for sl, t in self._in_play])
                         for ch, c in zip(self._channels, commands)])

    def update(self, rows: np.ndarray, defer: bool = False) -> None:
        """After a physics step: the perception of environments ``rows``. With ``defer``
        the batched perception waits for the next :meth:`flush`, to run in one pass with the
        episodes that start in between (when nothing reads the beliefs before)."""
        if self.vision is not None:
            if defer:
                self._stepped = rows
            else:
                self.vision.update(rows, *self.truth_arrays(rows))
            return
        if self.truth:
            return
        worlds = self.batch.worlds
        for k in rows.tolist():
            self.seen[k] = self.perceptions[k].update(worlds[k].snapshot(), self.body(k))[0]

    def flush(self) -> None:
        """The batched perception: advance the environments whose update was deferred and
        start those whose episodes began since the last flush (:meth:`start`), in one pass
        (the two never meet: an environment that starts over did not step)."""
        if self.vision is None:
            return
        stepped, self._stepped = self._stepped, None
        step = None if stepped is None else (stepped, *self.truth_arrays(stepped))
        start = None
        if self._starting:
            rows = np.array(self._starting, dtype=np.int64)
            self._starting = []
            start = (rows, *self.truth_arrays(rows), [self.sensor_rngs[k] for k in rows])
        self.vision.advance(step, start)

    def arrays(self) -> tuple[np.ndarray, np.ndarray] | None:
        """Every environment's world as its observation sees it, when that comes as arrays:
        ``(ball (n, 6), robots (n, N, 6))``, the truth (:attr:`truth`) or the batched
        perception's beliefs; None when each environment perceives on its own
        (:attr:`seen`)."""
        if self.truth:
            state = self.batch.state
            return state[:, 0], state[:, 1:]
        return None if self.vision is None else self.vision.beliefs()

    def present(self, robot: int = 0) -> tuple[np.ndarray, np.ndarray, np.ndarray] | None:
        """Robot ``robot``'s belief at the present time in every environment (what a single
        environment reports in ``info["estimate"]``): ``(times (n,) [s], ball (n, 6), robots
        (n, N, 6))``, as :meth:`arrays` lays them out; None in truth mode (the estimate is
        the truth)."""
        if self.truth:
            return None
        if self.vision is not None:
            return self.vision.present()
        beliefs = [p.current(robot) for p in self.perceptions]
        return (np.array([b.time for b in beliefs], dtype=np.float64),
                np.stack([b.ball for b in beliefs]), np.stack([b.robots for b in beliefs]))

    def truth_arrays(self, rows: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """``(times, balls (d, 3) x y z, robot poses (d, N, 3))`` of environments ``rows``,
        what the overhead cameras see."""
        batch = self.batch
        state = batch.state[rows]
        balls = state[:, 0, 0:3].copy()
        worlds = batch.worlds
        balls[:, 2] = [worlds[k]._z for k in rows.tolist()]
        return batch.times[rows], balls, state[:, 1:, 0:3]
