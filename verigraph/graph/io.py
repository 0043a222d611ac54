"""Reading and writing scene graphs and goals as JSON or YAML, with errors that name the fix."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import yaml
from pydantic import ValidationError

from verigraph.errors import InputFileError
from verigraph.graph.bulk import collector_paused, graph_items
from verigraph.graph.goal import Goal, looks_like_formula
from verigraph.graph.model import SceneGraph

MAX_FILE_BYTES = 64 * 1024 * 1024


def read_structured(path: str | Path, *, what: str) -> Any:
    """Decode a JSON or YAML file (chosen by suffix; YAML also reads JSON)."""
    text = read_text(path, what=what)
    return decode_structured(text, what=what, json_only=Path(path).suffix.lower() == ".json")


def read_text(path: str | Path, *, what: str) -> str:
    """A JSON or YAML file's text, with errors that name the fix."""
    p = Path(path)
    if not p.is_file():
        raise InputFileError(f"{what} file '{p}' does not exist", field=what, value=str(p),
                             fix="give the path of an existing .json or .yaml file")
    if p.stat().st_size > MAX_FILE_BYTES:
        raise InputFileError(f"{what} file is larger than {MAX_FILE_BYTES} bytes", field=what,
                             value=str(p), fix="split the file or remove unused data")
    try:
        text = p.read_text(encoding="utf-8")
    except UnicodeDecodeError:
        raise InputFileError(f"{what} file is not UTF-8 text", field=what, value=str(p),
                             fix="save it as UTF-8 JSON or YAML") from None
    return text


def decode_structured(text: str, *, what: str, json_only: bool = False) -> Any:
    try:
        if json_only:
            return json.loads(text)
        return yaml.safe_load(text)
    except json.JSONDecodeError as exc:
        raise InputFileError(f"invalid JSON in {what}: {exc.msg} at line {exc.lineno}, column "
                             f"{exc.colno}", field=what, value=None,
                             fix="fix the JSON syntax at that position") from None
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem_mark", None)
        where = f" at line {mark.line + 1}, column {mark.column + 1}" if mark else ""
        raise InputFileError(f"invalid YAML in {what}{where}", field=what, value=None,
                             fix="fix the YAML syntax at that position") from None


def _pydantic_error(exc: ValidationError, what: str, example: str) -> InputFileError:
    err = exc.errors()[0]
    loc = ".".join(str(p) for p in err["loc"]) or what
    more = f" (and {exc.error_count() - 1} more)" if exc.error_count() > 1 else ""
    return InputFileError(f"{what}.{loc}: {err['msg']}{more}", field=f"{what}.{loc}",
                          value=err.get("input") if not isinstance(err.get("input"), dict | list)
                          else None, fix=f"follow the documented shape, e.g. {example}")


SCENE_EXAMPLE = ('{"nodes": [{"id": "cup", "label": "cup"}], "edges": [{"source": "cup", '
                 '"relation": "on", "target": "table"}]}')


def scene_from_data(data: Any, *, what: str = "scene") -> SceneGraph:
    if not isinstance(data, dict):
        raise InputFileError(f"{what} must be a mapping with 'nodes' and 'edges'", field=what,
                             value=type(data).__name__, fix=f"use {SCENE_EXAMPLE}")
    try:
        with collector_paused(graph_items(data)):
            return SceneGraph.model_validate(data)
    except ValidationError as exc:
        raise _pydantic_error(exc, what, SCENE_EXAMPLE) from None


# The fewest bytes a node or an edge takes as JSON: text of this size holds at most
# len // JSON_ITEM_BYTES items, enough to tell a large graph from a small one.
JSON_ITEM_BYTES = 24


def scene_from_json(text: str | bytes, *, what: str = "scene") -> SceneGraph:
    """A scene graph straight from JSON text (one pass in pydantic's parser, no
    intermediate Python dicts): the fastest way to load a large graph."""
    try:
        with collector_paused(len(text) // JSON_ITEM_BYTES):
            return SceneGraph.model_validate_json(text)
    except ValidationError as exc:
        raise _pydantic_error(exc, what, SCENE_EXAMPLE) from None


def goal_from_data(data: Any) -> Goal:
    try:
        return Goal.parse(data)
    except ValidationError as exc:
        raise _pydantic_error(exc, "goal", '{"predicate": "single_stack"}, {"formula": '
                              '"(forall ...)"} or a scene graph, optionally with "partial": '
                              'true') from None


def load_scene(path: str | Path) -> SceneGraph:
    """Read a scene graph file (JSON or YAML)."""
    return scene_from_data(read_structured(path, what="scene"))


def load_goal(path: str | Path) -> Goal:
    """Read a goal file: a scene graph, `{"graph": ..., "partial": true}`, a predicate,
    `{"formula": "(forall ...)"}`, or a formula as the whole text (a `.bddl` file's
    `(:goal ...)` section too)."""
    text = read_text(path, what="goal")
    if looks_like_formula(text):
        return Goal.parse(text.strip())
    return goal_from_data(decode_structured(text, what="goal",
                                            json_only=Path(path).suffix.lower() == ".json"))


def save_graph(graph: SceneGraph, path: str | Path) -> None:
    """Write JSON or YAML by suffix."""
    p = Path(path)
    data = graph.model_dump(exclude_none=True, exclude_defaults=False)
    if p.suffix.lower() in (".yaml", ".yml"):
        p.write_text(yaml.safe_dump(data, sort_keys=False))
    else:
        p.write_text(json.dumps(data, indent=2) + "\n")
