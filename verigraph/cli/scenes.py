"""The `--scene` argument, read the same way by every subcommand: a scene file, a
built-in scene id (cup_on_book, ...), or (agent only) the generator as FAMILY:SEED[:N]."""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from verigraph.errors import VeriGraphError

GENERATOR = re.compile(r"^(?P<family>[a-z_]+):(?P<seed>\d+)(?::(?P<n>\d+))?$")


@dataclass(frozen=True)
class SceneArgument:
    """What `--scene` named: exactly one of a graph (from a file), a built-in id, a
    generator spec."""

    graph: Any = None  # SceneGraph read from a file
    builtin: str | None = None
    generator: dict[str, Any] | None = None


def scene_argument(scene: str, *, generator: bool = True) -> SceneArgument:
    """Resolve `--scene`; a VeriGraphError names the three accepted forms otherwise."""
    from verigraph.graph.builtin_scenes import BUILTIN_SCENES

    if Path(scene).is_file():
        from verigraph.graph.io import load_scene

        return SceneArgument(graph=load_scene(scene))
    if scene in BUILTIN_SCENES:
        return SceneArgument(builtin=scene)
    if generator and (m := GENERATOR.match(scene)) is not None:
        spec: dict[str, Any] = {"family": m.group("family"), "seed": int(m.group("seed"))}
        if m.group("n"):
            spec["n_objects"] = int(m.group("n"))
        return SceneArgument(generator=spec)
    forms = "a built-in scene or FAMILY:SEED" if generator else "nor a built-in scene"
    raise VeriGraphError(f"'{scene}' is not a scene file, {forms}", field="--scene",
                         value=scene, fix=f"use one of {', '.join(BUILTIN_SCENES)}, a "
                         ".json/.yaml scene file" + (", or e.g. blocks:3" if generator else ""))


def scene_graph(scene: str) -> tuple[Any, Any]:
    """(graph, built-in goal or None) for subcommands that need the graph itself."""
    from verigraph.graph.builtin_scenes import BUILTIN_GOALS, BUILTIN_SCENES

    resolved = scene_argument(scene, generator=False)
    if resolved.builtin is None:
        return resolved.graph, None
    goal = BUILTIN_GOALS.get(resolved.builtin)
    return BUILTIN_SCENES[resolved.builtin](), goal() if goal else None
