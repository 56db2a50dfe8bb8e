"""Command-line pieces shared by the ``soccer-env`` commands: the help formatter, the
environment options of ``train`` and ``eval``, the sensor-preset choices per robot kind and
``key=value`` parsing."""

from __future__ import annotations

import argparse
import json
import textwrap
from collections.abc import Mapping
from typing import Any

from soccer_env import presets
from soccer_env.perception.base import OBS_MODES, PerceptionConfig
from soccer_env.perception.options import BALL_FILTERS

__all__ = ["HelpFormatter", "add_env_arguments", "env_kwargs_from_args", "key_values",
           "add_trust_argument", "SENSOR_PRESETS", "sensor_preset", "check_perception",
           "preset_kind", "robot_choices_help", "sensor_presets_help", "DEFAULT_ROBOT"]

#: The robot preset of the environments unless ``robot=`` names another.
DEFAULT_ROBOT = "ssl"

#: The sensor presets of each robot kind (:data:`soccer_env.presets.SENSOR_PRESETS`).
SENSOR_PRESETS = presets.SENSOR_PRESETS

_KIND_LABELS = {"ssl": "SSL robots (overhead vision)", "humanoid": "humanoids (head camera)"}


class HelpFormatter(argparse.ArgumentDefaultsHelpFormatter):
    """The help of every ``soccer-env`` command: each option's default appended as
    ``(default: VALUE)``, unless the option is a flag, its default is None or empty (its help
    then says what happens without it) or its help already states the default; descriptions
    and epilogs wrapped paragraph by paragraph (paragraphs apart by a blank line), lines that
    start with a space (listings, examples) kept as written."""

    def _split_lines(self, text: str, width: int) -> list[str]:
        # Never break inside a name such as ekf-improved or a long path.
        return textwrap.wrap(" ".join(text.split()), width, break_on_hyphens=False,
                             break_long_words=False)

    def _fill_text(self, text: str, width: int, indent: str) -> str:
        paragraphs = []
        for para in text.split("\n\n"):
            if any(line.startswith(" ") for line in para.splitlines()):
                paragraphs.append("\n".join(indent + line for line in para.splitlines()))
            else:
                paragraphs.append(textwrap.fill(" ".join(para.split()), width,
                                                initial_indent=indent,
                                                subsequent_indent=indent,
                                                break_on_hyphens=False))
        return "\n\n".join(paragraphs)

    def _get_help_string(self, action: argparse.Action) -> str:
        text = action.help or ""
        default = action.default
        if ("%(default)" in text or "(default: " in text or action.nargs == 0
                or default is None or default is argparse.SUPPRESS
                or isinstance(default, bool) or default == []):
            return text
        return f"{text} (default: %(default)s)"


def add_trust_argument(p: argparse.ArgumentParser) -> None:
    """``--trust``: load the pickled parts of stable-baselines3 files (see
    :mod:`agents.sb3.model_files`)."""
    p.add_argument("--trust", action="store_true",
                   help="also load what only unpickling can read (a stable-baselines3 .zip's "
                        "serialized entries, *_vecnormalize.pkl statistics): unpickling runs "
                        "whatever code the file names, so only for files from a source you "
                        "trust (without it: arrays and JSON only; .npz policies never need "
                        "it)")


def key_values(items: list[str], what: str) -> dict[str, Any]:
    """``key=value`` pairs, values parsed as JSON where they parse (else kept as strings).

    Raises:
        ValueError: an item without ``=`` or without a key (the message names ``what``).
    """
    out: dict[str, Any] = {}
    for item in items:
        key, sep, value = item.partition("=")
        if not sep or not key:
            raise ValueError(f"{what} must be key=value, got {item!r}")
        try:
            out[key] = json.loads(value)
        except json.JSONDecodeError:
            out[key] = value
    return out


def preset_kind(robot: Any) -> str | None:
    """The kind (``"ssl"`` or ``"humanoid"``) of robot preset ``robot`` (a name of
    :data:`soccer_env.presets.ROBOTS`); None if ``robot`` is not such a name."""
    if isinstance(robot, str) and robot in presets.ROBOTS:
        return presets.ROBOTS[robot].kind
    return None


def robot_choices_help() -> str:
    """The robot presets grouped by kind: ``"SSL: ssl, ssl-2012; humanoid: humanoid,
    humanoid-2012"``."""
    groups: dict[str, list[str]] = {}
    for name in presets.ROBOTS:
        groups.setdefault(preset_kind(name) or "other", []).append(name)
    return "; ".join(f"{'SSL' if kind == 'ssl' else kind}: {', '.join(names)}"
                     for kind, names in groups.items())


def sensor_presets_help() -> str:
    """The sensor presets grouped by robot kind, for help texts and error messages."""
    return "; ".join(f"{_KIND_LABELS[kind]}: {', '.join(table)}"
                     for kind, table in SENSOR_PRESETS.items())


def sensor_preset(name: str) -> str:
    """``--perception``'s type: ``name`` if it is a sensor preset of some robot kind (which
    kind is checked once the robot is known, by :func:`check_perception`).

    Raises:
        argparse.ArgumentTypeError: an unknown name; the message lists the presets.
    """
    if any(name in table for table in SENSOR_PRESETS.values()):
        return name
    raise argparse.ArgumentTypeError(f"unknown sensor preset {name!r}; choose from "
                                     f"{sensor_presets_help()}")


def check_perception(perception: Any, robot: Any, option: str = "--perception") -> None:
    """Check that a preset name given as ``perception`` belongs to the kind of ``robot`` (a
    robot preset name; None: :data:`DEFAULT_ROBOT`). Anything else (a mapping, a robot that
    is not a preset name) is left to the environment to check.

    Raises:
        ValueError: the preset is not one of the robot kind's; the message lists those.
    """
    kind = preset_kind(DEFAULT_ROBOT if robot is None else robot)
    if not isinstance(perception, str) or kind is None:
        return
    allowed = SENSOR_PRESETS[kind]
    if perception not in allowed:
        shown = DEFAULT_ROBOT if robot is None else robot
        raise ValueError(f"{option} {perception}: not a sensor preset of robot {shown!r}; "
                         f"{_KIND_LABELS[kind]} take {', '.join(allowed)}")


def add_env_arguments(p: argparse.ArgumentParser) -> None:
    """``--robot``, ``--obs-mode``, ``--perception``, ``--ball-filter`` and ``--env-kwarg``
    (read back by :func:`env_kwargs_from_args`)."""
    p.add_argument("--robot", choices=list(presets.ROBOTS), default=None,
                   help=f"robot preset of the environment's robots ({robot_choices_help()}) "
                        f"(default: {DEFAULT_ROBOT})")
    p.add_argument("--obs-mode", choices=OBS_MODES, default=None,
                   help="observation mode: the true state, the latest delayed detections, or "
                        "the estimation stack's belief (default: truth)")
    p.add_argument("--perception", type=sensor_preset, default=None, metavar="PRESET",
                   help=f"sensor preset, by robot kind: {sensor_presets_help()} (default: "
                        "ideal for truth observations, realistic otherwise; a humanoid's own "
                        "head camera)")
    p.add_argument("--ball-filter", choices=list(BALL_FILTERS), default=None,
                   help="ball filter of SSL robots' perceived observations (see soccer-env "
                        f"list) (default: {PerceptionConfig.ball_filter})")
    p.add_argument("--env-kwarg", action="append", default=[], metavar="KEY=VALUE",
                   help="another environment keyword argument (value parsed as JSON), "
                        "repeatable, e.g. shaping='{\"intercept\": 1}'")


def env_kwargs_from_args(args: argparse.Namespace, base: Mapping[str, Any] | None = None
                         ) -> dict[str, Any]:
    """The environment keyword arguments given by :func:`add_env_arguments`'s options, over
    ``base`` (the options over ``--env-kwarg``, both over ``base``).

    Raises:
        ValueError: a bad ``--env-kwarg``, or a ``--perception`` preset of another robot kind
            than the robot's.
    """
    kwargs = dict(base or {})
    kwargs.update(key_values(args.env_kwarg, "--env-kwarg"))
    if getattr(args, "robot", None) is not None:
        kwargs["robot"] = args.robot
    if args.obs_mode is not None:
        kwargs["obs_mode"] = args.obs_mode
    if args.perception is not None:
        check_perception(args.perception, kwargs.get("robot"))
        kwargs["perception"] = args.perception
    if args.ball_filter is not None:
        perception = kwargs.get("perception")
        preset = "camera" if preset_kind(kwargs.get("robot", DEFAULT_ROBOT)) == "humanoid" \
            else "vision"
        perception = (dict(perception) if isinstance(perception, Mapping)
                      else {} if perception is None else {preset: perception})
        perception["ball_filter"] = args.ball_filter
        kwargs["perception"] = perception
    return kwargs
