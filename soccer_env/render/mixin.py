"""``render()`` and ``close()`` of the environments (:class:`RenderingMixin`): the renderer
made on first use, and what each frame shows (the scene, the task's text, the title card over
an episode's first second, the outcome banner)."""

from __future__ import annotations

from typing import Any

from soccer_env.render.cards import Banner
from soccer_env.render.renderer import Renderer
from soccer_env.render.title import seed_text, title_alpha

__all__ = ["RenderingMixin"]


class RenderingMixin:
    """``render()`` and ``close()`` for the environments.

    Expects ``render_mode``, ``field``, ``ball_spec``, ``world`` (its robot specs),
    ``metadata["render_fps"]``, ``_render_width`` and ``_render_view`` on the environment, a
    ``_scene()`` method returning what to draw (the truth, the belief to draw over it or None,
    and the humanoids' camera views, as :meth:`Renderer.draw` takes them), and these, whose
    defaults draw nothing: ``_hud()`` (lines of text), ``_title_card()`` (the title card's
    lines, :mod:`soccer_env.render.title`), ``_banner()`` (the outcome banner or None),
    ``_team_labels()`` and ``_belief_owner()`` (the legend's words). The renderer is created
    on first use. ``reset`` calls :meth:`_note_reset` with its seed, for the title card.
    """

    _renderer: Renderer | None = None
    _render_view: str = "field"
    _render_width: int
    #: The seed of the latest seeded reset, and the episodes begun since it (0: this one).
    _render_seed: int | None = None
    _render_episode = 0

    def _hud(self) -> list[str]:
        return []

    def _title_card(self) -> list[str]:
        return []

    def _banner(self) -> Banner | None:
        return None

    def _team_labels(self) -> tuple[str, str]:
        return ("blue team", "yellow team")

    def _belief_owner(self) -> str:
        return "the team"

    def _caption(self) -> str:
        return "soccer_env"

    def _note_reset(self, seed: int | None) -> None:
        """Remember the episode's seed for the title card (a reset without a seed continues
        the generator of the latest seeded one)."""
        if seed is not None:
            self._render_seed, self._render_episode = int(seed), 0
        else:
            self._render_episode += 1

    def _seed_text(self) -> str:
        """The title card's seed (:func:`~soccer_env.render.title.seed_text`)."""
        return seed_text(self._render_seed, self._render_episode)

    @property
    def renderer(self) -> Renderer | None:
        """The renderer (None before the first :meth:`render`): its view and toggles, and
        what the latest frame shows (:attr:`Renderer.contents`)."""
        return self._renderer

    def render(self) -> Any:
        """The current frame (``rgb_array``), or draw it in the window (``human``).

        The frame is the field view (``render_view="field"``: the whole walled area;
        ``"follow"``: a window around the ball and the robots nearest it, zoomed 2-4 times)
        above an info bar with the task's text and a legend of the overlays on screen. The
        title card shows over an episode's first second; the outcome banner on frames after
        its end. In ``human`` mode the window's keys are: space pauses and resumes, ``n`` or
        the right arrow lets one frame through while paused, ``o`` toggles the overlays (the
        belief and the camera views), ``l`` the legend, ``z`` the follow view, ``q`` or Esc
        closes the window (see :class:`Renderer`).
        """
        if self.render_mode is None:
            import gymnasium

            gymnasium.logger.warn("render() called without a render_mode; pass render_mode= "
                                  "when creating the environment")
            return None
        if self._renderer is None:
            self._renderer = Renderer(self.field, list(self.world.robot_specs), self.ball_spec,
                                      self.render_mode, self._render_width,
                                      self.metadata["render_fps"], self._render_view,
                                      self._team_labels(), self._belief_owner(),
                                      self._caption())
        state, belief, heads = self._scene()
        alpha = title_alpha(state.time)
        title = [] if alpha is None else self._title_card()
        return self._renderer.draw(state, self._hud(), belief, heads or None, title=title,
                                   title_alpha=1.0 if alpha is None else alpha,
                                   banner=self._banner())

    def close(self) -> None:
        """Close the window, if any."""
        if self._renderer is not None:
            self._renderer.close()
            self._renderer = None
