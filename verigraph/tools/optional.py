"""Subsystems other issues deliver (simulator, solver, perception), looked up at call time.

The tools work without them (graph-only mode). When a module lands, the matching tool
starts using it without a change here; until then the tool answers with a
FeatureUnavailableError that says what to use instead.
"""

from __future__ import annotations

import importlib
import logging
from collections.abc import Callable
from typing import Any

from verigraph.tools.errors import FeatureUnavailableError

log = logging.getLogger("verigraph.tools")


def _attribute(module: str, name: str) -> Callable[..., Any] | None:
    """`module.name` if the module imports and has it; a broken module counts as absent."""
    try:
        mod = importlib.import_module(module)
    except ImportError as exc:
        if not (exc.name and (exc.name == module or module.startswith(exc.name + "."))):
            log.warning("%s is installed but cannot be imported: %s", module, exc)
        return None
    value = getattr(mod, name, None)
    return value if callable(value) else None


def world_for_graph() -> Callable[..., Any]:
    """`verigraph.sim2d.world_for_graph(graph, seed=0) -> SimWorld`."""
    fn = _attribute("verigraph.sim2d", "world_for_graph")
    if fn is None:
        raise FeatureUnavailableError(
            "the 2D simulator (verigraph.sim2d) is not available in this installation",
            field="simulate", value=True,
            fix="load the scene with simulate=false (graph-only verification)")
    return fn


def generate_scene() -> Callable[..., Any]:
    """`verigraph.sim2d.generate_scene(family, seed, n_objects=None)`: has .graph and .world."""
    fn = _attribute("verigraph.sim2d", "generate_scene")
    if fn is None:
        raise FeatureUnavailableError(
            "the scene generator (verigraph.sim2d.generate_scene) is not available in this "
            "installation", field="generator", value=None,
            fix="load a built-in scene with scene_id (cup_on_book, three_blocks, kitchen_pan) "
                "or pass a graph")
    return fn


def solver() -> Callable[..., Any]:
    """`verigraph.solver.solve(scene_graph_or_state, goal) -> SolveResult`."""
    fn = _attribute("verigraph.solver", "solve")
    if fn is None:
        raise FeatureUnavailableError(
            "the reference solver (verigraph.solver) is not available in this installation",
            field="solve", value=None,
            fix="plan with validate_action / execute_actions feedback instead")
    return fn


def perception() -> Callable[..., Any]:
    """`verigraph.perception.perceive(image_bgr, dictionary=..., task=...)` -> SceneGraph."""
    fn = _attribute("verigraph.perception", "perceive")
    if fn is None:
        raise FeatureUnavailableError(
            "built-in perception (image -> scene graph) is not available yet",
            field="image", value=None,
            fix="use your own vision model: call get_scene_image(episode_id) for the image and "
                "the scene-graph prompt, then send your graph with submit_scene_graph")
    return fn


def perception_report() -> Callable[..., Any] | None:
    """`verigraph.perception.perceive_image(image_bgr, dictionary=...)` -> a result with
    `.graph`, `.warnings`, `.uncertain` and `.confident`; None when absent (then
    `perception()` alone is used and its graph is taken as it is)."""
    return _attribute("verigraph.perception", "perceive_image")


def has(module: str, name: str) -> bool:
    """Whether an optional subsystem entry point exists (used for capability reports)."""
    return _attribute(module, name) is not None
