"""Rendering: top-down frames of the truth and the beliefs (pygame), videos and figures.

pygame, imageio and matplotlib are optional (``pip install soccer-env[render]``); each is
imported when first used.
"""

from soccer_env.render.renderer import (
    KEYS_HELP,
    OVERLAY_COLOURS,
    RENDER_MODES,
    RENDER_VIEWS,
    TEAM_COLOURS,
    TITLE_SECONDS,
    Banner,
    FrameContents,
    Renderer,
    RenderingMixin,
    check_view,
    wrap_text,
)
from soccer_env.render.video import hold_last, write_video

__all__ = ["Renderer", "RenderingMixin", "Banner", "FrameContents", "RENDER_MODES",
           "RENDER_VIEWS", "TEAM_COLOURS", "OVERLAY_COLOURS", "TITLE_SECONDS", "KEYS_HELP",
           "check_view", "wrap_text", "write_video", "hold_last"]
