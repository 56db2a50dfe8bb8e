"""Videos of rendered frames (imageio, the ``render`` extra).
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

import numpy as np

__all__ = ["write_video", "hold_last", "HOLD_SECONDS"]

#: How long a video holds an episode's last frame (its outcome banner) [s].
HOLD_SECONDS = 1.0


def write_video(frames: Sequence[np.ndarray], path: Path, fps: int) -> Path:
    """Write rgb_array ``frames`` to ``path`` (an ``.mp4``); without an ffmpeg backend, to a
    ``.gif`` of every second frame beside it. Returns the file written. Needs imageio (the
    ``render`` extra)."""
    import imageio.v2 as imageio

    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    frames = [_even(f) for f in frames]
    try:
        imageio.mimsave(path, frames, fps=fps, macro_block_size=1)
    except Exception:  # no ffmpeg backend: fall back to a GIF
        path.unlink(missing_ok=True)
        path = path.with_suffix(".gif")
        imageio.mimsave(path, frames[::2], duration=2.0 / fps)
    return path


def hold_last(frames: list[np.ndarray], fps: float, seconds: float = HOLD_SECONDS) -> None:
    """Append copies of the last of ``frames`` (in place) so that a video at ``fps`` frames
    per second shows it ``seconds`` [s] longer: an episode's last frame, with its outcome
    banner, before the next episode starts. Nothing happens to an empty list."""
    if frames and frames[-1] is not None:
        frames.extend([frames[-1]] * int(round(seconds * fps)))


def _even(frame: np.ndarray) -> np.ndarray:
    """``frame`` with its last row and column repeated as needed to make both sizes even
    (H.264 encoders refuse odd ones)."""
    h, w = frame.shape[:2]
    if h % 2 == 0 and w % 2 == 0:
        return frame
    return np.pad(frame, ((0, h % 2), (0, w % 2), (0, 0)), mode="edge")
