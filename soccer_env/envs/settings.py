"""The settings every environment takes, declared once: :class:`EnvSettings`.

Each task's constructor takes its own arguments (the Goalkeeper's ``shots`` and ``mates``, the
Shootout's ``start``, the match's team sizes and game) and, as keywords, the fields of
:class:`EnvSettings`, which are the same for every task::

    @settings_keywords
    def __init__(self, *, shots=None, mates=None, **settings: Any) -> None:
        s, spec, field, ball = self._take_settings(settings)

:func:`settings_keywords` gives the constructor the signature a reader expects (the task's own
arguments, then the settings: what ``inspect.signature``, ``help()`` and
:func:`~soccer_env.validation.keyword_names` report), and :meth:`EnvSettings.from_keywords`
(which :meth:`~soccer_env.envs.base.SingleAgentTask._take_settings` calls) refuses an unknown
keyword in Python's own wording, listing the allowed ones. The settings are checked where they
are used (:meth:`~soccer_env.envs.base.SoccerCore._build` checks the choices, the world its
time steps), in the same order for every task.
"""

from __future__ import annotations

import inspect
from collections.abc import Callable, Mapping
from dataclasses import dataclass, fields
from typing import Any, TypeVar

from soccer_env import presets
from soccer_env.presets import BallSpec, FieldSpec, RobotSpec
from soccer_env.validation import keyword_names, reject_unknown

__all__ = ["EnvSettings", "settings_keywords", "resolve_world", "per_team"]

_F = TypeVar("_F", bound=Callable[..., Any])


@dataclass(frozen=True)
class EnvSettings:
    """The keyword arguments every environment takes, as given (see the tasks' "Arguments").

    Attributes:
        robot: a robot preset's name or a :class:`~soccer_env.presets.RobotSpec` (the match
            also takes ``{"blue": ..., "yellow": ...}``).
        field: a field preset's name or a :class:`~soccer_env.presets.FieldSpec`; None: the
            robot preset's field (Division B for SSL robots).
        ball: a ball preset's name or a :class:`~soccer_env.presets.BallSpec`; None: the
            field's ball.
        obs_mode: ``"truth"``, ``"raw"`` or ``"perceived"`` (the match also takes one per
            team).
        perception: a vision preset's name, a
            :class:`~soccer_env.perception.base.PerceptionConfig` or a mapping of its fields
            (the match also takes one per team); it also sets the actuation latency and the
            command loss, in every mode.
        render_mode: None, ``"rgb_array"`` or ``"human"``.
        shaping: ``{term: scale}`` of the task's shaping terms (all off by default).
        control_dt: the control step [s].
        physics_dt: the longest physics substep [s].
        out_of_range_actions: ``"clip"`` (actions clipped into [-1, 1]) or ``"raise"``.
        render_width: the frames' width [px].
        render_view: ``"field"`` (the whole field) or ``"follow"`` (a window around the ball
            and the nearest robots).
        head: how humanoids' heads are aimed: ``"auto"``, ``"scan"`` or ``"action"`` (the
            policy's action entries 4 and 5).
        belief_features: whether the observations end with how sure the belief is.
        info_mode: ``"full"`` (nested dicts) or ``"flat"`` (numbers under fixed keys, see
            :mod:`soccer_env.envs.flat_info`).
    """

    robot: Any = "ssl"
    field: str | FieldSpec | None = None
    ball: str | BallSpec | None = None
    obs_mode: Any = "truth"
    perception: Any = None
    render_mode: str | None = None
    shaping: Mapping[str, float] | None = None
    control_dt: float = 1.0 / 60.0
    physics_dt: float = 1.0 / 240.0
    out_of_range_actions: str = "clip"
    render_width: int = 960
    render_view: str = "field"
    head: str = "auto"
    belief_features: bool = False
    info_mode: str = "full"

    @classmethod
    def from_keywords(cls, where: str, keywords: Mapping[str, Any],
                      init: Callable[..., Any]) -> EnvSettings:
        """The settings among a constructor's ``keywords`` (the rest of its ``**settings``).

        Raises:
            TypeError: for a keyword that is no setting, as Python words it (``where() got an
                unexpected keyword argument 'name'``), followed by every keyword of ``init``
                (the constructor, decorated with :func:`settings_keywords`).
        """
        names = {f.name for f in fields(cls)}
        reject_unknown(where, {k: v for k, v in keywords.items() if k not in names},
                       keyword_names(init))
        return cls(**keywords)

    def presets(self, robot: Any = None) -> tuple[RobotSpec, FieldSpec, BallSpec]:
        """The robot, field and ball presets (:func:`resolve_world`) of ``robot`` (default:
        :attr:`robot`) and these settings."""
        return resolve_world(self.robot if robot is None else robot, self.field, self.ball)


def settings_keywords(init: _F) -> _F:
    """Decorate a task's ``__init__(self, *, <own arguments>, **settings)``: its signature
    becomes the task's own arguments followed by the fields of :class:`EnvSettings` as keyword
    arguments with their defaults, which ``inspect.signature``, ``help()`` and
    :func:`~soccer_env.validation.keyword_names` report."""
    sig = inspect.signature(init)
    own = [p for p in sig.parameters.values() if p.kind is not inspect.Parameter.VAR_KEYWORD]
    common = [inspect.Parameter(f.name, inspect.Parameter.KEYWORD_ONLY, default=f.default,
                                annotation=f.type) for f in fields(EnvSettings)]
    init.__signature__ = sig.replace(parameters=own + common)  # type: ignore[attr-defined]
    return init


def resolve_world(robot: Any, field: Any, ball: Any) -> tuple[RobotSpec, FieldSpec, BallSpec]:
    """The robot, field and ball presets of an environment's arguments: the field defaults to
    the robot preset's, the ball to the field's."""
    spec = presets.robot(robot)
    fld = presets.field(field if field is not None else presets.default_field(spec))
    return spec, fld, presets.ball(ball if ball is not None else fld.ball)


def per_team(name: str, value: Any) -> tuple[Any, Any]:
    """``value`` for both teams, or ``{"blue": ..., "yellow": ...}`` (both keys needed; else
    ``ValueError`` naming the setting ``name``)."""
    if isinstance(value, Mapping) and set(value) & {"blue", "yellow"}:
        if set(value) != {"blue", "yellow"}:
            raise ValueError(f"{name} per team must have exactly the keys 'blue' and "
                             f"'yellow', got {sorted(value)}")
        return value["blue"], value["yellow"]
    return value, value
