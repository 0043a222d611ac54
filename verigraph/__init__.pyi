"""VeriGraph: scene graphs as an execution verifier for LLM robot planning."""

from .actions import (
    AlignAction as AlignAction,
)
from .actions import (
    MoveAction as MoveAction,
)
from .actions import (
    ValidationReport as ValidationReport,
)
from .actions import (
    Violation as Violation,
)
from .actions import (
    execute_until_violation as execute_until_violation,
)
from .actions import (
    parse_plan as parse_plan,
)
from .actions import (
    validate_plan as validate_plan,
)
from .errors import VeriGraphError as VeriGraphError
from .graph import Goal as Goal
from .graph import SceneGraph as SceneGraph
from .graph import WorldState as WorldState

__version__: str
__all__ = [
    "AlignAction",
    "Goal",
    "MoveAction",
    "SceneGraph",
    "ValidationReport",
    "VeriGraphError",
    "Violation",
    "WorldState",
    "execute_until_violation",
    "parse_plan",
    "validate_plan",
]
