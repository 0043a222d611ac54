"""VeriGraph: scene graphs as an execution verifier for LLM robot planning."""

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
