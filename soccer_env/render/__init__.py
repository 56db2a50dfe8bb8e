"""Rendering: top-down frames of the truth and the beliefs (pygame), videos and figures.

The renderer (:class:`Renderer`, :mod:`~soccer_env.render.renderer`) composes a frame from its
parts: the view's world-to-pixel transform (:mod:`~soccer_env.render.view`), the field
(:mod:`~soccer_env.render.field`), the overlays of the truth and the belief
(:mod:`~soccer_env.render.overlays`), the info bar and its legend
(:mod:`~soccer_env.render.bar`), the title card and the outcome banner
(:mod:`~soccer_env.render.cards`, their words in :mod:`~soccer_env.render.title`) and the
``human`` window with its keys (:mod:`~soccer_env.render.window`). The environments render
through :class:`RenderingMixin`.

pygame, imageio and matplotlib are optional (``pip install soccer-env[render]``); each is
imported when first used.
"""

from soccer_env.render.bar import KEYS_HELP
from soccer_env.render.cards import Banner
from soccer_env.render.colours import OVERLAY_COLOURS, TEAM_COLOURS
from soccer_env.render.mixin import RenderingMixin
from soccer_env.render.renderer import RENDER_MODES, FrameContents, Renderer
from soccer_env.render.text import wrap_text
from soccer_env.render.title import TITLE_SECONDS
from soccer_env.render.video import hold_last, write_video
from soccer_env.render.view import RENDER_VIEWS, check_view

__all__ = ["Renderer", "RenderingMixin", "Banner", "FrameContents", "RENDER_MODES",
           "RENDER_VIEWS", "TEAM_COLOURS", "OVERLAY_COLOURS", "TITLE_SECONDS", "KEYS_HELP",
           "check_view", "wrap_text", "write_video", "hold_last"]
