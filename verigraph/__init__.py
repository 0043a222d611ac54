"""VeriGraph: scene graphs as an execution verifier for LLM robot planning.

The public names below are loaded on first use (PEP 562 `__getattr__`), so that
`import verigraph.<something>` runs no more than that something needs: checking one PDDL
plan from the shell does not pay for the pydantic models of the scene-graph path.
`from verigraph import validate_plan` and `verigraph.SceneGraph` work as before.
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from verigraph.actions import (
        AlignAction,
        MoveAction,
        ValidationReport,
        Violation,
        execute_until_violation,
        parse_plan,
        validate_plan,
    )
    from verigraph.errors import VeriGraphError
    from verigraph.graph import Goal, SceneGraph, WorldState

__version__ = "0.1.0"
__all__ = [
    "AlignAction", "Goal", "MoveAction", "SceneGraph", "ValidationReport", "VeriGraphError",
    "Violation", "WorldState", "execute_until_violation", "parse_plan", "validate_plan",
]

# Public name -> the package that defines it (its public API, not a private module).
_SOURCES = {
    "AlignAction": "verigraph.actions", "MoveAction": "verigraph.actions",
    "ValidationReport": "verigraph.actions", "Violation": "verigraph.actions",
    "execute_until_violation": "verigraph.actions", "parse_plan": "verigraph.actions",
    "validate_plan": "verigraph.actions", "VeriGraphError": "verigraph.errors",
    "Goal": "verigraph.graph", "SceneGraph": "verigraph.graph", "WorldState": "verigraph.graph",
}


def __getattr__(name: str) -> Any:
    """Import a public name's package on first access and keep the name here."""
    source = _SOURCES.get(name)
    if source is None:  # an AttributeError lets `from verigraph import tools` find a package
        raise AttributeError(f"module 'verigraph' has no attribute '{name}'")
    value = getattr(importlib.import_module(source), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))
