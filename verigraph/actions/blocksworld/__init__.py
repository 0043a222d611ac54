"""PDDL blocks world in: the 4-operator hand domain and the 3-operator move domain.

Layer: part of `actions` (it needs only `graph` and `actions`): a recognised domain and
problem become a native scene (blocks, a table, and a hand that holds one block), and
the plan is checked by the hand model in `hand.py`. The solver layer may use it; it
uses nothing above `actions`.
"""

from verigraph.actions.blocksworld.domain import (
    BlocksDomain,
    UnsupportedDomainError,
    recognise_domain,
)
from verigraph.actions.blocksworld.plans import PlanStep, parse_blocks_plan
from verigraph.actions.blocksworld.problem import BlocksProblem, native_state, read_problem
from verigraph.actions.blocksworld.sexpr import PddlSyntaxError
from verigraph.actions.blocksworld.validate import validate_blocks_dict, validate_pddl_plan

__all__ = [
    "BlocksDomain", "BlocksProblem", "PddlSyntaxError", "PlanStep", "UnsupportedDomainError",
    "native_state", "parse_blocks_plan", "read_problem", "recognise_domain",
    "validate_blocks_dict", "validate_pddl_plan",
]
