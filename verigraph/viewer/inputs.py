"""What a person pastes into the viewer page, turned into validate_plan's input.

The scene is a built-in scene id or a graph in JSON/YAML; the plan is text (one action
per line) or a JSON list; the goal is optional: a predicate name or a goal/graph in
JSON/YAML. Every problem is a VeriGraphError naming the field and the fix.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

from pydantic import ValidationError

from verigraph.errors import InputFileError, VeriGraphError
from verigraph.graph.builtin_scenes import BUILTIN_SCENES
from verigraph.graph.goal import PREDICATES, Goal, looks_like_formula
from verigraph.graph.io import decode_structured, goal_from_data, scene_from_data
from verigraph.graph.model import SceneGraph
from verigraph.tools.acting import ValidatePlanInput
from verigraph.tools.context import ToolContext
from verigraph.viewer.page import report_html
from verigraph.viewer.views import EpisodeView, plan_view

MAX_FIELD_CHARS = 2_000_000


def _text(value: Any, field: str) -> str:
    if not isinstance(value, str):
        raise InputFileError(f"{field} must be text", field=field, value=type(value).__name__,
                             fix=f"send {field} as a string")
    if len(value) > MAX_FIELD_CHARS:
        raise InputFileError(f"{field} is longer than {MAX_FIELD_CHARS} characters",
                             field=field, value=len(value), fix=f"shorten the {field}")
    return value.strip()


def plan_input(scene: Any, plan: Any, goal: Any = "") -> ValidatePlanInput:
    """validate_plan's input from the page's three text fields."""
    scene_text, plan_text, goal_text = (_text(scene, "scene"), _text(plan, "plan"),
                                        _text(goal or "", "goal"))
    if not scene_text:
        raise InputFileError("the scene is empty", field="scene", value=None,
                             fix=f"paste a scene graph, or a built-in id: "
                                 f"{', '.join(BUILTIN_SCENES)}")
    if not plan_text:
        raise InputFileError("the plan is empty", field="plan", value=None,
                             fix="write one action per line, e.g. move(cup, on, desk)")
    arguments: dict[str, Any] = {"plan": plan_text}
    if plan_text.startswith("["):
        arguments["plan"] = decode_structured(plan_text, what="plan", json_only=True)
    if scene_text in BUILTIN_SCENES:
        arguments["scene_id"] = scene_text
    else:
        arguments["graph"] = scene_from_data(decode_structured(scene_text, what="scene"))
    if goal_text:
        arguments["goal"] = (Goal.parse(goal_text)  # a predicate's name or a formula
                             if goal_text in PREDICATES or looks_like_formula(goal_text)
                             else goal_from_data(decode_structured(goal_text, what="goal")))
    try:
        return ValidatePlanInput.model_validate(arguments)
    except ValidationError as exc:
        err = exc.errors()[0]
        where = ".".join(str(p) for p in err["loc"]) or "input"
        raise InputFileError(f"{where}: {err['msg'].removeprefix('Value error, ')}",
                             field=where, value=None, fix="correct that field") from None


def write_report(ctx: ToolContext, path: str | Path, scene: SceneGraph, plan: str,
                 goal: Goal | None, *, all_errors: bool = False, title: str = "plan report"
                 ) -> EpisodeView:
    """`verigraph validate --html FILE`: the per-step view of one validation, in one file."""
    arguments: dict[str, Any] = {"plan": plan, "graph": scene, "goal": goal,
                                 "all_errors": all_errors}
    if plan.lstrip().startswith("["):
        arguments["plan"] = json.loads(plan)
    try:
        params = ValidatePlanInput.model_validate(arguments)
    except ValidationError as exc:
        raise VeriGraphError(f"cannot build the HTML report: {exc.errors()[0]['msg']}",
                             field="--html", value=str(path),
                             fix="validate without --html, or split the plan") from None
    view = plan_view(ctx, params, title=title)
    try:
        Path(path).write_text(report_html(view), encoding="utf-8")
    except OSError as exc:
        raise InputFileError(f"cannot write the HTML report: {exc.strerror}", field="--html",
                             value=str(path), fix="give a path in an existing, writable "
                                                  "folder") from None
    return view
