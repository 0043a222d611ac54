"""Actions, constraints, validation and plan parsing."""

from .execution import ExecutionResult as ExecutionResult
from .execution import execute_until_violation as execute_until_violation
from .feedback import CONSTRAINT_DESCRIPTIONS as CONSTRAINT_DESCRIPTIONS
from .feedback import Violation as Violation
from .model import Action as Action
from .model import AlignAction as AlignAction
from .model import AnyAction as AnyAction
from .model import DoneAction as DoneAction
from .model import MoveAction as MoveAction
from .parser import parse_plan as parse_plan
from .report import StepReport as StepReport
from .report import ValidationReport as ValidationReport
from .report import validate_plan as validate_plan
from .validator import GraphEdit as GraphEdit
from .validator import apply_action as apply_action
from .validator import validate_action as validate_action

__all__ = [
    "Action",
    "AlignAction",
    "AnyAction",
    "CONSTRAINT_DESCRIPTIONS",
    "DoneAction",
    "ExecutionResult",
    "GraphEdit",
    "MoveAction",
    "StepReport",
    "ValidationReport",
    "Violation",
    "apply_action",
    "execute_until_violation",
    "parse_plan",
    "validate_action",
    "validate_plan",
]
