"""What the legend of a rendered frame can list, and how its entries flow into rows (no
pygame)."""

from __future__ import annotations

from collections.abc import Sequence

__all__ = ["LEGEND_LABELS", "BELIEF_KEYS", "HUMANOID_KEYS", "legend_keys", "flow"]

#: Every legend entry, in the order the legend lists them: key -> label (the teams' labels
#: are the environment's, e.g. ``"blue: keeper"``).
LEGEND_LABELS: dict[str, str] = {
    "team0": "blue team",
    "team1": "yellow team",
    "ball": "ball",
    "ball_flight": "ball in flight (shadow on the carpet)",
    "belief_robots": "believed robots",
    "belief_ball": "believed ball",
    "belief_velocity": "believed velocity x 0.2 s",
    "ellipses": "2\u03c3 position ellipses",
    "ball_particles": "ball tracker particles",
    "pose_particles": "self-localization particles",
    "measurement": "latest ball sighting",
    "camera": "head camera view (1 m)",
    "fallen": "fallen humanoid's body",
}
#: The entries of the belief overlay (what ``o`` hides, with the camera views).
BELIEF_KEYS = ("belief_robots", "belief_ball", "belief_velocity", "ellipses",
               "ball_particles", "pose_particles", "measurement")
#: The entries only humanoids draw.
HUMANOID_KEYS = ("ball_particles", "pose_particles", "camera", "fallen")


def legend_keys(humanoids: bool) -> list[str]:
    """Every key the legend of a world can list (``humanoids``: whether it has any)."""
    return [k for k in LEGEND_LABELS if humanoids or k not in HUMANOID_KEYS]


def flow(widths: Sequence[int], width: int, spacing: int) -> list[tuple[int, int]]:
    """Place items of ``widths`` [px] left to right in rows of ``width`` [px], ``spacing``
    [px] apart, starting a new row when the next item does not fit (an item wider than a
    row gets a row of its own). Returns each item's ``(row, x)``."""
    out, row, x = [], 0, 0
    for w in widths:
        if x > 0 and x + w > width:
            row, x = row + 1, 0
        out.append((row, x))
        x += w + spacing
    return out
