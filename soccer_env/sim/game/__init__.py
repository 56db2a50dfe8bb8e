"""The SSL game flow: the referee commands, stages, fouls and cards of the RoboCup Small Size
League rules, 2025 edition (https://robocup-ssl.github.io/ssl-rules/2025/sslrules.html; the
numbers in :data:`soccer_env.presets.RULES`, section numbers below are the rule book's).

:class:`GameController` plays the SSL game controller and its automatic referees on the truth:
each control step it reads a :class:`Frame` (the ball, the robots and which robots touched the
ball during the step) and returns a :class:`Decision`: the game events of the step (named as
the SSL game controller names them), whether a goal counts, and what the simulation must do
for the referee (place the ball, line the teams up, take a robot off the field or bring it
back). It never touches the physics itself, so each rule is tested on constructed frames.

The package, module by module:

* :mod:`~soccer_env.sim.game.types`: commands, stages, :class:`Frame`, :class:`Decision`,
  :class:`GameEvent`, :class:`TeamInfo`, :class:`GameOptions` and :func:`game_config`
  (shared with the humanoid flow, :mod:`soccer_env.sim.humanoid_game`);
* :mod:`~soccer_env.sim.game.geometry`: the defense areas, valid free-kick positions,
  penalty marks and distances the rules measure;
* :mod:`~soccer_env.sim.game.state`: :class:`RefereeState`, what both controllers keep and
  the steps they share;
* :mod:`~soccer_env.sim.game.fouls`: the fouls and cards;
* :mod:`~soccer_env.sim.game.restarts`: stop, ball placement and the restarts until the
  ball is in play;
* :mod:`~soccer_env.sim.game.controller`: :class:`GameController`, its clock, stages and the
  ball in play.

Commands (what a team's software receives, :data:`COMMANDS`): ``stop``, ``ball_placement``
(by a team), ``prepare_kickoff``, ``prepare_penalty``, ``normal_start``, ``direct_free`` (for
a team) and ``force_start``. Halt is not used: the simulation has no emergencies.

The flow (5):

* **Kick-off** (5.3.2) at the start of each half and after a goal: the ball on the centre
  spot, both teams lined up in their halves by the simulation (the referee places the ball;
  the formation is the one :func:`~soccer_env.sim.referee.place_kickoff` builds, in which the
  robots' own software would have driven them), then ``normal_start``. The ball is in play
  once it has moved :attr:`~RuleSpec.ball_in_play_distance` or after
  :attr:`~RuleSpec.kickoff_time`.
* **Stop** (5.1.1) after the ball leaves the field, a foul that stops the game, or a goal:
  every robot must keep :attr:`~RuleSpec.stop_distance` from the ball and move slower than
  :attr:`~RuleSpec.stop_speed`.
* **Ball placement** (5.2) by the team that will bring the ball into play, when the ball is
  not already close to the designated position: it succeeds when the ball rests within
  :attr:`~RuleSpec.placement_tolerance` of it, no robot within
  :attr:`~RuleSpec.placement_clearance`, no earlier than :attr:`~RuleSpec.placement_min_time`
  and within :attr:`~RuleSpec.placement_time`. A failure gives the free kick to the other
  team, which must place in turn; if it fails too, the referee places the ball and the
  original command follows. A team that failed :attr:`~RuleSpec.max_placement_failures` times
  (net of successes) may not place for the rest of the half. With ``placement="referee"`` (or
  for a team that may not place) the referee places the ball at once.
* **Free kick** (5.3.3) for throw-ins, goal kicks, corner kicks (6), fouls and failed
  placements; after the ball went out, for the opponents of the team that touched it last,
  or if nobody touched it since the last restart, for the team defending the half (touch
  line) or the end (goal line) where it went out (the rules leave that case open; every
  referee of the package follows :func:`soccer_env.sim.referee.restart_team`). All free kicks
  are direct, as in the 2025 rules; with ``free_kicks="2019"`` the
  2019 edition's indirect free kick is played after throw-ins, double touches, aimless kicks
  and failed placements: a goal counts only if the ball touched a robot of the attacking team
  after it entered play (the 2019 rules, 5.3.4). The ball is in play once it has moved
  :attr:`~RuleSpec.ball_in_play_distance` or after :attr:`~RuleSpec.free_kick_time`.
* **Penalty kick** (5.3.5) after the multiple-defenders foul: the ball on the penalty mark,
  the keeper on its goal line and everybody else :attr:`~RuleSpec.penalty_behind` behind the
  ball (set by the simulation), then ``normal_start``. A goal counts; the game goes on with a
  goal kick for the defenders if the ball leaves the field elsewhere, moves away from the
  goal, is turned back by the keeper (its direction changed by 90 degrees or more) or is still
  in play after :attr:`~RuleSpec.penalty_time`.
* **Force start** (5.3.4) after no progress (8.1): both teams may play at once.
* **Stages** (4.4.1): two halves of ``duration / 2`` seconds of playing time (the clock runs
  only while a team may play the ball), the second started by the team that did not start
  the first; teams keep their ends (the simulated field is symmetric). The half-time break,
  timeouts, overtime and the shoot-out are not played. The match ends early when a team has
  10 goals and leads by more than one (4.4.3).

Fouls (8.4), each a game event against a team, every :attr:`~RuleSpec.fouls_per_card`-th of a
team giving it a yellow card: a yellow card takes one of its robots off the field for
:attr:`~RuleSpec.yellow_card_time` seconds of playing time, and a third running card is a red
card, for the rest of the match (5.5). The robot taken off is the team's highest-numbered
robot on the field other than its keeper (robot 0), and it comes back at the first stop after
its card expires. A team keeps at least one robot. Implemented:

* stopping fouls, then a free kick for the other team from where the ball was: a robot too
  close to the opponent defense area during stop or a free kick
  (``attacker_too_close_to_defense_area``), the ball kept in a defense area too long
  (``keeper_held_ball``), a double touch after a kick-off or free kick
  (``attacker_double_touched_ball``; 8.2);
* the multiple-defenders foul: a robot other than the keeper touching the ball while entirely
  inside its own defense area gives a penalty kick, without counting as a foul
  (``defender_in_defense_area``);
* non-stopping fouls: an attacker touching the ball while partly inside the opponent defense
  area (``attacker_touched_ball_in_defense_area``), a ball kicked faster than
  :attr:`~RuleSpec.ball_speed_limit` (``bot_kicked_ball_too_fast``), crashing
  (``bot_crash_unique``, ``bot_crash_drawn``);
* fouls while the ball is out of play: too close to the ball at an opponent kick-off or free
  kick (``defender_too_close_to_kick_point``), too fast during stop (``bot_too_fast_in_stop``),
  interfering with the opponent's ball placement (``bot_interfered_placement``);
* aimless kicks in Division B (6.2.3) and no progress (8.1).

Not implemented: pushing, ball holding, excessive dribbling, boundary crossing (the walls keep
the ball in), tipping over, robot substitutions beyond the cards', timeouts, and the
referee's discretion (unsporting behaviour, red cards for severe fouls).

Distances from a robot are from its nearest side (its centre minus its radius), as the rule book
measures them (2.1.3). Blue (team 0) defends the goal at ``x = -length / 2``. Keeper ids are
robot 0 of each team.
"""

from soccer_env.sim.game.controller import GameController
from soccer_env.sim.game.geometry import segment_distance
from soccer_env.sim.game.state import RefereeState
from soccer_env.sim.game.types import (
    COMMANDS,
    FOULS,
    FREE_KICK_RULES,
    GAME_KEYS,
    PLACEMENTS,
    SITUATIONS,
    STAGES,
    Decision,
    Frame,
    GameEvent,
    GameOptions,
    TeamInfo,
    game_config,
)

__all__ = ["GameController", "GameOptions", "Frame", "Decision", "GameEvent", "TeamInfo",
           "COMMANDS", "STAGES", "PLACEMENTS", "FREE_KICK_RULES", "FOULS", "SITUATIONS",
           "GAME_KEYS", "game_config", "RefereeState", "segment_distance"]
