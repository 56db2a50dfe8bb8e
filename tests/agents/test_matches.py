"""Head-to-head matches (agents.studies.matches): outcomes counted from the right side whatever the
colour, a side against itself is a perfect mirror, a team that plays beats one that does not,
each team's ball error comes from its own belief, the numbers do not depend on the workers,
and bad input is refused before any match."""

import dataclasses
import math

import numpy as np
import pytest

import soccer_env
from agents.common.stats import t975
from agents.policies import NumpyPolicy
from agents.studies.matches import (
    HeadToHead,
    MatchRecord,
    Side,
    checkpoint_sides,
    head_to_head,
    match_jobs,
    play_match,
    team_policy,
    widened_team,
)

ONE_V_ONE = {"blue": 1, "yellow": 1, "match_duration": 12.0}


def _numbers(h: HeadToHead):
    return [(r.seed, r.a_blue, r.goals_a, r.goals_b, r.steps, r.err_sum, r.err_sq_sum,
             r.err_count) for r in h.records]


def test_match_k_plays_seed_k_over_2_with_a_blue_when_k_is_even():
    jobs = match_jobs(Side(), Side("idle"), 5, start_seed=7)
    assert [(j[3], j[4]) for j in jobs] == [(7, True), (7, False), (8, True), (8, False),
                                            (9, True)]


def test_a_side_against_itself_is_a_mirror():
    # Without a keeper, one scripted robot against another scores many goals in 12 s.
    h = head_to_head(Side("scripted", "truth"), Side("scripted", "truth"), 4, start_seed=2,
                     env_kwargs=ONE_V_ONE, workers=1)
    goals = [(r.goals_a, r.goals_b) for r in h.records]
    assert sum(a + b for a, b in goals) > 0
    # Both sides are the same, so a seed played with a as yellow is the same match as with a
    # as blue, seen from the other side.
    for first, second in zip(goals[::2], goals[1::2]):
        assert second == first[::-1]
    assert h.wins == h.losses and h.goals_for == h.goals_against
    assert h.goal_difference() == (0.0, 0.0, 0.0)
    assert h.ball_error(0) == h.ball_error(1) == (0.0, 0.0)  # both see the truth


def test_a_team_that_plays_beats_one_that_does_not_from_either_side():
    h = head_to_head(Side("scripted", "truth"), Side("idle", "truth"), 2,
                     env_kwargs=ONE_V_ONE, workers=1)
    assert [r.a_blue for r in h.records] == [True, False]
    assert h.wins == 2 and h.goals_against == 0 and h.goals_for >= 2
    assert h.rate("wins")[0] == 1.0 and h.rate("losses")[0] == 0.0
    assert h.goal_difference()[0] == h.goals_for / 2
    # The reverse pairing is the same matches seen from the other side.
    r = head_to_head(Side("idle", "truth"), Side("scripted", "truth"), 2,
                     env_kwargs=ONE_V_ONE, workers=1)
    assert r.losses == 2 and r.goals_against == h.goals_for


def test_each_team_is_measured_on_its_own_belief():
    truth = Side("scripted", "truth")
    seen = Side("scripted", "perceived", {"vision": "ssl-2012"})
    # Two against two: no goal in 4 s (a goal teleports the ball, and a belief takes the
    # vision's latency to follow).
    h = head_to_head(truth, seen, 2, env_kwargs={"blue": 2, "yellow": 2,
                                                 "match_duration": 4.0}, workers=1)
    assert h.goals_for == h.goals_against == 0
    assert h.ball_error(0) == (0.0, 0.0)  # from both sides
    mean, rms = h.ball_error(1)
    assert 0.005 < mean <= rms < 0.3  # 25 mm noise and 120 ms of latency
    assert all(r.err_count == (r.steps, r.steps) for r in h.records)  # one belief per team


def test_workers_do_not_change_the_numbers():
    a = Side("scripted", "perceived", {"vision": "realistic"}, label="ekf")
    b = Side("scripted", "raw", {"vision": "realistic"}, label="raw")
    kwargs = {"blue": 2, "yellow": 2, "match_duration": 3.0}
    one = head_to_head(a, b, 3, start_seed=5, env_kwargs=kwargs, workers=1)
    two = head_to_head(a, b, 3, start_seed=5, env_kwargs=kwargs, workers=2)
    assert _numbers(one) == _numbers(two)
    # And a match is the same when played again alone.
    alone = play_match(kwargs, b, a, 5)
    assert alone["goals"] == (two.records[1].goals_b, two.records[1].goals_a)
    assert alone["err_sum"] == two.records[1].err_sum[::-1]


def test_a_numpy_policy_file_plays_for_every_robot_of_its_team(tmp_path):
    import soccer_env

    kwargs = {"blue": 2, "yellow": 2, "match_duration": 1.0}
    env = soccer_env.parallel_env(**kwargs)
    obs, _ = env.reset(seed=0)
    n = env.observation_space("blue_0").shape[0]
    # A constant policy: drive forward at full speed.
    forward = NumpyPolicy([("linear", np.zeros((6, n)), np.array([1.0, 0, 0, 0, 0, 0]))],
                          "clip", -np.ones(6), np.ones(6)).save(tmp_path / "forward.npz")
    actions = team_policy(str(forward), env, "yellow")(obs)
    env.close()
    assert sorted(actions) == ["yellow_0", "yellow_1"]
    assert all(list(a) == [1, 0, 0, 0, 0, 0] for a in actions.values())
    h = head_to_head(Side(str(forward), "truth"), Side("idle", "truth"), 2, env_kwargs=kwargs,
                     workers=1)
    assert h.a.label == "forward (truth)" and h.matches == 2
    small = NumpyPolicy([("linear", np.zeros((6, 7)), np.zeros(6))], "clip", -np.ones(6),
                        np.ones(6)).save(tmp_path / "small.npz")
    with pytest.raises(ValueError, match="takes observations of size 7, the match gives"):
        head_to_head(Side(str(small)), Side(), 1, env_kwargs=ONE_V_ONE, workers=1)


def test_a_team_trained_without_the_game_flow_plays_under_it_on_the_entries_it_knows():
    """The shipped truth-trained team reads the game flow's observation: the game block's
    entries, which come last, weigh nothing, and the map takes the game flow's rules (the
    scripted team plays the restarts)."""
    from agents.baselines import SSL_TEAM_2V2
    from agents.policies.numpy_policy import widen

    team = NumpyPolicy.load(SSL_TEAM_2V2)
    env = soccer_env.parallel_env(blue=2, yellow=2, game=True, match_duration=2.0)
    obs, _ = env.reset(seed=3)
    n = env.observation_space("blue_0").shape[0]
    wide = widened_team(team, env, "yellow")
    assert team.obs_size < n and wide.obs_size == n
    assert "rules" in wide.action_map["params"] and "rules" not in team.action_map["params"]
    x = np.stack([obs["yellow_0"], obs["yellow_1"]])
    want = team.network_action(x[:, :team.obs_size])
    np.testing.assert_allclose(wide.network_action(x), want, rtol=1e-6)
    x[:, team.obs_size:] = 1e3  # whatever the game block says
    np.testing.assert_allclose(wide.network_action(x), want, rtol=1e-6)
    actions = team_policy(str(SSL_TEAM_2V2), env, "yellow")(obs)
    assert sorted(actions) == ["yellow_0", "yellow_1"]
    # A team that reads the game block does not play a match without it.
    plain = soccer_env.parallel_env(blue=2, yellow=2, match_duration=2.0)
    with pytest.raises(ValueError, match=f"takes observations of size {n}, the match gives"):
        team_policy(wide, plain, "blue")
    assert widened_team(wide, env, "blue").obs_size == n
    with pytest.raises(ValueError, match="obs_size must be an integer >= the policy's"):
        widen(team, team.obs_size - 1)
    env.close()
    plain.close()


def _full_speed(obs):
    """Every robot drives forward at full speed, whatever the referee says."""
    out = np.zeros((len(obs), 6), dtype=np.float32)
    out[:, 0] = 1.0
    return out


def test_fouls_and_cards_are_counted_per_side_under_the_game_flow():
    """A team that never slows down at a stop is called for it and carded; the idle team is
    not; without the game flow nothing is counted."""
    # Ten seconds of steps (the match clock barely runs: the idle team never kicks off), a
    # yellow card for every foul.
    kwargs = {"blue": 2, "yellow": 2, "match_duration": 20.0, "control_dt": 1 / 30,
              "max_cycles": 300}
    rules = dataclasses.replace(soccer_env.presets.RULES.get("ssl-2025-div-b"), fouls_per_card=1)
    fast, idle = Side(_full_speed, "truth", label="fast"), Side("idle", "truth")
    h = head_to_head(fast, idle, 2, env_kwargs={**kwargs, "game": rules}, workers=1)
    assert all(r.fouls[0] >= 1 and r.fouls[1] == 0 for r in h.records)
    assert h.per_match("fouls", 0)[0] >= 1.0 and h.per_match("fouls", 1)[0] == 0.0
    assert all(r.yellow_cards == (r.fouls[0], 0) for r in h.records)
    assert h.to_dict()["fouls_per_match"]["b"][0] == 0.0
    plain = head_to_head(fast, idle, 2, env_kwargs=kwargs, workers=1)
    assert all(r.fouls == (0, 0) and r.yellow_cards == (0, 0) for r in plain.records)
    with pytest.raises(ValueError, match="what must be"):
        h.per_match("goals", 0)


def test_checkpoint_sides_are_a_runs_copies_oldest_first(tmp_path):
    from agents.baselines import SSL_TEAM_CHECKPOINTS

    sides = checkpoint_sides(SSL_TEAM_CHECKPOINTS, "truth")
    assert [s.label for s in sides] == ["copy at 15 M steps", "copy at 20 M steps"]
    assert all(s.obs_mode == "truth" and s.policy.endswith(".npz") for s in sides)
    assert checkpoint_sides(tmp_path / "missing") == []


def test_goal_difference_interval_is_paired_by_seed():
    def rec(seed, a_blue, ga, gb):
        return MatchRecord(seed, a_blue, ga, gb, 1, (0.0, 0.0), (0.0, 0.0), (1, 1), 0.0)

    # Seeds 0, 1, 2 with mean differences 1, 2, 3 (each the mean of its two matches).
    recs = [rec(0, True, 2, 0), rec(0, False, 0, 0), rec(1, True, 3, 1), rec(1, False, 2, 0),
            rec(2, True, 3, 0), rec(2, False, 4, 1)]
    h = HeadToHead(Side(), Side("idle"), recs)
    mean, lo, hi = h.goal_difference()
    assert mean == 2.0
    assert hi - mean == pytest.approx(mean - lo) == pytest.approx(4.302652729911275 / math.sqrt(3))
    assert (h.wins, h.draws, h.losses) == (5, 1, 0)
    one = HeadToHead(Side(), Side("idle"), recs[:2])
    assert one.goal_difference() == (1.0, -math.inf, math.inf)
    assert one.to_dict()["goal_difference"] == [1.0, None, None]


@pytest.mark.parametrize("dof, exact", [(1, 12.706204736174707), (4, 2.776445105197793),
                                        (5, 2.570581835636314), (10, 2.228138851986274),
                                        (30, 2.042272456301238), (1000, 1.962339)])
def test_student_t_quantile(dof, exact):
    assert t975(dof) == pytest.approx(exact, abs=3e-4)


@pytest.mark.parametrize("make, match", [
    (lambda: Side("champion"), "policy must be 'scripted', 'idle', a numpy policy file"),
    (lambda: Side(42), "policy must be .* got int"),
    (lambda: Side(obs_mode="oracle"), "obs_mode must be one of"),
    (lambda: Side(perception="ssl-2012"), "perception must be a mapping"),
    (lambda: match_jobs(Side(), Side(), 0), "matches must be an integer >= 1, got 0"),
    (lambda: match_jobs(Side(), Side(), 2, env_kwargs={"obs_mode": "raw"}),
     r"must not set \['obs_mode'\]: each side sets them"),
    (lambda: match_jobs(Side(), Side(), 2, env_kwargs={"info_mode": "flat"}),
     "info_mode must be 'full'"),
])
def test_bad_input_is_refused(make, match):
    with pytest.raises(ValueError, match=match):
        make()
