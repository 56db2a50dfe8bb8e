"""The SSL game flow (soccer_env.sim.game), each rule on a constructed situation: frames of
ball and robots made by hand, not by the physics, so that each test shows the rule alone."""

import math

import numpy as np
import pytest

from soccer_env import presets
from soccer_env.presets.rules import RULES, rules
from soccer_env.sim.game import Decision, Frame, GameController, GameOptions
from soccer_env.sim.world import BallExit

FIELD = presets.field("ssl-div-b")  # 9 x 6 m, defense areas 2 x 1 m
BALL = presets.ball("ssl")
R = 0.09
DT = 1.0 / 60.0
HX, HY = FIELD.half_length, FIELD.half_width


class Game:
    """A controller and a hand-made world: blue 0 (keeper) and 1, yellow 0 (keeper) and 1,
    far from the ball and from each other."""

    def __init__(self, duration: float = 600.0, rule: str = "ssl-2025-div-b", **options):
        self.teams = [0, 0, 1, 1]
        self.gc = GameController(FIELD, BALL, self.teams, [R] * 4, rules(rule),
                                 GameOptions(**options), duration, np.random.default_rng(0))
        self.t = 0.0
        self.robots = np.array([[-4.0, 0.0, 0, 0, 0, 0], [-2.0, 1.5, 0, 0, 0, 0],
                                [4.0, 0.0, np.pi, 0, 0, 0], [2.0, -1.5, np.pi, 0, 0, 0]])
        self.ball = np.zeros(6)
        self.events: list[str] = []

    def step(self, touched=(), exit=None, dt=DT):
        self.t += dt
        d = self.gc.step(Frame(self.t, self.ball.copy(), self.robots.copy(),
                               [i in touched for i in range(4)], exit))
        self.events += [e.kind for e in d.events]
        if d.place_ball is not None:
            self.ball[:] = 0.0
            self.ball[0:2] = d.place_ball
        return d

    def run(self, seconds: float, **kw):
        out = []
        for _ in range(int(round(seconds / DT))):
            out.append(self.step(**kw))
        return out

    def kick(self, robot: int, to=(0.1, 0.0), speed=(1.0, 0.0)):
        """Robot ``robot`` kicks the ball: it touches it and the ball moves."""
        self.ball[0:2] = to
        self.ball[3:5] = speed
        return self.step(touched=(robot,))

    def kick_off(self, team: int = 0):
        """Start the match and play the kick-off: the ball in play, and touched by the
        kicker's keeper after the kicker (so that the kicker may touch it again)."""
        self.gc.start(team)
        self.step()
        assert (self.gc.command, self.gc.command_team) == ("normal_start", team)
        self.kick(1 if team == 0 else 3)
        assert self.gc.in_play
        self.kick(0 if team == 0 else 2, to=(0.2, 0.0))

    def throw_in(self, x: float = 1.0):
        """Yellow touches the ball last and it leaves over the touch line at ``x``: blue's
        throw-in (a free kick) follows."""
        self.kick(3, to=(x, 2.5))
        return self.exit(x, HY + 0.03)

    def free_kick(self, x: float = 1.0):
        """Blue's throw-in at ``x`` placed by the referee, every robot away: blue's free kick
        is issued."""
        self.throw_in(x)
        self.keep_away()
        self.run(2.1)

    def exit(self, x, y, z=0.0):
        """The ball has left the field at ``(x, y)``."""
        self.ball[0:3] = (x, y, z)
        self.ball[3:5] = 0.0
        return self.step(exit=BallExit(x, y, z, self.t))

    def keep_away(self):
        """Every robot standing still, at least 1 m from the ball and 1.4 m from the defense
        areas."""
        spots = [(x, y) for x in (-2.0, 0.0, 2.0) for y in (-2.0, 0.0, 2.0)]
        spots = [p for p in spots if math.hypot(p[0] - self.ball[0], p[1] - self.ball[1]) >= 1.0]
        for i in range(4):
            self.robots[i, 0:2] = spots[i]
            self.robots[i, 3:6] = 0.0

    def play(self, seconds: float):
        """Open play: the ball rolls around the centre circle, nobody touches it."""
        for _ in range(int(round(seconds / DT))):
            a = self.t
            self.ball[0:2] = (0.8 * math.cos(a), 0.8 * math.sin(a))
            self.step()


def test_kick_off_starts_the_match_and_the_ball_enters_play_when_it_moves():
    g = Game()
    d = g.gc.start(1)
    assert (g.gc.command, g.gc.command_team, g.gc.stage) == ("prepare_kickoff", 1, "first_half")
    g.step()
    assert g.gc.command == "normal_start" and not g.gc.in_play
    g.ball[0] = -0.04  # less than 5 cm: not yet in play
    g.step(touched=(3,))
    assert not g.gc.in_play
    g.kick(3, to=(-0.06, 0.0))
    assert g.gc.in_play
    assert d.line_up is None  # the simulation lined the teams up before the start


def test_kick_off_ball_is_in_play_after_ten_seconds_untouched():
    g = Game()
    g.gc.start(0)
    g.run(9.9)
    assert not g.gc.in_play
    g.run(0.2)
    assert g.gc.in_play


def test_the_clock_stops_while_no_team_may_play_the_ball():
    g = Game(duration=100.0)
    g.gc.start(0)
    assert g.gc.stage_time_left == 50.0
    g.step()  # prepare -> normal start: the clock runs from here
    g.run(1.0)
    assert g.gc.stage_time_left == pytest.approx(49.0, abs=1e-9)
    g.kick(1)
    g.exit(1.0, HY + 0.03)  # stop: the clock stops
    left = g.gc.stage_time_left
    g.run(1.0)
    assert g.gc.command == "ball_placement" and g.gc.stage_time_left == left


def test_throw_in_is_placed_by_the_robots_of_the_team_that_did_not_touch_last():
    g = Game()
    g.kick_off(0)
    d = g.throw_in()  # yellow touches last
    assert "ball_left_field_touch_line" in g.events
    assert (g.gc.command, g.gc.command_team) == ("ball_placement", 0)
    assert g.gc.next_command == ("direct_free", 0)
    assert g.gc.designated == pytest.approx((1.0, HY - 0.2))
    assert d.place_ball is None
    # Blue's robot brings the ball there and backs off; it takes at least 2 s.
    g.ball[0:2] = (1.05, HY - 0.25)
    g.keep_away()
    g.step()
    assert g.gc.command == "ball_placement"
    g.run(2.0)
    assert "placement_succeeded" in g.events
    assert (g.gc.command, g.gc.command_team) == ("direct_free", 0)
    assert g.gc.team_info[0].placement_failures == 0


def test_failed_placement_passes_the_free_kick_then_the_referee_places():
    g = Game()
    g.kick_off(0)
    g.throw_in()
    g.keep_away()
    g.run(30.1)  # blue never moves the ball
    assert g.events.count("placement_failed") == 1
    assert (g.gc.command, g.gc.command_team) == ("ball_placement", 1)
    assert g.gc.next_command == ("direct_free", 1)
    assert g.gc.team_info[0].placement_failures == 1
    g.run(30.0)  # yellow fails too: the referee places and blue's free kick follows
    assert g.events.count("placement_failed") == 2
    assert g.gc.command == "stop" and g.gc.next_command == ("direct_free", 0)
    assert g.ball[0:2] == pytest.approx((1.0, HY - 0.2))
    g.run(2.1)
    assert (g.gc.command, g.gc.command_team) == ("direct_free", 0)


def test_a_team_with_five_failures_may_not_place_and_loses_throw_ins():
    g = Game()
    g.kick_off(0)
    g.gc.team_info[0].placement_failures = 4
    g.throw_in()
    g.keep_away()
    g.run(30.1)
    assert not g.gc.team_info[0].can_place
    g.run(30.0)
    g.run(2.1)
    g.kick(1, to=(1.0, 2.7))
    g.kick(3, to=(-1.0, 2.5))
    g.exit(-1.0, HY + 0.03)  # blue's throw-in, but blue may not place
    assert (g.gc.command, g.gc.command_team) == ("ball_placement", 1)
    assert g.gc.next_command == ("direct_free", 1)


def test_referee_placement_stops_until_every_robot_keeps_its_distance():
    g = Game(placement="referee")
    g.kick_off(0)
    d = g.throw_in()
    assert g.gc.command == "stop" and d.place_ball == pytest.approx((1.0, HY - 0.2))
    g.robots[1, 0:2] = (1.2, HY - 0.3)  # 0.13 m from the ball's surface
    g.run(5.0)
    assert g.gc.command == "stop"
    g.robots[1, 0:2] = (1.0, 1.5)
    g.step()
    assert (g.gc.command, g.gc.command_team) == ("direct_free", 0)


def test_goal_kick_and_corner_kick_spots():
    g = Game(placement="referee")
    g.kick_off(0)
    g.kick(1, to=(3.0, 1.0))  # blue touches last
    g.exit(HX + 0.03, 1.2)  # over yellow's goal line beside the goal
    assert g.gc.next_command == ("direct_free", 1)  # goal kick for yellow
    assert g.gc.designated == pytest.approx((HX - 1.0, HY - 0.2))
    g = Game(placement="referee", rule="ssl-2025-div-a")  # no aimless kicks in division A
    g.kick_off(0)
    g.kick(3, to=(3.0, -1.0))  # yellow touches its own goal line's ball
    g.exit(HX + 0.03, -1.2)
    assert g.gc.next_command == ("direct_free", 0)  # corner for blue
    assert g.gc.designated == pytest.approx((HX - 0.2, -(HY - 0.2)))


def test_aimless_kick_in_division_b():
    g = Game(placement="referee")
    g.kick_off(0)
    g.kick(1, to=(-1.0, 0.5))  # blue kicks from its own half
    g.ball[0] = 1.0
    g.step()  # across the halfway line, nobody touches it
    g.exit(HX + 0.03, 1.5)
    assert "aimless_kick" in g.events
    assert g.gc.next_command == ("direct_free", 1)
    assert g.gc.designated == pytest.approx((-1.0, 0.5))


def test_goal_then_kick_off_for_the_other_team():
    g = Game(placement="referee")
    g.kick_off(0)
    g.kick(1, to=(4.0, 0.1))
    d = g.exit(HX + 0.03, 0.1)
    assert d.scorer == 0 and d.exit_kind == "goal" and g.gc.team_info[0].goals == 1
    assert d.place_ball == (0.0, 0.0) and g.gc.next_command == ("prepare_kickoff", 1)
    g.keep_away()
    ups = [x.line_up for x in g.run(2.1)]
    assert ("kickoff", 1) in ups
    assert g.gc.command == "normal_start" and g.gc.command_team == 1


def test_a_chipped_goal_does_not_count():
    g = Game(placement="referee")
    g.kick_off(0)
    g.ball[2] = 0.3
    g.kick(1, to=(3.0, 0.0))  # chipped: 0.3 m high after blue's touch
    g.ball[2] = 0.0
    g.step()
    d = g.exit(HX + 0.03, 0.0)
    assert d.scorer == -1 and "invalid_goal" in g.events
    assert g.gc.next_command == ("direct_free", 1)  # as over the goal line: a goal kick


def test_multiple_defenders_gives_a_penalty_and_the_penalty_is_played():
    g = Game(placement="referee")
    g.kick_off(0)
    g.robots[1, 0:2] = (-4.2, 0.3)  # blue 1 (not the keeper) entirely in its defense area
    g.kick(1, to=(-3.9, 0.3))
    assert "defender_in_defense_area" in g.events
    assert g.gc.team_info[0].fouls == 0  # not counted as a foul
    assert g.gc.next_command == ("prepare_penalty", 1)
    g.keep_away()
    d = g.run(2.1)
    assert ("penalty", 1) in [x.line_up for x in d]
    mark = (-HX + 6.0, 0.0)  # yellow shoots at blue's goal, 6 m from it
    assert g.gc.designated == pytest.approx(mark)
    g.ball[0:2] = mark
    g.step()
    assert g.gc.command == "normal_start"
    g.kick(3, to=(mark[0] - 0.1, 0.0), speed=(-3.0, 0.0))
    assert g.gc.in_play
    d = g.exit(-HX - 0.03, 0.0)
    assert d.scorer == 1


def test_penalty_turned_back_by_the_keeper_ends_with_a_goal_kick():
    g = Game(placement="referee")
    g.kick_off(1)
    g.robots[3, 0:2] = (4.2, 0.3)
    g.kick(3, to=(3.9, 0.3))  # yellow's defender in its own area: penalty for blue
    g.keep_away()
    g.run(2.1)
    g.ball[0:2] = g.gc.designated
    g.step()
    g.kick(1, to=(g.ball[0] + 0.1, 0.0), speed=(3.0, 0.0))
    g.step()
    g.ball[3:5] = (-2.0, 0.0)
    g.step(touched=(2,))  # yellow's keeper turns it back
    assert "penalty_kick_failed" in g.events
    assert g.gc.next_command == ("direct_free", 1)


def test_double_touch_after_a_free_kick():
    g = Game(placement="referee")
    g.kick_off(0)
    g.free_kick()
    assert g.gc.command == "direct_free"
    g.kick(1, to=(1.1, HY - 0.2))
    assert g.gc.in_play
    g.kick(1, to=(1.3, HY - 0.2))
    assert "attacker_double_touched_ball" in g.events
    assert g.gc.next_command == ("direct_free", 1) and g.gc.team_info[0].fouls == 1


def test_no_double_touch_when_another_robot_touched_in_between():
    g = Game(placement="referee")
    g.kick_off(0)
    g.free_kick()
    g.kick(1, to=(1.1, HY - 0.2))
    g.kick(3, to=(1.2, HY - 0.3))
    g.kick(1, to=(1.3, HY - 0.3))
    assert "attacker_double_touched_ball" not in g.events and g.gc.in_play


def test_ball_speed_foul_does_not_stop_the_game():
    g = Game()
    g.kick_off(0)
    g.kick(1, to=(0.5, 0.0), speed=(7.0, 0.0))
    assert "bot_kicked_ball_too_fast" in g.events
    assert g.gc.in_play and g.gc.team_info[0].fouls == 1
    g.kick(3, to=(0.4, 0.0), speed=(6.0, 0.0))  # under the limit
    assert g.events.count("bot_kicked_ball_too_fast") == 1


def test_a_non_stopping_foul_voids_a_goal_within_two_seconds():
    g = Game(placement="referee")
    g.kick_off(0)
    g.kick(1, to=(3.0, 0.0), speed=(7.0, 0.0))
    d = g.exit(HX + 0.03, 0.0)
    assert d.scorer == -1 and "invalid_goal" in g.events


@pytest.mark.parametrize("vb, vy, kinds", [
    ((2.0, 0.0), (0.0, 0.0), {"bot_crash_unique": 0}),
    ((1.0, 0.0), (-1.0, 0.0), {"bot_crash_drawn": None}),
    ((1.0, 0.0), (0.0, 0.0), {}),  # closing at 1 m/s: no crash
])
def test_crashing(vb, vy, kinds):
    g = Game()
    g.kick_off(0)
    g.robots[1] = (0.0, 2.0, 0.0, *vb, 0.0)
    g.robots[3] = (0.3, 2.0, np.pi, *vy, 0.0)
    g.step()
    g.robots[1, 0], g.robots[3, 0] = 0.05, 0.05 + 2 * R
    before = list(g.events)
    g.step()
    new = g.events[len(before):]
    assert set(new) == set(kinds)
    if "bot_crash_unique" in kinds:
        assert g.gc.team_info[0].fouls == 1 and g.gc.team_info[1].fouls == 0
    if "bot_crash_drawn" in kinds:
        assert g.gc.team_info[0].fouls == 1 == g.gc.team_info[1].fouls
    assert g.gc.in_play


def test_every_third_foul_is_a_yellow_card_that_takes_a_robot_off_for_two_minutes():
    g = Game()
    g.kick_off(0)
    sent = []
    for k in range(3):
        g.run(2.1)
        d = g.kick(1, to=(0.5 + 0.1 * k, 0.0), speed=(7.0, 0.0))
        sent += d.send_off
        g.kick(3, to=(0.4, 0.0), speed=(1.0, 0.0))
    assert g.events.count("bot_kicked_ball_too_fast") == 3
    assert g.events.count("yellow_card") == 1
    assert sent == [1]  # the highest-numbered robot other than the keeper
    assert g.gc.robots_allowed(0) == 1 and g.gc.team_info[0].off == [1]
    # 120 s of playing time later the robot may come back, at the next stop.
    g.play(121.0)
    assert g.gc.team_info[0].yellow_cards == [] and g.gc.team_info[0].returning == [1]
    d = g.exit(1.0, HY + 0.03)
    assert d.bring_on == [1] and g.gc.team_info[0].off == []


def test_a_third_running_card_is_red():
    g = Game()
    g.kick_off(0)
    for _ in range(2):
        g.gc._card(Decision(), 1)
    assert len(g.gc.team_info[1].yellow_cards) == 2
    g.gc.team_info[1].fouls = 2
    g.kick(3, to=(0.5, 0.0), speed=(7.0, 0.0))
    assert "red_card" in g.events and g.gc.team_info[1].red_cards == 1


def test_cards_can_be_turned_off():
    g = Game(cards=False)
    g.kick_off(0)
    for k in range(3):
        g.run(2.1)
        g.kick(1, to=(0.5 + 0.1 * k, 0.0), speed=(7.0, 0.0))
        g.kick(3, to=(0.4, 0.0))
    assert g.gc.team_info[0].fouls == 3 and "yellow_card" not in g.events


def test_fouls_can_be_turned_off():
    g = Game(fouls=False)
    g.kick_off(0)
    g.kick(1, to=(0.5, 0.0), speed=(7.0, 0.0))
    assert g.events == []


def test_too_fast_in_stop_after_the_grace_period_once_per_robot():
    g = Game(placement="referee")
    g.kick_off(0)
    g.throw_in()
    g.robots[0, 3] = 2.0  # blue's keeper drives at 2 m/s
    g.robots[0, 0:2] = (-4.0, 0.0)
    g.robots[1, 0:2] = (1.0, 2.6)  # and blue 1 stands at the ball: the stop goes on
    g.run(1.9)
    assert "bot_too_fast_in_stop" not in g.events
    g.run(3.0)
    assert g.events.count("bot_too_fast_in_stop") == 1


def test_defender_too_close_at_a_free_kick_restarts_the_kickers_timer():
    g = Game(placement="referee")
    g.kick_off(0)
    g.free_kick()
    assert g.gc.command == "direct_free"
    g.run(9.0)
    g.robots[3, 0:2] = (1.3, HY - 0.2)  # yellow 0.21 m from the ball's centre
    g.step()
    assert "defender_too_close_to_kick_point" in g.events
    g.run(9.0)
    assert not g.gc.in_play  # the 10 s started again


def test_robot_too_close_to_the_opponent_defense_area_at_a_free_kick():
    g = Game(placement="referee")
    g.kick_off(0)
    g.free_kick()
    g.robots[1, 0:2] = (HX - 1.2, 0.0)  # 0.11 m from yellow's defense area
    g.run(2.1)
    assert "attacker_too_close_to_defense_area" in g.events
    assert g.gc.next_command == ("direct_free", 1)


def test_keeper_held_ball():
    g = Game(placement="referee")
    g.kick_off(0)
    g.kick(2, to=(HX - 0.5, 0.2), speed=(0.0, 0.0))  # yellow's keeper holds it
    g.robots[2, 0:2] = (HX - 0.4, 0.2)
    for _ in range(11):
        g.ball[1] = 0.2 + 0.1 * (_ % 2)  # moving a little: progress, but in the area
        g.run(1.0)
    assert "keeper_held_ball" in g.events
    assert g.gc.next_command == ("direct_free", 0)
    assert g.gc.designated[0] <= HX - 1.0 - 1.0 + 1e-9  # 1 m from the defense area


def test_no_progress_ends_in_a_force_start():
    g = Game(placement="referee")
    g.kick_off(0)
    g.kick(1, to=(0.5, 0.5), speed=(0.0, 0.0))
    g.run(10.1)
    assert "no_progress_in_game" in g.events
    assert g.gc.next_command == ("force_start", -1)
    g.keep_away()
    g.run(2.1)
    assert g.gc.command == "force_start" and g.gc.in_play


def test_placement_interference_adds_time_and_one_foul():
    """An interfering robot costs its team one foul and extends the placement once (10 s),
    however long it stays: a robot that cannot leave does not hold the game up for ever,
    and the placement still fails in the end."""
    g = Game()
    g.kick_off(0)
    g.kick(3, to=(1.0, 2.5))
    g.exit(-1.0, HY + 0.03)  # blue places from (-1, 3.03) to (-1, 2.8)
    g.keep_away()
    g.robots[3, 0:2] = (-1.0, HY - 0.1)  # yellow on the ball's way
    g.run(4.5)
    assert g.events.count("bot_interfered_placement") == 1
    assert g.gc._placement_left == pytest.approx(30.0 - 4.5 + 10.0, abs=0.05)
    g.run(35.6)  # 40 s in all: the placement has failed
    assert g.events.count("bot_interfered_placement") == 1
    assert "placement_failed" in g.events


def test_half_time_and_the_end_of_the_match():
    g = Game(duration=20.0)
    g.kick_off(1)
    g.play(9.9)
    assert g.gc.stage == "first_half"
    g.play(0.1)
    assert g.gc.stage == "second_half" and "stage_changed" in g.events
    assert g.gc.next_command == ("prepare_kickoff", 0)  # blue starts the second half
    g.keep_away()
    g.run(2.1)
    g.kick(1)
    g.play(10.1)
    assert g.gc.stage == "post_game" and g.gc.command == "stop"


def test_one_period_without_half_time():
    g = Game(duration=20.0, half_time=False)
    g.kick_off(0)
    g.play(19.0)
    assert g.gc.stage == "first_half"
    g.play(1.1)
    assert g.gc.stage == "post_game"


def test_indirect_free_kick_under_the_2019_rules():
    for touch_again, counts in ((False, False), (True, True)):
        g = Game(placement="referee", free_kicks="2019")
        g.kick_off(0)
        g.free_kick(3.0)  # after a throw-in: indirect in 2019
        g.kick(1, to=(3.1, 2.7), speed=(3.0, -2.0))
        if touch_again:
            g.kick(0, to=(3.5, 1.0))  # another blue robot touches it
        d = g.exit(HX + 0.03, 0.0)
        assert (d.scorer == 0) == counts


def test_the_2025_free_kick_is_direct():
    g = Game(placement="referee")
    g.kick_off(0)
    g.free_kick(3.0)
    g.kick(1, to=(3.1, 2.7), speed=(3.0, -2.0))
    assert g.exit(HX + 0.03, 0.0).scorer == 0


def test_early_end_at_ten_goals_with_a_lead():
    g = Game(placement="referee")
    g.kick_off(0)
    g.gc.team_info[0].goals = 9
    g.kick(1, to=(4.0, 0.0))
    assert g.exit(HX + 0.03, 0.0).over


def test_bad_options_and_rules():
    with pytest.raises(ValueError, match="placement must be one of"):
        GameOptions(placement="magic")
    with pytest.raises(ValueError, match="free_kicks must be one of"):
        GameOptions(free_kicks="1998")
    with pytest.raises(ValueError, match="half_time must be True or False"):
        GameOptions(half_time=1)
    with pytest.raises(ValueError, match="penalty mark lies 8.0 m from the goal, outside field"):
        GameController(presets.field("ssl-2012"), BALL, [0, 1], [R, R],
                       RULES["ssl-2025-div-a"], GameOptions(), 60.0, np.random.default_rng(0))
    with pytest.raises(ValueError, match="duration must be a positive"):
        GameController(FIELD, BALL, [0, 1], [R, R], RULES["ssl-2025-div-b"], GameOptions(),
                       math.inf, np.random.default_rng(0))


@pytest.mark.parametrize("team", [0, 1])
def test_penalty_formation(team):
    from soccer_env.envs.match import SoccerParallelEnv
    from soccer_env.sim.referee import place_penalty

    env = SoccerParallelEnv(blue=4, yellow=3)
    env.reset(seed=0)
    w = env.world
    direction = 1.0 if team == 0 else -1.0
    mark = (direction * (HX - 6.0), 0.0)
    poses = place_penalty(w, team, mark, 1.0)
    keeper = 4 if team == 0 else 0  # the defending team's robot 0
    kicker = 1 if team == 0 else 5
    assert poses[keeper, 0] == pytest.approx(direction * (HX - w.radii[keeper]))
    assert abs(poses[keeper, 1]) < 0.5 * FIELD.goal_width
    assert 0.0 < (mark[0] - poses[kicker, 0]) * direction < 0.2
    for i in range(len(poses)):
        if i not in (keeper, kicker):  # 1 m behind the ball, in the field
            assert (mark[0] - poses[i, 0]) * direction >= 1.0 + w.radii[i]
            assert abs(poses[i, 1]) <= HY
    gaps = [math.dist(poses[i, :2], poses[j, :2]) for i in range(7) for j in range(i)]
    assert min(gaps) >= 2 * R
    env.close()
