"""Actions, constraints, validation and plan parsing."""

from verigraph.actions.execution import ExecutionResult, execute_until_violation
from verigraph.actions.feedback import CONSTRAINT_DESCRIPTIONS, Violation
from verigraph.actions.model import Action, AlignAction, AnyAction, DoneAction, MoveAction
from verigraph.actions.parser import parse_plan
from verigraph.actions.report import StepReport, ValidationReport, validate_plan
from verigraph.actions.validator import GraphEdit, apply_action, validate_action

__all__ = [
    "CONSTRAINT_DESCRIPTIONS", "Action", "AlignAction", "AnyAction", "DoneAction",
    "ExecutionResult", "GraphEdit", "MoveAction", "StepReport", "ValidationReport", "Violation",
    "apply_action", "execute_until_violation", "parse_plan", "validate_action", "validate_plan",
]
