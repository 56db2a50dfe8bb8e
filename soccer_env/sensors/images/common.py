"""What both renderers share: the fixed-point drawing units, lighting and noise
(:class:`Photometry`), and the per-robot lists (:func:`robot_markers`,
:func:`check_robot_count`).

Drawing: OpenCV draws with :data:`DRAW_SHIFT` fractional bits, so a pixel coordinate ``u``
is passed as the integer ``round(u * DRAW_ONE)``.

Lighting and noise: per frame a global gain ``g = 1 + gain_sigma * N(0, 1)`` (clipped to [0.3,
2]) and a linear brightness ramp of amplitude ``a ~ U(0, gradient)`` in a random direction ``phi
~ U(0, 2 pi)``: pixel values are multiplied by ``g (1 + a (cos(phi) x_n + sin(phi) y_n))``,
``x_n, y_n`` in [-1, 1] across the image; then Gaussian noise of ``noise_sigma`` grey levels is
added to each channel and the result saturated to [0, 255]. The noise (rounded to grey levels)
is read at a random offset from a bank of Gaussian samples twice the image's size, drawn once
per renderer from a fixed seed (drawing 900 k normals per frame would cost more than the rest of
the frame): within a frame the samples are independent; consecutive frames read different,
shifted windows. All per-frame draws come from the ``rng`` given to ``render``, so the same
generator state gives the same image. Both run in one compiled pass over the pixels
(:func:`~soccer_env.sensors.images.photometry_kernels.light_and_noise`).
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from soccer_env.presets import RobotSpec
from soccer_env.sensors.images.patterns import PATTERN_IDS
from soccer_env.sensors.images.photometry_kernels import light_and_noise
from soccer_env.state import WorldState

__all__ = ["DRAW_SHIFT", "DRAW_ONE", "Photometry", "robot_markers", "check_robot_count"]

#: Fractional bits of the pixel coordinates given to OpenCV's drawing functions.
DRAW_SHIFT = 4
#: One pixel in those fixed-point units (``2 ** DRAW_SHIFT``).
DRAW_ONE = 1 << DRAW_SHIFT


class Photometry:
    """Per-frame lighting and noise of an image of ``(height, width)`` pixels (see the module
    docstring): a global gain ``1 + gain_sigma N(0, 1)``, a linear brightness ramp of
    amplitude up to ``gradient`` in a random direction, then Gaussian noise of
    ``noise_sigma`` grey levels read from a fixed bank at a random offset.

    Args:
        width, height: the image's size [px].
        gain_sigma: standard deviation of the global gain.
        gradient: largest amplitude of the brightness ramp across the image.
        noise_sigma: standard deviation of the pixel noise [grey levels].
    """

    def __init__(self, width: int, height: int, gain_sigma: float, gradient: float,
                 noise_sigma: float) -> None:
        self.width, self.height = width, height
        self.gain_sigma, self.gradient, self.noise_sigma = gain_sigma, gradient, noise_sigma
        self.active = gain_sigma > 0.0 or gradient > 0.0 or noise_sigma > 0.0
        self._xn = np.linspace(-1.0, 1.0, width, dtype=np.float32)
        self._yn = np.linspace(-1.0, 1.0, height, dtype=np.float32)
        self._bank: np.ndarray | None = None
        if noise_sigma > 0.0:
            # A fixed table of noise samples (the same for every renderer of this size and
            # sigma), rounded to grey levels; frames read random windows of it.
            bank_rng = np.random.default_rng(0x5EED)
            self._bank = np.rint(noise_sigma * bank_rng.standard_normal(
                (2 * height, 2 * width, 3), dtype=np.float32)).astype(np.int16)
            self._bank_rows = self._bank.reshape(2 * height, 6 * width)

    def apply(self, img: np.ndarray, rng: np.random.Generator | None) -> np.ndarray:
        """``img`` (``(height, width, 3)`` ``uint8``) with this frame's lighting and noise
        drawn from ``rng`` (the image itself when there is none; then ``rng`` may be None)."""
        if not self.active:
            return img
        if rng is None:
            raise ValueError("this spec has lighting or noise: render() needs an rng")
        z = float(rng.standard_normal())
        a_u, phi_u = rng.random(2).tolist()
        oy, ox = rng.integers(0, (self.height + 1, self.width + 1)).tolist()
        lit = self.gain_sigma > 0.0 or self.gradient > 0.0
        row, column = self._xn, self._yn  # (not read when not lit)
        if lit:
            gain = min(2.0, max(0.3, 1.0 + self.gain_sigma * z))
            a = self.gradient * a_u
            phi = 2.0 * math.pi * phi_u
            gx, gy = gain * a * math.cos(phi), gain * a * math.sin(phi)
            # The ramp (float32) is row[x] + column[y].
            row, column = gain + gx * self._xn, gy * self._yn
        noisy = self._bank is not None
        h, w = self.height, self.width
        out = np.empty((h, w, 3), dtype=np.uint8)
        light_and_noise(np.ascontiguousarray(img).reshape(h, 3 * w), np.repeat(row, 3),
                        column, lit, self._bank_rows if noisy else _NO_BANK, oy, ox, noisy,
                        out.reshape(h, 3 * w))
        return out


#: The bank :func:`light_and_noise` is given when there is no noise (never read).
_NO_BANK = np.zeros((1, 3), dtype=np.int16)


def robot_markers(robot_specs: RobotSpec | Sequence[RobotSpec], teams: Sequence[int]
                  ) -> tuple[list[RobotSpec], list[int], list[int]]:
    """Every robot's spec (``robot_specs``: one for all or one per robot), team (0 blue, 1
    yellow) and number within its team, which picks the marker pattern it wears
    (:data:`~soccer_env.sensors.images.patterns.PATTERN_IDS`); raises ``ValueError`` for a
    team other than 0 or 1, a list of the wrong length or more robots in a team than there
    are patterns."""
    team_list = [int(t) for t in teams]
    if any(t not in (0, 1) for t in team_list):
        raise ValueError(f"teams must hold 0 (blue) or 1 (yellow) per robot, got {list(teams)}")
    n = len(team_list)
    if isinstance(robot_specs, (list, tuple)):
        specs = list(robot_specs)
        if len(specs) != n:
            raise ValueError(f"robot_specs must have one spec per robot ({n}), got {len(specs)}")
    else:
        specs = [robot_specs] * n
    counts = [0, 0]
    index = []
    for t in team_list:
        index.append(counts[t])
        counts[t] += 1
    if max(counts) > len(PATTERN_IDS):
        raise ValueError(f"at most {len(PATTERN_IDS)} robots per team can be told apart, "
                         f"got {max(counts)}")
    return specs, team_list, index


def check_robot_count(state: WorldState, n: int) -> None:
    """Raise ``ValueError`` unless ``state`` holds the ``n`` robots a renderer draws."""
    if state.robots.shape[0] != n:
        raise ValueError(f"state has {state.robots.shape[0]} robots, the renderer {n}")
