"""PDDL blocks world in: the 4-operator hand domain and the 3-operator move domain.

Layer: part of `pddl` (it reads PDDL with `pddl.syntax`): a recognised domain and
problem become a native scene (blocks, a table, and a hand that holds one block), and
the plan is checked by the hand model in `hand.py`. The report is plain data; the
`ValidationReport` form is `actions.pddl.validate_pddl_plan`.
"""

from .domain import BlocksDomain as BlocksDomain
from .domain import UnsupportedDomainError as UnsupportedDomainError
from .domain import recognise_domain as recognise_domain
from .plans import PlanStep as PlanStep
from .plans import parse_blocks_plan as parse_blocks_plan
from .problem import BlocksProblem as BlocksProblem
from .problem import native_state as native_state
from .problem import read_blocks_problem as read_blocks_problem
from .validate import validate_blocks_dict as validate_blocks_dict

__all__ = [
    "BlocksDomain",
    "BlocksProblem",
    "PlanStep",
    "UnsupportedDomainError",
    "native_state",
    "parse_blocks_plan",
    "read_blocks_problem",
    "recognise_domain",
    "validate_blocks_dict",
]
