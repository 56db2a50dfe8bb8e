"""The architecture: layers that data flows down, checked over every import of every module.

A module may import modules of its own layer and of the layers below it, never above. Every
import statement counts, including those inside functions, and so do
``importlib.import_module("...")`` calls with a literal name. ``agents`` is a stack of layers
of its own (its subpackages), and its optional libraries follow them: the layers below
``agents.sb3`` import without stable-baselines3, torch or Ray.
"""

from __future__ import annotations

import os
import subprocess
import sys

import pytest
from source_tree import ROOT, imports_in, imports_of, module_name, source_files

#: The layers, lowest first: (name, module prefixes). The package root ``soccer_env`` registers
#: the environments, so it belongs to their layer. ``agents`` is layered by subpackage: what
#: every layer shares (``common``), the scripted teams, numpy policies and the learner's view,
#: the shipped baselines, what needs stable-baselines3, its vectorised environments, runs
#: (resolving, evaluation, training), studies (matches, ratings, ablations); its root is a thin
#: front above them all.
LAYERS = (
    ("estimators", ("estimators",)),
    ("presets and state", ("soccer_env.presets", "soccer_env.state", "soccer_env.validation")),
    ("simulation", ("soccer_env.sim",)),
    ("sensors", ("soccer_env.sensors",)),
    ("perception", ("soccer_env.perception",)),
    ("observations", ("soccer_env.observations",)),
    ("rendering", ("soccer_env.render",)),
    ("environments", ("soccer_env.envs", "soccer_env")),
    ("protocols", ("soccer_env.protocol",)),
    ("agents: common", ("agents.common",)),
    ("agents: scripted", ("agents.scripted",)),
    ("agents: policies", ("agents.policies",)),
    ("agents: baselines", ("agents.baselines",)),
    ("agents: sb3", ("agents.sb3",)),
    ("agents: vec", ("agents.vec",)),
    ("agents: runs", ("agents.runs",)),
    ("agents: studies", ("agents.studies",)),
    ("agents: live", ("agents.live",)),
    ("agents: front", ("agents",)),
    ("application", ("soccer_lab",)),
)
#: What the estimators may import besides the standard library and themselves: numpy, numba
#: (their compiled kernels), and OpenCV in the colour operations of the image trackers only.
ESTIMATOR_LIBRARIES = {"numpy": None, "numba": None, "cv2": ("estimators.image.colour",)}

#: The layers of ``agents`` that run without the learning libraries (numpy and gymnasium
#: only), and those libraries.
NUMPY_ONLY_AGENTS = ("agents: common", "agents: scripted", "agents: policies",
                     "agents: baselines", "agents: front")
LEARNING_LIBRARIES = ("stable_baselines3", "sb3_contrib", "torch", "ray")
#: Modules above those layers that import the learning libraries only in the calls that need
#: them, so that the command line's eval and train (its options, its checks) and the
#: evaluation of numpy policies start without them.
DEFERRED_LIBRARIES = ("agents.sb3", "agents.sb3.algorithms", "agents.sb3.model_files",
                      "agents.sb3.normalization", "agents.sb3.policies", "agents.vec",
                      "agents.runs", "agents.runs.folders", "agents.runs.resolve",
                      "agents.runs.evaluation", "agents.runs.imitation", "agents.runs.training",
                      "agents.studies")


def layer_of(module: str) -> int | None:
    """Index of the layer of ``module`` (the longest matching prefix), None outside the
    package's code."""
    best, best_len = None, -1
    for i, (_, prefixes) in enumerate(LAYERS):
        for p in prefixes:
            if (module == p or module.startswith(p + ".")) and len(p) > best_len:
                best, best_len = i, len(p)
    return best


def test_every_module_has_a_layer():
    assert source_files(), "no source files found"
    assert [module_name(p) for p in source_files() if layer_of(module_name(p)) is None] == []


@pytest.mark.parametrize("path", source_files(), ids=lambda p: module_name(p))
def test_imports_point_down(path):
    me = module_name(path)
    mine = layer_of(me)
    wrong = []
    for imp in imports_of(path):
        line, target = imp.line, imp.module
        theirs = layer_of(target)
        if theirs is not None and theirs > mine:
            wrong.append(f"line {line}: {target} ({LAYERS[theirs][0]})")
    assert not wrong, f"{me} ({LAYERS[mine][0]}) imports from higher layers: {wrong}"


@pytest.mark.parametrize("path", sorted((ROOT / "estimators").rglob("*.py")),
                         ids=lambda p: module_name(p))
def test_estimators_need_numpy_only(path):
    import sys

    me = module_name(path)
    third_party = []
    for imp in imports_of(path):
        line, target = imp.line, imp.module
        top = target.split(".")[0]
        if top in sys.stdlib_module_names or top == "estimators" or top == "__future__":
            continue
        allowed = ESTIMATOR_LIBRARIES.get(top, ())
        if allowed is None or me in (allowed or ()):
            continue
        third_party.append(f"line {line}: {target}")
    assert not third_party, f"{me} imports {third_party}"


def test_the_checker_sees_imports_inside_functions():
    """The check is not vacuous: upward imports hidden in a function, relative or dynamic,
    are found."""
    source = ("def f():\n    from agents import ScriptedGoalkeeper\n"
              "    from ..envs import goalkeeper\n"
              "    import importlib\n    importlib.import_module('soccer_lab.cli')\n")
    sim = layer_of("soccer_env.sim")
    found = [i.module for i in imports_in(source, "soccer_env.sim")
             if (layer_of(i.module) or 0) > sim]
    assert found == ["agents", "soccer_env.envs.goalkeeper", "soccer_lab.cli"]


def test_agents_modules_sit_in_their_layers():
    """Every module of ``agents`` but its root lies in one of its layered subpackages (or is
    one of the scripted modules), none in the front by default."""
    front = next(i for i, (name, _) in enumerate(LAYERS) if name == "agents: front")
    loose = [m for m in map(module_name, source_files())
             if m.startswith("agents.") and layer_of(m) == front]
    assert loose == []


def test_numpy_only_layers_import_without_the_learning_libraries():
    """The layers below ``agents.sb3`` (and the modules that defer the libraries to the calls
    that need them) import with stable-baselines3, sb3-contrib, torch and Ray blocked, and
    load none of them."""
    numpy_only = set(NUMPY_ONLY_AGENTS)
    modules = [m for m in map(module_name, source_files())
               if m.split(".")[0] == "agents" and LAYERS[layer_of(m)][0] in numpy_only]
    modules += list(DEFERRED_LIBRARIES)
    assert "agents.policies.numpy_policy" in modules and "agents.baselines" in modules
    code = (f"import sys\nfor name in {LEARNING_LIBRARIES!r}:\n    sys.modules[name] = None\n"
            f"import importlib\nfor m in {modules!r}:\n    importlib.import_module(m)\n"
            f"loaded = [n for n in sys.modules if n.split('.')[0] in {LEARNING_LIBRARIES!r} "
            "and sys.modules[n] is not None]\nassert not loaded, loaded\n")
    run = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True,
                         env={**os.environ, "PYTHONPATH": str(ROOT)})
    assert run.returncode == 0, run.stderr
