"""Prompt templates (planner and scene-graph generation) as text files, and `render`.

Filling them from a state, a goal or a dictionary is `verigraph.prompts.filling`.

The templates live next to this file as Markdown with `$name` placeholders
(`string.Template`), so they are readable and editable without touching code. The MCP
server exposes them as prompts; the agent loop calls `render` directly.

>>> text = render("direct_planner", relations="on", objects="- cup (cup)",
...               current_graph="cup on table", goal="cup on shelf", actions="move(x, on, y)",
...               constraints="- already_there", tool_hint="")
>>> "done" in text
True
"""

from __future__ import annotations

import string
from functools import cache
from importlib import resources

from verigraph.errors import VeriGraphError

PROMPT_NAMES = ("iterative_planner", "direct_planner", "scene_graph_generation")


@cache
def template(name: str) -> string.Template:
    """The raw template of a prompt by name."""
    if name not in PROMPT_NAMES:
        raise VeriGraphError(f"no prompt named '{name}'", field="name", value=name,
                             fix=f"use one of {', '.join(PROMPT_NAMES)}")
    text = resources.files("verigraph.prompts").joinpath(f"{name}.md").read_text("utf-8")
    return string.Template(text)


def variables(name: str) -> list[str]:
    """The placeholders a prompt needs, in order of first use."""
    seen: list[str] = []
    for match in template(name).pattern.finditer(template(name).template):
        key = match.group("named") or match.group("braced")
        if key and key not in seen:
            seen.append(key)
    return seen


def render(name: str, **values: object) -> str:
    """Fill a prompt; every placeholder must be given (missing ones are named)."""
    missing = [v for v in variables(name) if v not in values]
    if missing:
        raise VeriGraphError(f"prompt '{name}' needs values for: {', '.join(missing)}",
                             field="values", value=missing,
                             fix="pass every placeholder as a keyword argument "
                                 "(use an empty string for optional ones such as tool_hint)")
    text = template(name).substitute({k: str(v) for k, v in values.items()})
    return text.rstrip() + "\n"


__all__ = ["PROMPT_NAMES", "render", "template", "variables"]
