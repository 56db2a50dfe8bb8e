"""Egocentric observations, built for all agents of a team with a handful of array operations.

Every agent's observation is a float32 vector laid out as below (``k`` team-mates other than
itself, ``m`` opponents). "Body frame" means rotated into the agent's heading (``+x`` forward,
``+y`` left); "team frame" is the field frame rotated so that the agent's team attacks ``+x``
(identity for blue, a half turn for yellow), so that one policy can play either side.

=================  ==========================================================================
entries            meaning
=================  ==========================================================================
self (7)           ``x, y`` [m] in the team frame; ``ax, ay``: the team's ``+x`` axis in the
                   body frame, i.e. ``(cos h, -sin h)`` for heading ``h`` in the team frame;
                   ``vx, vy`` [m/s] body frame; ``omega`` [rad/s]
ball (4)           position relative to self [m] and velocity [m/s], both body frame
mate_j (6 each)    relative position [m], ``cos, sin`` of the relative heading, velocity
                   [m/s], body frame; team-mates in index order, skipping self
opp_j (6 each)     the same for opponents, in index order
goals (8)          own goal's left and right post, then the opponent goal's left and right
                   post (left/right as seen from the centre spot facing the team's ``+x``),
                   relative position [m] in body frame
game (g)           task-specific game state (see each environment)
belief (11-16)     only with ``belief_features=True``: how sure the belief is (below)
=================  ==========================================================================

Belief features (:class:`~soccer_env.state.BeliefQuality`; names ``belief.*``):

=========================  ===================================================================
entries                    meaning
=========================  ===================================================================
``ball.sigma``             standard deviation of the believed ball position per axis [m]
``ball.velocity_sigma``    the same for its velocity [m/s]
``ball.age``               time since the capture of the latest ball measurement [s]
``ball.tracking``,         the ball track's state, one-hot (see
``ball.coasting``,         :data:`~soccer_env.state.BALL_STATUSES`): measured in the latest
``ball.reset``,            frame period; predicted only; (re)started fewer than 3
``ball.lost``              measurements ago; not seen for long (or never)
``self.sigma_xy``          spread of the agent's own believed position per axis [m]
``self.sigma_theta``       spread of its believed heading [rad]
``ball.measured_dx``,      the latest ball measurement (the vision's latest detection; a
``ball.measured_dy``       humanoid's own latest sighting) minus the believed ball, body frame
                           [m]: what the filter has not taken in (after a kick, the
                           detections run ahead of a track that still rejects or smooths
                           them); 0 with no measurement
``ball.fused_age``         (environments with humanoids) time since the latest fusion of the
                           team's sightings [s]
``ball.seen_by``           (environments with humanoids) robots whose sightings went into it
``ball.p_rest``,           (a ball filter with motion modes: ``ball_filter="imm"``) the
``ball.p_rolling``,        probabilities that the ball lies still, rolls under friction, or is
``ball.p_maneuver``        being kicked or bounced (:meth:`estimators.IMMBall.mode_probabilities`)
=========================  ===================================================================

Truth mode fills them with a perfect sensor's values (no spread, no age, tracking, every
team-mate seeing the ball, measurements on the belief); unknown spreads and ages read as their
bounds (:data:`SIGMA_BOUND`, :data:`BALL_SPEED_BOUND`, :data:`AGE_BOUND`, ``pi``).

Values are clipped to the observation space's bounds, which are wide enough that only
pathological states reach them. The builder reads a belief, never the world, so the same
code serves ``obs_mode="truth"`` and the perception stack.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
from gymnasium import spaces

from soccer_env.presets import FieldSpec
from soccer_env.state import BALL_STATUSES, Belief, WorldState

__all__ = ["ObservationBuilder", "ROBOT_SPEED_BOUND", "ROBOT_TURN_BOUND", "BALL_SPEED_BOUND",
           "SIGMA_BOUND", "AGE_BOUND", "BELIEF_FEATURES", "HUMANOID_BELIEF_FEATURES",
           "SLOT_PREFIX", "other_robots"]

#: Observation bound on robot speed components [m/s] (robots can be shoved beyond their drive).
ROBOT_SPEED_BOUND = 10.0
#: Observation bound on robot turn rate [rad/s].
ROBOT_TURN_BOUND = 50.0
#: Observation bound on ball speed components [m/s].
BALL_SPEED_BOUND = 20.0
#: Observation bound on a belief feature's position spread [m].
SIGMA_BOUND = 5.0
#: Observation bound on a belief feature's age [s].
AGE_BOUND = 5.0
#: Team names accepted by :meth:`ObservationBuilder.names_for`.
_TEAM_NAMES = {"blue": 0, "yellow": 1}

#: Names of the belief features (after ``belief.``).
BELIEF_FEATURES = ("ball.sigma", "ball.velocity_sigma", "ball.age",
                   *(f"ball.{s}" for s in BALL_STATUSES), "self.sigma_xy", "self.sigma_theta",
                   "ball.measured_dx", "ball.measured_dy")
#: The further belief features of environments with humanoids.
HUMANOID_BELIEF_FEATURES = ("ball.fused_age", "ball.seen_by")


#: The prefix of a game entry about one of an agent's other robots, ``game.slot<j>.<entry>``
#: for slot ``j`` (:func:`other_robots`); :meth:`ObservationBuilder.names_for` names it after
#: the slot, ``game.mate<j>.<entry>`` or ``game.opp<j>.<entry>``.
SLOT_PREFIX = "game.slot"


def other_robots(teams: Sequence[int]) -> list[list[int]]:
    """Each robot's other robots in the order of its observation's slots: its team-mates in
    robot order, then its opponents in robot order (``teams``: every robot's team)."""
    n = len(teams)
    return [[j for j in range(n) if teams[j] == teams[i] and j != i]
            + [j for j in range(n) if teams[j] != teams[i]] for i in range(n)]


class ObservationBuilder:
    """Builds the observations of the robots ``agents`` (of either team) in one pass.

    Args:
        field: field geometry (goal posts, bounds).
        teams: team of every robot of the belief (0 blue, 1 yellow), in robot order.
        agents: robot indices that get an observation, in the order of the output rows.
        game_low: lower bounds of the task's game-state entries.
        game_high: upper bounds of the task's game-state entries.
        game_names: names of the game-state entries.
        implementation: ``"auto"`` (plain Python for few agents seeing few robots, the linear
            map otherwise: see :meth:`build`), ``"python"`` or ``"arrays"``; all give the
            same observations.
        belief_features: append the belief features (see the module docstring): 11 entries,
            or 13 with ``humanoid``, and one per ``ball_modes``.
        humanoid: the environment has humanoids (their team fusion's two entries).
        team_size: the most robots a team has (the bound of ``ball.seen_by``; default from
            ``teams``).
        ball_modes: the ball filter's motion modes (with ``belief_features``: one more entry
            per mode, ``ball.p_<mode>``, its probability; the beliefs' quality must carry
            them).

    An agent's team-mates are the other robots of its team and its opponents those of the
    other team, both in robot order; every agent sees the other ``N - 1`` robots, so the rows
    have one length even when the teams differ in size (only the entry names differ, see
    :meth:`names_for`).
    """

    def __init__(
        self,
        field: FieldSpec,
        teams: Sequence[int],
        agents: Sequence[int],
        game_low: Sequence[float] = (),
        game_high: Sequence[float] = (),
        game_names: Sequence[str] = (),
        implementation: str = "auto",
        belief_features: bool = False,
        humanoid: bool = False,
        team_size: int | None = None,
        ball_modes: Sequence[str] = (),
    ) -> None:
        if implementation not in ("auto", "python", "arrays"):
            raise ValueError(f"implementation must be one of ['auto', 'python', 'arrays'], "
                             f"got {implementation!r}")
        self.implementation = implementation
        self.teams = [int(t) for t in teams]
        self.n_robots = len(self.teams)
        self.own = list(agents)
        self.signs = [1.0 if self.teams[i] == 0 else -1.0 for i in self.own]
        slots = other_robots(self.teams)
        self.others = [slots[i] for i in self.own]
        self.k = self.n_robots - 1
        self.game_size = len(game_names)
        hx, gw = field.half_length, 0.5 * field.goal_width
        # Posts in the team frame: own left, own right, opponent left, opponent right.
        self.posts_team = [(-hx, gw), (-hx, -gw), (hx, gw), (hx, -gw)]

        ox = field.half_length + field.boundary
        oy = field.half_width + field.boundary
        span = math.hypot(2 * ox, 2 * oy)
        rv, rw, bv = ROBOT_SPEED_BOUND, ROBOT_TURN_BOUND, BALL_SPEED_BOUND
        high = [ox, oy, 1, 1, rv, rv, rw, span, span, bv, bv]
        high += [span, span, 1, 1, rv, rv] * self.k + [span, span] * 4
        low = [-h for h in high] + list(game_low)
        high += list(game_high)
        self._game_names = tuple(game_names)
        self._base_size = len(high)
        self.belief_features = bool(belief_features)
        self._feature_names: tuple[str, ...] = ()
        self._n_modes = 0
        if self.belief_features:
            self._features_init(humanoid, team_size, span, tuple(ball_modes))
            low += list(self._feature_low)
            high += list(self._feature_high)
        self.size = len(high)
        self.low = np.asarray(low, dtype=np.float32)
        self.high = np.asarray(high, dtype=np.float32)
        self._compile()

    def _features_init(self, humanoid: bool, team_size: int | None, span: float,
                       modes: tuple[str, ...] = ()) -> None:
        """Names, bounds and the perfect sensor's values of the belief features (``span``:
        the bound of a measurement's offset from the belief [m]; ``modes``: the ball
        filter's motion modes)."""
        names = (BELIEF_FEATURES + (HUMANOID_BELIEF_FEATURES if humanoid else ())
                 + tuple(f"ball.p_{m}" for m in modes))
        self._feature_names = tuple(f"belief.{n}" for n in names)
        self._humanoid_features = humanoid
        if team_size is None:
            team_size = max(self.teams.count(0), self.teams.count(1))
        n_status = len(BALL_STATUSES)
        high = [SIGMA_BOUND, BALL_SPEED_BOUND, AGE_BOUND, *([1.0] * n_status), SIGMA_BOUND,
                math.pi, span, span]
        perfect = [0.0, 0.0, 0.0, 1.0, *([0.0] * (n_status - 1)), 0.0, 0.0, 0.0, 0.0]
        if humanoid:
            high += [AGE_BOUND, float(team_size)]
            perfect += [0.0, float(team_size)]
        # Mode probabilities exist only in a filter's belief (the truth's raise).
        self._n_modes = len(modes)
        high += [1.0] * len(modes)
        perfect += [math.nan] * len(modes)
        self._feature_high = np.asarray(high, dtype=np.float64)
        self._feature_low = np.zeros_like(self._feature_high)
        self._measured_at = BELIEF_FEATURES.index("ball.measured_dx")
        self._feature_low[self._measured_at:self._measured_at + 2] = -span
        self._perfect = np.tile(np.asarray(perfect, dtype=np.float32), (len(self.own), 1))

    def names_for(self, team: int | str) -> tuple[str, ...]:
        """Entry names of the observation of an agent of ``team``: 0 or ``"blue"``, 1 or
        ``"yellow"``; anything else raises ``ValueError``."""
        team = _TEAM_NAMES.get(team, team) if isinstance(team, str) else team
        if isinstance(team, bool) or team not in (0, 1):
            raise ValueError(f"team must be 0, 1, 'blue' or 'yellow', got {team!r}")
        n_mates = sum(1 for t in self.teams if t == team) - 1
        names = ["self.x", "self.y", "self.ax", "self.ay", "self.vx", "self.vy", "self.omega",
                 "ball.dx", "ball.dy", "ball.vx", "ball.vy"]
        for j in range(self.k):
            tag = f"mate{j}" if j < n_mates else f"opp{j - n_mates}"
            names += [f"{tag}.{e}" for e in ("dx", "dy", "cos", "sin", "vx", "vy")]
        for post in ("own_left", "own_right", "opp_left", "opp_right"):
            names += [f"goal.{post}.dx", f"goal.{post}.dy"]
        # The game flow's slot entries (game.slot<j>.on_field) named after the slots.
        game = [self._slot_name(name, n_mates) for name in self._game_names]
        return (*names, *game, *self._feature_names)

    @staticmethod
    def _slot_name(name: str, n_mates: int) -> str:
        """A game entry's name, ``game.slot<j>.<entry>`` named after slot ``j``: ``game.mate<j>.``
        or ``game.opp<j - n_mates>.``."""
        if not name.startswith(SLOT_PREFIX):
            return name
        j_text, entry = name[len(SLOT_PREFIX):].split(".", 1)
        j = int(j_text)
        tag = f"mate{j}" if j < n_mates else f"opp{j - n_mates}"
        return f"game.{tag}.{entry}"

    @property
    def names(self) -> tuple[str, ...]:
        """Entry names of the first agent's observation."""
        return self.names_for(self.teams[self.own[0]])

    def _compile(self) -> None:
        """Precompute the linear part of the observation.

        Writing a planar vector ``(x, y)`` as the complex number ``x + iy``, every vector of
        the observation except the relative headings is, before rotation into the body frame,
        a linear function of ``S = [robots.ravel(), ball, 1]``: relative positions are
        differences of positions, goal posts constants minus the own position, velocities
        copies, and the team's ``+x`` axis a constant. So the vectors of all agents are
        ``Z = L @ S`` for one complex matrix ``L`` of shape ``(n, V, 6 N + 7)``, and the
        rotation into agent ``i``'s body frame is the product of its rows with
        ``exp(-i theta_i)``. A few unrotated entries (own team-frame position, ``omega``) ride
        along as extra columns. The whole build is a dozen numpy calls whatever the team
        sizes, which matters at the step rates these environments run at.
        """
        n, k, nr = len(self.own), self.k, self.n_robots
        d = 6 * nr + 7
        one, ball = d - 1, 6 * nr
        # Rotated vectors: 0..k-1 others' positions, k ball, k+1..k+4 posts, k+5..2k+4 others'
        # velocities, 2k+5 ball velocity, 2k+6 own velocity, 2k+7 team +x axis. Then the
        # unrotated columns: 2k+8 own team-frame position, 2k+9 omega (+ 0i).
        n_rot = 2 * k + 8
        lin = np.zeros((n, n_rot + 2, d), dtype=np.complex128)

        def put(a: int, col: int, index: int, coef: complex = 1.0) -> None:
            """Add ``coef * (S[index] + i S[index + 1])`` to vector ``col`` of agent ``a``."""
            lin[a, col, index] += coef
            lin[a, col, index + 1] += 1j * coef

        for a, i in enumerate(self.own):
            for j, r in enumerate(self.others[a]):
                put(a, j, 6 * r)
                put(a, j, 6 * i, -1.0)
                put(a, k + 5 + j, 6 * r + 3)
            put(a, k, ball)
            put(a, k, 6 * i, -1.0)
            sign = self.signs[a]
            for p, (px, py) in enumerate(self.posts_team):
                lin[a, k + 1 + p, one] = sign * (px + 1j * py)  # field frame
                put(a, k + 1 + p, 6 * i, -1.0)
            put(a, 2 * k + 5, ball + 3)
            put(a, 2 * k + 6, 6 * i + 3)
            lin[a, 2 * k + 7, one] = sign
            put(a, 2 * k + 8, 6 * i, sign)
            lin[a, 2 * k + 9, 6 * i + 5] = 1.0
        # Single precision suffices (the observation is float32; positions of a few metres
        # keep micrometre resolution) and saves a cast. S is complex so that the product with
        # the complex L needs no cast either.
        self._lin = lin.astype(np.complex64)
        self._n_rot = n_rot
        self._s = np.zeros(d, dtype=np.complex64)
        self._s[one] = 1.0
        first = self.own[0]
        contiguous = self.own == list(range(first, first + n))
        self._own_index = slice(first, first + n) if contiguous else np.asarray(self.own)
        self._others_index = np.asarray(self.others, dtype=np.int64).reshape(n, k)

        # Columns of the float view [Z (2 (n_rot + 2)), relative headings (2 k), game (g)]
        # in output order.
        def z(v: int) -> list[int]:
            return [2 * v, 2 * v + 1]

        c_rel = 2 * (n_rot + 2)
        c_game = c_rel + 2 * k
        perm = [*z(2 * k + 8), *z(2 * k + 7), *z(2 * k + 6), 2 * (2 * k + 9), *z(k),
                *z(2 * k + 5)]
        for j in range(k):
            perm += [*z(j), c_rel + 2 * j, c_rel + 2 * j + 1, *z(k + 5 + j)]
        for p in range(4):
            perm += z(k + 1 + p)
        perm += list(range(c_game, c_game + self.game_size))
        assert len(perm) == self._base_size
        self._perm = np.asarray(perm, dtype=np.int64)
        # Few agents seeing few robots: plain Python beats numpy's per-call overhead.
        self._small = (n * (k + 2) <= 8 if self.implementation == "auto"
                       else self.implementation == "python")
        # The bounds of the entries before the belief features.
        self._base_low = self.low[: self._base_size]
        self._base_high = self.high[: self._base_size]
        self._low_list = self._base_low.tolist()
        self._high_list = self._base_high.tolist()

    @property
    def path(self) -> str:
        """The implementation :meth:`build` uses: ``"python"`` or ``"arrays"``."""
        return "python" if self._small else "arrays"

    def space(self) -> spaces.Box:
        """A fresh ``Box`` for one agent's observation."""
        return spaces.Box(self.low, self.high, dtype=np.float32)

    def build(self, belief: Belief, game: np.ndarray | None = None) -> np.ndarray:
        """Observations ``(len(own), size)`` float32 from ``belief``.

        Args:
            belief: field-frame ``ball`` (6,) and ``robots`` (N, 6).
            game: ``(len(own), game_size)`` game-state entries, or None if ``game_size`` is 0.

        Two implementations of the same layout: plain Python floats for few agents and few
        robots (a single keeper: about 5 microseconds against 12 for the array version, whose
        cost is the fixed overhead of a dozen numpy calls), and the linear-map version for
        teams (a 6 vs 6 match: about 30 microseconds for all twelve agents, against several
        times that in Python). ``tests/test_observations.py`` checks both against a direct
        reading of the documentation.
        """
        out = (self._build_python(belief, game) if self._small
               else self._build_arrays(belief, game))
        if self.belief_features:
            out = np.concatenate([out, self._features(belief)], axis=1)
        return out

    def build_batch(self, robots: np.ndarray, ball: np.ndarray,
                    game: np.ndarray | None = None) -> np.ndarray:
        """The observations of a batch of worlds at once: ``(B, len(own), size)`` float32.

        Args:
            robots: ``(B, N, 6)`` field-frame ``x, y, theta, vx, vy, omega`` of every robot
                of every world.
            ball: ``(B, 6)`` field-frame ball ``x, y, z, vx, vy, vz`` of every world.
            game: ``(B, len(own), game_size)`` game-state entries, or None if ``game_size``
                is 0.

        The same layout and the same arithmetic as the plain-Python build, in float64 numpy
        over the batch (a few dozen numpy calls whatever ``B``), then float32; belief
        features are a perfect sensor's (truth). Equal to :meth:`build` world by world up to
        the last bit of numpy's sine and cosine against the C library's.
        """
        robots = np.asarray(robots, dtype=np.float64)
        ball = np.asarray(ball, dtype=np.float64)
        n_worlds = robots.shape[0]
        if robots.shape[1:] != (self.n_robots, 6) or ball.shape != (n_worlds, 6):
            raise ValueError(f"robots must have shape (B, {self.n_robots}, 6) and ball (B, 6), "
                             f"got {robots.shape} and {ball.shape}")
        own = robots[:, self.own]  # (B, n, 6)
        x, y, th, vx, vy, om = (own[..., j] for j in range(6))
        c, s = np.cos(th), np.sin(th)
        sign = np.asarray(self.signs)
        bx, by = ball[:, 0:1], ball[:, 1:2]
        bvx, bvy = ball[:, 3:4], ball[:, 4:5]
        dx, dy = bx - x, by - y
        cols = [sign * x, sign * y, sign * c, -sign * s, c * vx + s * vy, c * vy - s * vx, om,
                c * dx + s * dy, c * dy - s * dx, c * bvx + s * bvy, c * bvy - s * bvx]
        if self.k:
            others = robots[:, self._others_index]  # (B, n, k, 6)
            c3, s3 = c[..., None], s[..., None]
            dx = others[..., 0] - x[..., None]
            dy = others[..., 1] - y[..., None]
            rel = others[..., 2] - th[..., None]
            block = np.stack([c3 * dx + s3 * dy, c3 * dy - s3 * dx, np.cos(rel), np.sin(rel),
                              c3 * others[..., 3] + s3 * others[..., 4],
                              c3 * others[..., 4] - s3 * others[..., 3]], axis=-1)
        for px, py in self.posts_team:
            dx, dy = sign * px - x, sign * py - y
            cols += [c * dx + s * dy, c * dy - s * dx]
        head = np.stack(cols[:11], axis=-1)
        parts = [head]
        if self.k:
            parts.append(block.reshape(n_worlds, len(self.own), 6 * self.k))
        parts.append(np.stack(cols[11:], axis=-1))
        if self.game_size:
            parts.append(np.asarray(game, dtype=np.float64))
        out = np.concatenate(parts, axis=-1)
        np.clip(out, self._base_low, self._base_high, out=out)
        out = out.astype(np.float32)
        if self.belief_features:
            perfect = np.broadcast_to(self._truth_features(), (n_worlds, *self._perfect.shape))
            out = np.concatenate([out, perfect], axis=-1)
        return out

    def _truth_features(self) -> np.ndarray:
        """The perfect sensor's belief features; ``ValueError`` with mode probabilities,
        which only a filter's belief has."""
        if self._n_modes:
            raise ValueError("the true state has no ball mode probabilities: build the "
                             "observations without ball_modes for obs_mode='truth'")
        return self._perfect

    def _features(self, belief: Belief | WorldState) -> np.ndarray:
        """The belief features ``(len(own), F)`` of ``belief`` (a perfect sensor's for the
        truth)."""
        if isinstance(belief, WorldState):
            return self._truth_features()
        q = belief.quality
        if q is None:
            raise ValueError("belief features need beliefs that carry their quality: build "
                             "the perception with features=True")
        common = [q.ball_sigma, q.ball_velocity_sigma, q.ball_age]
        common += [1.0 if k == q.ball_status else 0.0 for k in range(len(BALL_STATUSES))]
        rows = np.empty((len(self.own), len(self._feature_names)), dtype=np.float64)
        rows[:, 0:len(common)] = common
        rows[:, len(common):len(common) + 2] = q.pose_sigma[self.own]
        m = self._measured_at
        if q.ball_measured is None:
            rows[:, m:m + 2] = 0.0
        else:  # into each agent's body frame: (c dx + s dy, c dy - s dx)
            dx = float(q.ball_measured[0] - belief.ball[0])
            dy = float(q.ball_measured[1] - belief.ball[1])
            th = belief.robots[self.own, 2]
            c, s = np.cos(th), np.sin(th)
            rows[:, m] = c * dx + s * dy
            rows[:, m + 1] = c * dy - s * dx
        end = len(self._feature_names) - self._n_modes
        if self._humanoid_features:
            rows[:, end - 2] = q.fused_age
            rows[:, end - 1] = q.seen_by
        if self._n_modes:
            if q.ball_modes is None or len(q.ball_modes) != self._n_modes:
                raise ValueError(f"the belief features need the ball filter's "
                                 f"{self._n_modes} mode probabilities; the belief's quality "
                                 f"carries {q.ball_modes!r}")
            rows[:, end:] = q.ball_modes
        np.minimum(rows, self._feature_high, out=rows)
        np.maximum(rows, self._feature_low, out=rows)
        return rows.astype(np.float32)

    def _build_python(self, belief: Belief, game: np.ndarray | None) -> np.ndarray:
        robots = belief.robots.tolist()
        bx, by, _, bvx, bvy, _ = belief.ball.tolist()
        games = game.tolist() if self.game_size else None
        cos, sin = math.cos, math.sin
        low, high = self._low_list, self._high_list
        rows = []
        for a, i in enumerate(self.own):
            sign = self.signs[a]
            x, y, th, vx, vy, om = robots[i]
            c, s = cos(th), sin(th)
            dx, dy = bx - x, by - y
            out = [sign * x, sign * y, sign * c, -sign * s, c * vx + s * vy, c * vy - s * vx, om,
                   c * dx + s * dy, c * dy - s * dx, c * bvx + s * bvy, c * bvy - s * bvx]
            for j in self.others[a]:
                xj, yj, thj, vxj, vyj, _ = robots[j]
                dx, dy = xj - x, yj - y
                out += (c * dx + s * dy, c * dy - s * dx, cos(thj - th), sin(thj - th),
                        c * vxj + s * vyj, c * vyj - s * vxj)
            for px, py in self.posts_team:
                dx, dy = sign * px - x, sign * py - y
                out += (c * dx + s * dy, c * dy - s * dx)
            if games is not None:
                out += games[a]
            rows.append([lo if v < lo else (hi if v > hi else v)
                         for v, lo, hi in zip(out, low, high)])
        return np.array(rows, dtype=np.float32)

    def _build_arrays(self, belief: Belief, game: np.ndarray | None) -> np.ndarray:
        robots = belief.robots
        s = self._s
        s[: 6 * self.n_robots] = robots.ravel()
        s[6 * self.n_robots: -1] = belief.ball
        rot = np.exp(-1j * robots[self._own_index, 2:3]).astype(np.complex64)  # into body frame
        z = self._lin @ s
        z[:, : self._n_rot] *= rot
        parts = [z.view(np.float32)]
        if self.k:
            heading = np.exp(1j * robots[:, 2]).astype(np.complex64)
            parts.append((heading[self._others_index] * rot).view(np.float32))
        if self.game_size:
            parts.append(game.astype(np.float32))
        flat = np.concatenate(parts, axis=1) if len(parts) > 1 else parts[0]
        out = flat[:, self._perm]
        np.maximum(out, self._base_low, out=out)
        np.minimum(out, self._base_high, out=out)
        return out
