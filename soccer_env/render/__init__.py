"""Rendering: top-down frames of the truth and the beliefs (pygame), videos and figures.

pygame, imageio and matplotlib are optional (``pip install soccer-env[render]``); each is
imported when first used.
"""

from soccer_env.render.renderer import RENDER_MODES, TEAM_COLOURS, Renderer, RenderingMixin
from soccer_env.render.video import write_video

__all__ = ["Renderer", "RenderingMixin", "RENDER_MODES", "TEAM_COLOURS", "write_video"]
