"""The words of an episode's title card (no pygame): the task and the seed, the robots, and
each team's observations and perception; and whose belief the frames draw.

An environment gathers the facts (:class:`TeamCard` per team with robots) and
:func:`title_card` words them; :class:`~soccer_env.render.cards.Cards` draws the lines over an
episode's first :data:`TITLE_SECONDS` (:func:`title_alpha`).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any, NamedTuple

__all__ = ["TeamCard", "title_card", "title_alpha", "perception_text", "seed_text",
           "belief_owner", "TEAM_NAMES", "TITLE_SECONDS", "TITLE_FADE"]

#: The teams' names, by team index.
TEAM_NAMES = ("blue", "yellow")
#: The title card shows over an episode's first this many simulated seconds [s], fading out
#: over the last :data:`TITLE_FADE` of them.
TITLE_SECONDS = 1.0
TITLE_FADE = 0.3


class TeamCard(NamedTuple):
    """One team's line of the title card: its ``team`` (0 blue, 1 yellow), how many
    ``robots`` it plays, their preset's name (``robot``) and its observations and perception
    in words (``perception``, :func:`perception_text`)."""

    team: int
    robots: int
    robot: str
    perception: str


def title_alpha(t: float) -> float | None:
    """The title card's opacity at the episode's time ``t`` [s] (None: no title card, after
    :data:`TITLE_SECONDS`)."""
    if t < TITLE_SECONDS - 1e-9:
        return min(1.0, (TITLE_SECONDS - t) / TITLE_FADE)
    return None


def seed_text(seed: int | None, episodes: int) -> str:
    """The seed in words: ``seed`` of the latest seeded reset (None: none yet) and the
    ``episodes`` begun since it (0: this one)."""
    if seed is None:
        return "unseeded"
    if episodes == 0:
        return f"seed {seed}"
    return f"seed {seed} + {episodes} episodes"


def perception_text(mode: str, config: Any, humanoid: bool, camera: str | None) -> str:
    """A team's observations and perception in words.

    Args:
        mode: the team's observation mode (``"truth"``, ``"raw"``, ``"perceived"``).
        config: its :class:`~soccer_env.perception.base.PerceptionConfig`.
        humanoid: whether the team plays humanoids (head cameras) rather than SSL robots
            (overhead vision).
        camera: the name of its robots' head camera, or None.
    """
    if mode == "truth":
        return "truth (no sensors)"
    if humanoid:
        words = f"camera {camera}" if camera is not None else "head cameras"
        if mode == "raw":
            return f"raw: {words}, dead reckoning, own sightings"
        text = (f"perceived: {words}, {config.localization} localization, {config.fusion} "
                f"fusion, {config.ball_tracker} tracker")
    else:
        text = f"{mode}: vision {config.vision.name}"
        if mode == "perceived":
            text += f", ball filter {config.ball_filter}"
        if config.detector != "geometric":
            text += f", {config.detector} detector"
    return text + (", randomised" if config.randomize else "")


def title_card(task_id: str, seed: str, teams: Sequence[TeamCard]) -> list[str]:
    """The title card's lines: the task and ``seed`` (:func:`seed_text`), the robots of every
    team in ``teams``, then their perception (one line when every team's is the same)."""
    robots = [f"{TEAM_NAMES[c.team]}: {c.robots} {c.robot} robot{'s' if c.robots > 1 else ''}"
              for c in teams]
    lines = [f"{task_id}    {seed}", ",  ".join(robots)]
    texts = [c.perception for c in teams]
    if len(set(texts)) == 1:
        lines.append(f"obs {texts[0]}")
    else:
        lines += [f"{TEAM_NAMES[c.team]} obs {c.perception}" for c in teams]
    return lines


def belief_owner(name: str, humanoid: bool) -> str:
    """Whose belief the frames draw, for the robot ``name`` (e.g. ``"blue_0"``): a humanoid's
    own (``"blue 0"``), else its team's (``"blue team"``)."""
    if humanoid:
        return name.replace("_", " ")
    return f"{name.split('_')[0]} team"
