"""The `--scene` argument, read the same way by every subcommand: a scene file, a
built-in scene id (cup_on_book, ...), or (agent only) the generator as FAMILY:SEED[:N]."""

from __future__ import annotations

import json
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


MAX_DICTIONARY_FILE_BYTES = 1024 * 1024


def dictionary_argument(value: str) -> Any:
    """`--dictionary NAME|FILE.json`: a built-in dictionary (or all, or behavior), or a
    JSON file holding a dictionary of the user's own, in the inline form a scene may carry
    (`{"extends": "tableware", "objects": {"laptop": {"surface": true}}}`, docs/worlds.md).
    A file is fine here: the CLI runs on the user's machine (the MCP path stays inline).
    Errors name the option and the problem, never the file's content."""
    from pydantic import ValidationError

    from verigraph.graph.behavior import BEHAVIOR
    from verigraph.graph.dictionary import BUILTIN_DICTIONARIES, InlineDictionary

    names = (*BUILTIN_DICTIONARIES, "all", BEHAVIOR)
    if value in names:
        return value
    path = Path(value)
    fix = (f"use one of {', '.join(names)}, or a .json file "
           "{\"extends\": ..., \"objects\": {label: {surface, container, capacity}}}")
    if not path.is_file():
        raise VeriGraphError(f"'{value[:120]}' is neither a built-in dictionary nor a file",
                             field="--dictionary", value=value[:120], fix=fix)
    if path.stat().st_size > MAX_DICTIONARY_FILE_BYTES:
        raise VeriGraphError(f"dictionary file {value[:120]} is over 1 MiB",
                             field="--dictionary", value=value[:120], fix=fix)
    try:
        data = json.loads(path.read_bytes())
        return InlineDictionary.model_validate(data)
    except (ValueError, RecursionError, UnicodeDecodeError) as exc:
        where = ""
        if isinstance(exc, ValidationError) and exc.errors():
            first = exc.errors()[0]
            loc = ".".join(str(p) for p in first["loc"])
            where = f": {loc + ': ' if loc else ''}{first['msg']}"
        elif isinstance(exc, json.JSONDecodeError):
            where = f": not JSON (line {exc.lineno} column {exc.colno})"
        elif isinstance(exc, RecursionError):
            where = ": nested too deeply"
        raise VeriGraphError(f"dictionary file {value[:120]} is not a dictionary{where}",
                             field="--dictionary", value=value[:120], fix=fix) from None


def with_dictionary(graph: Any, value: str | None) -> Any:
    """The scene graph with `--dictionary` as its dictionary (unchanged without it)."""
    if value is None:
        return graph
    from verigraph.graph.model import SceneGraph

    data = graph.model_dump(mode="python")
    data["dictionary"] = dictionary_argument(value)
    return SceneGraph.model_validate(data)
