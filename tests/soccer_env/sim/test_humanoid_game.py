"""The Humanoid League game flow (soccer_env.sim.humanoid_game), each law on a constructed
situation: frames of ball and robots made by hand, not by the physics, so that each test shows
the rule alone."""

import math

import numpy as np
import pytest

from soccer_env import presets
from soccer_env.presets.rules import RULES, HumanoidRuleSpec, RuleSpec, rules
from soccer_env.sim.game import Frame
from soccer_env.sim.humanoid_game import HumanoidGameController
from soccer_env.sim.world import BallExit

FIELD = presets.field("humanoid-kid")  # 9 x 6 m, centre circle radius 0.75 m
BALL = presets.ball("kidsize")
R = 0.1
DT = 0.02
HX, HY = FIELD.half_length, FIELD.half_width
INSET = 0.025
START = np.array([[-4.0, 0.0, 0, 0, 0, 0], [-2.0, 1.5, 0, 0, 0, 0],
                  [4.0, 0.0, np.pi, 0, 0, 0], [2.0, -1.5, np.pi, 0, 0, 0]])


class Game:
    """A controller and a hand-made world: blue 0 (keeper) and 1, yellow 2 (keeper) and 3, far
    from the ball and from each other. It does what the decisions ask, as an environment
    would."""

    def __init__(self, duration: float = 1200.0):
        self.gc = HumanoidGameController(FIELD, BALL, [0, 0, 1, 1], [R] * 4,
                                         rules("humanoid-2025-kid"), duration,
                                         np.random.default_rng(0))
        self.t = 0.0
        self.robots = START.copy()
        self.ball = np.zeros(6)
        self.events: list[str] = []
        self.decisions = []

    def step(self, touched=(), exit=None, dt=DT):
        self.t += dt
        d = self.gc.step(Frame(self.t, self.ball.copy(), self.robots.copy(),
                               [i in touched for i in range(4)], exit))
        self.events += [e.kind for e in d.events]
        self.decisions.append(d)
        if d.line_up is not None:
            self.robots[:] = START
            self.ball[:] = 0.0
        if d.place_ball is not None:
            self.ball[:] = 0.0
            self.ball[0:2] = d.place_ball
        for i in d.send_off:
            self.robots[i, 0:2] = (3.0 * (i - 1.5), -HY - 0.5)
        for i in d.bring_on:
            self.robots[i, 0:2] = START[i, 0:2]
        if d.clear is not None:
            keep, team = d.clear
            for i in range(4):
                if team >= 0 and i // 2 == team:
                    continue
                v = self.robots[i, 0:2] - self.ball[0:2]
                dist = math.hypot(*v)
                if dist < keep:
                    self.robots[i, 0:2] = self.ball[0:2] + v / dist * keep
        return d

    def run(self, seconds: float, **kw):
        return [self.step(**kw) for _ in range(int(round(seconds / DT)))]

    def kick(self, robot: int, to=(0.1, 0.0)):
        """Robot ``robot`` touches the ball, which moves to ``to``."""
        self.ball[0:2] = to
        return self.step(touched=(robot,))

    def roll(self, to):
        """The ball rolls to ``to``, nobody touching it."""
        self.ball[0:2] = to
        return self.step()

    def exit(self, x, y, z=0.0, touched=()):
        """The ball has left the field at ``(x, y, z)``."""
        self.ball[0:3] = (x, y, z)
        return self.step(touched=touched, exit=BallExit(x, y, z, self.t))

    def kick_off(self, team: int = 0):
        """Start the match and play the kick-off: the kicker and a team-mate touch the ball."""
        self.gc.start(team)
        self.kick(1 if team == 0 else 3, to=(0.1, 0.0))
        assert self.gc.in_play
        self.kick(0 if team == 0 else 2, to=(0.2, 0.0))

    def throw_in_for_blue(self, x: float = 1.0):
        """Yellow touches the ball last and it leaves over the touch line at ``(x, HY)``."""
        self.kick(3, to=(x, HY - 0.2))
        return self.exit(x, HY + 0.1)


# ----------------------------------------------------------------------------------------
# Presets
# ----------------------------------------------------------------------------------------


def test_the_humanoid_preset_holds_the_2025_kidsize_numbers():
    spec = RULES["humanoid-2025-kid"]
    assert isinstance(spec, HumanoidRuleSpec) and not isinstance(spec, RuleSpec)
    assert spec.kind == "humanoid" and "Humanoid League Laws of the Game 2025" in spec.source
    assert (spec.half_duration, spec.ball_in_play_distance, spec.in_play_time,
            spec.opponent_distance, spec.removal_time, spec.dropped_ball_time,
            spec.dropped_ball_distance, spec.line_inset) == (600.0, 0.05, 10.0, 0.75, 10.0,
                                                             120.0, 0.05, 0.025)
    assert rules("humanoid-2025-kid", removal_time=30.0).removal_time == 30.0
    with pytest.raises(ValueError, match="opponent_distance"):
        rules("humanoid-2025-kid", opponent_distance=-1.0)
    with pytest.raises(ValueError, match="kind"):
        HumanoidRuleSpec(name="x", kind="ssl")
    assert presets.HumanoidRuleSpec is HumanoidRuleSpec


def test_the_controller_takes_humanoid_rules_and_a_positive_duration():
    with pytest.raises(TypeError, match="HumanoidRuleSpec"):
        HumanoidGameController(FIELD, BALL, [0, 1], [R, R], RULES["ssl-2025-div-b"], 60.0,
                               np.random.default_rng(0))
    with pytest.raises(ValueError, match="duration"):
        HumanoidGameController(FIELD, BALL, [0, 1], [R, R], RULES["humanoid-2025-kid"], 0.0,
                               np.random.default_rng(0))
    g = Game()
    assert g.gc.situation() == ("stop", -1) and not g.gc.clock_running
    with pytest.raises(RuntimeError, match="start"):
        g.step()


# ----------------------------------------------------------------------------------------
# Kick-off (Law 8)
# ----------------------------------------------------------------------------------------


def test_kick_off_starts_playing_and_the_ball_is_in_play_once_it_moved_5_cm():
    g = Game()
    d = g.gc.start(1)
    assert d.line_up is None  # the simulation lined the teams up before the start
    assert (g.gc.command, g.gc.command_team, g.gc.stage) == ("normal_start", 1, "first_half")
    assert g.gc.situation() == ("kickoff", 1) and g.gc.restart_team == 1
    assert g.gc.designated == (0.0, 0.0) and g.gc.next_command is None
    assert g.gc.keepers == [0, 2] and g.gc.clock_running
    g.kick(3, to=(-0.04, 0.0))  # less than 5 cm: not yet in play
    assert not g.gc.in_play and g.gc.situation() == ("kickoff", 1)
    g.kick(3, to=(-0.06, 0.0))
    assert g.gc.in_play and g.gc.situation() == ("running", -1) and g.gc.restart_team == -1
    assert g.gc.command == "normal_start"


def test_kick_off_ball_is_in_play_ten_seconds_after_the_signal():
    g = Game()
    g.gc.start(0)
    g.run(9.9)
    assert not g.gc.in_play
    g.run(0.2)
    assert g.gc.in_play


def test_an_opponent_entering_the_centre_circle_before_the_kick_off_is_removed_for_ten_s():
    g = Game()
    g.gc.start(0)
    g.robots[2, 0:2] = (0.86, 0.0)  # its footprint 0.76 m from the centre: outside
    g.robots[1, 0:2] = (-0.3, 0.0)  # the kicking team may enter the circle
    g.step()
    assert g.events == []
    g.robots[3, 0:2] = (0.5, 0.3)  # footprint inside the circle
    d = g.step()
    assert d.send_off == [3] and g.events == ["defender_too_close_to_kick_point"]
    assert (d.events[0].team, d.events[0].robot) == (1, 3)
    info = g.gc.team_info[1]
    assert info.fouls == 1 and info.off == [3] and g.gc.robots_allowed(1) == 1
    assert g.gc.robots_allowed(0) == 2
    back = [d for d in g.run(9.9) if d.bring_on]
    assert back == [] and info.off == [3]
    back = [d.bring_on for d in g.run(0.2) if d.bring_on]
    assert back == [[3]] and info.off == [] and g.gc.robots_allowed(1) == 2
    assert info.fouls == 1


def test_entering_the_circle_after_the_kick_off_ball_is_in_play_is_no_foul():
    g = Game()
    g.kick_off(0)
    g.robots[3, 0:2] = (0.3, 0.3)
    g.step()
    assert g.events == [] and g.gc.team_info[1].off == []


def test_no_goal_directly_from_the_kick_off_the_opponents_get_a_goal_kick():
    g = Game()
    g.gc.start(0)
    g.kick(1, to=(0.3, 0.0))
    assert g.gc.in_play and g.gc.indirect
    g.roll((2.0, 0.1))  # out of the circle, untouched
    d = g.exit(HX + 0.1, 0.3)
    assert d.exit_kind == "goal" and d.scorer == -1 and "invalid_goal" in g.events
    assert g.gc.team_info[0].goals == 0
    assert (g.gc.command, g.gc.command_team, g.gc.restart_kind) == ("direct_free", 1,
                                                                   "goal_kick")
    assert d.place_ball == pytest.approx((0.0, HY - INSET))  # Law 16: halfway line, that side
    assert d.clear == pytest.approx((0.75 + R, 1))


def test_a_kick_off_goal_counts_after_another_players_touch():
    for second in (0, 2):  # a team-mate or an opponent
        g = Game()
        g.gc.start(0)
        g.kick(1, to=(0.3, 0.0))
        g.kick(second, to=(0.5, 0.0))
        assert not g.gc.indirect
        d = g.exit(HX + 0.1, 0.0)
        assert d.scorer == 0 and g.gc.team_info[0].goals == 1 and "goal" in g.events
        # The team that conceded kicks off.
        assert d.line_up == ("kickoff", 1)
        assert (g.gc.command, g.gc.command_team, g.gc.situation()) == ("normal_start", 1,
                                                                       ("kickoff", 1))


def test_a_kick_off_goal_counts_when_the_kicker_plays_the_ball_again_outside_the_circle():
    g = Game()
    g.gc.start(0)
    g.kick(1, to=(0.3, 0.0))
    g.kick(1, to=(0.6, 0.0))  # still inside the circle: the restriction stays
    assert g.gc.indirect
    g.kick(1, to=(0.9, 0.0))  # the ball left the circle during this step
    assert g.gc.indirect
    g.kick(1, to=(1.2, 0.0))  # a touch after it left the circle
    assert not g.gc.indirect
    assert g.exit(HX + 0.1, 0.0).scorer == 0


# ----------------------------------------------------------------------------------------
# Goals (Law 10) and halves (Law 7)
# ----------------------------------------------------------------------------------------


def test_a_goal_in_open_play_counts_and_the_conceding_team_kicks_off():
    g = Game()
    g.kick_off(1)
    g.kick(3, to=(-3.0, 0.5))
    d = g.exit(-HX - 0.1, 0.5)
    assert d.scorer == 1 and g.gc.team_info[1].goals == 1 and d.line_up == ("kickoff", 0)
    d = g.exit(-HX - 0.1, 0.5, z=1.5)  # over the crossbar, not a goal
    assert d.exit_kind == "over_bar" and d.scorer == -1


def test_halves_the_clock_never_stops_and_the_second_half_kick_off_is_the_other_teams():
    g = Game(duration=100.0)
    g.gc.start(1)
    assert g.gc.stage_time_left == 50.0 and g.gc.playing_time_left == 100.0
    assert g.gc.stage_duration == 50.0
    g.run(1.0)
    assert g.gc.stage_time_left == pytest.approx(49.0)
    g.kick(3, to=(-0.2, 0.0))
    g.throw_in_for_blue()  # a game interruption: the clock runs on
    g.run(1.0)
    assert g.gc.stage_time_left == pytest.approx(50.0 - 1.0 - 3 * DT - 1.0)
    decisions = g.run(50.0)
    changed = [d for d in decisions if any(e.kind == "stage_changed" for e in d.events)]
    assert len(changed) == 1 and changed[0].line_up == ("kickoff", 0)
    assert g.gc.stage == "second_half"
    assert (g.gc.command, g.gc.command_team, g.gc.restart_kind) == ("normal_start", 0,
                                                                   "kickoff")
    assert g.gc.playing_time_left == pytest.approx(g.gc.stage_time_left)
    decisions = g.run(50.0)
    over = [k for k, d in enumerate(decisions) if d.over]
    assert over and g.gc.stage == "post_game" and g.gc.command == "stop"
    assert g.gc.playing_time_left == 0.0 and g.gc.situation() == ("stop", -1)
    assert not g.gc.clock_running and g.step().over


def test_second_half_kick_off_is_lined_up_even_during_a_game_interruption():
    g = Game(duration=20.0)
    g.gc.start(0)
    g.run(9.5)
    g.kick(1, to=(0.1, 0.0))
    g.throw_in_for_blue()
    d = [d for d in g.run(1.0) if d.line_up is not None]
    assert d and d[0].line_up == ("kickoff", 1)
    assert g.gc.situation() == ("kickoff", 1) and g.gc.restart_kind == "kickoff"


# ----------------------------------------------------------------------------------------
# Dropped ball (Law 8)
# ----------------------------------------------------------------------------------------


def test_dropped_ball_after_two_minutes_without_the_ball_moving_5_cm_not_before():
    g = Game()
    g.kick_off(0)
    g.kick(0, to=(1.0, 1.0))
    for k in range(int(round(119.8 / DT))):  # the ball jiggles by 2 cm
        g.ball[0] = 1.0 + 0.02 * (k % 2)
        g.step()
    assert "drop_ball" not in g.events
    d = g.run(0.3)
    drop = [x for x in d if any(e.kind == "drop_ball" for e in x.events)]
    assert len(drop) == 1
    assert drop[0].place_ball == (0.0, 0.0)
    assert drop[0].clear == pytest.approx((FIELD.center_circle_radius + R, -1))
    assert (g.gc.command, g.gc.command_team, g.gc.in_play) == ("force_start", -1, True)
    assert g.gc.situation() == ("running", -1) and g.gc.restart_kind == "drop_ball"


def test_the_ball_moving_5_cm_restarts_the_dropped_ball_timer():
    g = Game()
    g.kick_off(0)
    g.run(100.0)
    g.roll((0.26, 0.0))  # 6 cm: progress
    g.run(119.0)
    assert "drop_ball" not in g.events
    g.run(1.1)
    assert "drop_ball" in g.events


def test_a_goal_may_be_scored_directly_from_a_dropped_ball():
    g = Game()
    g.kick_off(0)
    g.run(120.1)
    assert g.gc.restart_kind == "drop_ball" and not g.gc.indirect
    g.kick(1, to=(1.0, 0.0))
    assert g.exit(HX + 0.1, 0.0).scorer == 0


# ----------------------------------------------------------------------------------------
# Throw-in (Law 15)
# ----------------------------------------------------------------------------------------


def test_throw_in_for_the_team_that_did_not_touch_last_on_the_touch_line_where_it_left():
    g = Game()
    g.kick_off(0)
    d = g.throw_in_for_blue(1.0)
    assert d.exit_kind == "touch" and "ball_left_field_touch_line" in g.events
    assert d.place_ball == pytest.approx((1.0, HY - INSET))
    assert d.clear == pytest.approx((0.75 + R, 0))
    assert (g.gc.command, g.gc.command_team, g.gc.restart_kind) == ("direct_free", 0,
                                                                   "throw_in")
    assert g.gc.situation() == ("free_kick", 0) and g.gc.designated == d.place_ball
    assert g.gc.indirect and not g.gc.in_play
    # Near a corner the ball stays on the touch line, inside the goal line.
    g.kick(1, to=(4.0, -2.9))
    d = g.exit(HX + 0.05, -HY - 0.1)
    assert d.place_ball == pytest.approx((HX - INSET, -(HY - INSET)))
    assert g.gc.command_team == 1


def test_throw_in_ball_is_in_play_after_5_cm_or_10_s():
    g = Game()
    g.kick_off(0)
    g.throw_in_for_blue(1.0)
    g.run(9.9)
    assert not g.gc.in_play
    g.run(0.2)
    assert g.gc.in_play and g.gc.situation() == ("running", -1)
    g.throw_in_for_blue(-1.0)
    g.kick(1, to=(-1.0, HY - INSET - 0.06))
    assert g.gc.in_play


def test_no_goal_directly_from_a_throw_in():
    g = Game()
    g.kick_off(0)
    g.throw_in_for_blue(3.5)
    g.kick(1, to=(3.6, 2.5))
    d = g.exit(HX + 0.1, 0.5)
    assert d.scorer == -1 and "invalid_goal" in g.events
    assert (g.gc.restart_kind, g.gc.command_team) == ("goal_kick", 1)
    assert d.place_ball == pytest.approx((0.0, HY - INSET))


def test_a_goal_after_a_throw_in_counts_after_a_second_touch():
    g = Game()
    g.kick_off(0)
    g.throw_in_for_blue(3.5)
    g.kick(1, to=(3.6, 2.5))
    g.kick(0, to=(4.0, 1.0))  # another player
    assert not g.gc.indirect
    assert g.exit(HX + 0.1, 0.5).scorer == 0
    # The thrower playing the ball again once it is in play (Law 13) also lifts it.
    g = Game()
    g.kick_off(0)
    g.throw_in_for_blue(3.5)
    g.kick(1, to=(3.6, 2.5))
    assert g.gc.in_play and g.gc.indirect
    g.kick(1, to=(4.0, 1.0))
    assert not g.gc.indirect and g.exit(HX + 0.1, 0.5).scorer == 0


def test_a_throw_in_directly_into_the_throwers_own_goal_gives_a_corner_kick():
    g = Game()
    g.kick_off(0)
    g.throw_in_for_blue(-3.5)
    g.kick(1, to=(-3.6, 2.5))
    d = g.exit(-HX - 0.1, 0.5)
    assert d.scorer == -1 and "invalid_goal" in g.events and g.gc.team_info[1].goals == 0
    assert (g.gc.restart_kind, g.gc.command_team) == ("corner_kick", 1)
    assert d.place_ball == pytest.approx((-(HX - INSET), HY - INSET))


def test_an_opponent_nearer_than_75_cm_before_a_throw_in_is_in_play_is_removed():
    g = Game()
    g.kick_off(0)
    g.throw_in_for_blue(1.0)
    bx, by = 1.0, HY - INSET
    g.robots[3, 0:2] = (bx + 0.76, by)  # 0.76 m between the centres: allowed
    g.robots[1, 0:2] = (bx + 0.3, by)  # the thrower's team may come near
    g.step()
    assert g.events[-1] != "defender_too_close_to_kick_point"
    g.robots[3, 0:2] = (bx + 0.5, by - 0.5)  # 0.71 m
    d = g.step()
    assert d.send_off == [3] and g.events[-1] == "defender_too_close_to_kick_point"
    assert g.gc.team_info[1].fouls == 1 and g.gc.team_info[1].off == [3]
    assert g.gc.team_info[0].fouls == 0
    back = [d.bring_on for d in g.run(10.1) if d.bring_on]
    assert back == [[3]] and g.gc.team_info[1].off == []


def test_nobody_touched_the_ball_out_the_team_defending_that_half_restarts():
    g = Game()
    g.kick_off(0)
    g.throw_in_for_blue(1.0)
    g.run(10.1)  # in play by time, untouched
    d = g.exit(2.0, -HY - 0.1)
    assert d.place_ball == pytest.approx((2.0, -(HY - INSET))) and g.gc.command_team == 1


# ----------------------------------------------------------------------------------------
# Goal kick (Law 16) and corner kick (Law 17)
# ----------------------------------------------------------------------------------------


def test_goal_kick_on_the_touch_line_at_the_halfway_line_for_the_defenders():
    g = Game()
    g.kick_off(0)
    g.kick(3, to=(-4.0, 2.0))  # yellow attacks -x
    d = g.exit(-HX - 0.1, 2.0)
    assert d.exit_kind == "goal_line" and "ball_left_field_goal_line" in g.events
    assert (g.gc.restart_kind, g.gc.command, g.gc.command_team) == ("goal_kick", "direct_free",
                                                                   0)
    assert d.place_ball == pytest.approx((0.0, HY - INSET)) and d.clear[1] == 0
    assert not g.gc.indirect
    # Over the crossbar, on the other side: a goal kick on that side.
    g.kick(1, to=(4.0, -0.5))
    d = g.exit(HX + 0.1, -0.5, z=1.5)
    assert g.gc.command_team == 1 and d.place_ball == pytest.approx((0.0, -(HY - INSET)))


def test_a_goal_may_be_scored_directly_from_a_goal_kick():
    g = Game()
    g.kick_off(0)
    g.kick(3, to=(-4.0, 2.0))
    g.exit(-HX - 0.1, 2.0)
    g.kick(1, to=(0.3, HY - 0.2))
    assert g.exit(HX + 0.1, 0.0).scorer == 0


def test_corner_kick_at_the_corner_for_the_attackers():
    g = Game()
    g.kick_off(0)
    g.kick(0, to=(-4.0, -2.0))  # blue, defending x < 0, touched last
    d = g.exit(-HX - 0.1, -2.0)
    assert (g.gc.restart_kind, g.gc.command_team) == ("corner_kick", 1)
    assert d.place_ball == pytest.approx((-(HX - INSET), -(HY - INSET)))
    assert d.clear == pytest.approx((0.75 + R, 1))
    assert g.gc.situation() == ("free_kick", 1)
    g.robots[0, 0:2] = (-(HX - INSET) + 0.5, -(HY - INSET))
    d = g.step()
    assert d.send_off == [0]  # the keeper too must keep its distance
    g.kick(3, to=(-4.0, -0.5))  # straight into the goal from the corner kick: counts
    assert g.exit(-HX - 0.1, -0.5).scorer == 1
