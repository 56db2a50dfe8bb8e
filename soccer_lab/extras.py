"""What each ``soccer-env`` command needs beyond the base install, checked before it starts.

The base install (numpy, pymunk, gymnasium, pettingzoo) runs the environments. The commands
need more, from the extras of ``pyproject.toml``: ``render`` (matplotlib for figures, pygame to
draw frames, imageio to write videos), ``train`` (stable-baselines3, torch, tensorboard, and
tqdm with rich for the progress bar, sb3-contrib for RecurrentPPO), ``pixels`` (OpenCV, for
rendered camera images), ``rllib`` (Ray's RLlib) and ``ssl`` (protobuf and the league's message
classes).

:data:`REQUIREMENTS` is the one table: per command, or per use of one (``"paper meanshift"``,
``"train --backend rllib"``, ``"video"``), the modules it imports and the extra that installs
each. :func:`missing` looks them up with :func:`importlib.util.find_spec`, which finds a
module without importing it (nothing heavy is loaded); :func:`require` ends the command with
one line naming the extra to install; :func:`unavailable` says why an optional output (the
video) is skipped.
"""

from __future__ import annotations

import importlib.util
import sys
from collections.abc import Iterable
from typing import NamedTuple, NoReturn

__all__ = ["Need", "REQUIREMENTS", "missing", "message", "require", "unavailable",
           "install_command"]


class Need(NamedTuple):
    """Modules a command imports and the extra of ``pyproject.toml`` that installs them.

    Attributes:
        modules: top-level module names, as imported (``"cv2"``, ``"stable_baselines3"``).
        extra: the extra's name (``"render"``, ``"train"``, ``"pixels"``, ``"rllib"``).
    """

    modules: tuple[str, ...]
    extra: str


_FIGURES = Need(("matplotlib",), "render")
_IMAGES = Need(("cv2",), "pixels")
_SB3 = Need(("stable_baselines3", "torch"), "train")

#: What each command (or each use of one) needs beyond the base install, by the name the
#: commands look it up with; a command absent from the table (or an empty entry) needs
#: nothing more.
REQUIREMENTS: dict[str, tuple[Need, ...]] = {
    # Figures always; the video only if pygame and imageio are there (else skipped).
    "demo": (_FIGURES,),
    "video": (Need(("pygame", "imageio"), "render"),),
    "bench": (),
    "bench --batch": (Need(("stable_baselines3",), "train"),),
    "bench --frames": (_IMAGES,),
    "bench --pixels": (_IMAGES,),
    "paper ekf": (_FIGURES,),
    "paper ungm": (_FIGURES,),
    "paper localization": (_FIGURES,),
    "paper hough": (_FIGURES,),
    "paper team": (_FIGURES,),
    "paper meanshift": (_FIGURES, _IMAGES),
    "paper following": (_FIGURES, _IMAGES),
    "train": (Need(("stable_baselines3", "torch", "tensorboard"), "train"),),
    "train --algo recurrent-ppo": (Need(("sb3_contrib",), "train"),),
    "train progress bar": (Need(("tqdm", "rich"), "train"),),
    "train --backend rllib": (Need(("ray", "torch"), "rllib"),),
    "imitate": (Need(("torch",), "train"),),
    "eval": (),
    # A stable-baselines3 model file (.zip) as the policy of eval or ablation.
    "policy .zip": (_SB3,),
    "ablation": (_FIGURES,),
    # The humanoid estimator configuration that finds the ball in rendered images.
    "ablation pixels": (_IMAGES,),
    "list": (),
    "rate": (),
    "serve": (Need(("ssl_protocol", "google.protobuf"), "ssl"),),
    "connect": (Need(("ssl_protocol", "google.protobuf"), "ssl"),),
    "play": (Need(("pygame",), "render"),),
}


def _installed(module: str) -> bool:
    """Whether top-level ``module`` can be imported (found without importing it)."""
    try:
        return importlib.util.find_spec(module) is not None
    except (ImportError, ValueError):  # a broken installation, or a module without a spec
        return module in sys.modules and sys.modules[module] is not None


def missing(key: str) -> list[tuple[str, str]]:
    """What of :data:`REQUIREMENTS` ``[key]`` is not installed.

    Args:
        key: a key of :data:`REQUIREMENTS` (``"train"``, ``"paper meanshift"``, ...).

    Returns:
        The ``(module, extra)`` pairs whose module cannot be found, in table order.

    Raises:
        KeyError: ``key`` is not in the table (the message lists the keys).
    """
    if key not in REQUIREMENTS:
        raise KeyError(f"no requirements listed for {key!r}; known: {sorted(REQUIREMENTS)}")
    return [(module, need.extra) for need in REQUIREMENTS[key] for module in need.modules
            if not _installed(module)]


def _unique(items: Iterable[str]) -> list[str]:
    return list(dict.fromkeys(items))


def install_command(extras: Iterable[str]) -> str:
    """The pip command that installs ``extras``, e.g. ``pip install 'soccer-env[a,b]'``
    (each extra once, in the order given)."""
    return f"pip install 'soccer-env[{','.join(_unique(extras))}]'"


def message(key: str, command: str | None = None, hint: str | None = None) -> str | None:
    """The one line that says what a command lacks and how to install it.

    Args:
        key: a key of :data:`REQUIREMENTS`.
        command: the command as the line names it, after ``soccer-env`` (default: ``key``).
        hint: another way out, appended after a semicolon (``"or ... --no-progress"``).

    Returns:
        ``"soccer-env COMMAND needs the EXTRA extra: pip install 'soccer-env[EXTRA]'
        (missing: MODULES)"``, or None when everything is installed.
    """
    lacking = missing(key)
    if not lacking:
        return None
    extras = _unique(extra for _, extra in lacking)
    noun = "extra" if len(extras) == 1 else "extras"
    text = (f"soccer-env {command or key} needs the {' and '.join(extras)} {noun}: "
            f"{install_command(extras)} (missing: "
            f"{', '.join(_unique(module for module, _ in lacking))})")
    return f"{text}; {hint}" if hint else text


def require(key: str, command: str | None = None, hint: str | None = None) -> None:
    """Return if everything :data:`REQUIREMENTS` ``[key]`` names is installed; otherwise print
    :func:`message` (same arguments) to stderr and exit with status 2, as a command-line error
    does.

    Raises:
        SystemExit: with code 2, when a module is missing.
    """
    text = message(key, command, hint)
    if text is not None:
        _exit(text)


def _exit(text: str) -> NoReturn:
    print(text, file=sys.stderr)
    raise SystemExit(2)


def unavailable(key: str) -> str | None:
    """Why an optional output (the ``"video"``) cannot be made.

    Args:
        key: a key of :data:`REQUIREMENTS`.

    Returns:
        E.g. ``"pygame is not installed (pip install 'soccer-env[render]')"``, or None when
        everything the key names is installed.
    """
    lacking = missing(key)
    if not lacking:
        return None
    modules = _unique(module for module, _ in lacking)
    verb = "is" if len(modules) == 1 else "are"
    return (f"{' and '.join(modules)} {verb} not installed "
            f"({install_command(extra for _, extra in lacking)})")
