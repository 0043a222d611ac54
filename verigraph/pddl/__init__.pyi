"""PDDL plans in general: STRIPS with typing, negative preconditions, equality, constants.

Layer: `pddl`, below `actions` (docs/architecture.md): it imports `errors`, `budget` and
two import-free modules of `graph` (`graph.bulk`, the process-wide collector pause, and
`graph.support`, the support index the blocks world shares with `WorldState`), nothing
else. `syntax` owns the S-expression reader and the plan-line forms both engines read;
`blocksworld/` is the native blocks-world engine. `validate_pddl_dict` picks the engine:
the native blocks world for any domain that is one up to renaming, the STRIPS simulator
for the rest. Reports are plain dicts; `actions.pddl.as_validation_report` makes the
pydantic model at the MCP boundary. See docs/validator.md.
"""

from .model import SUPPORTED_REQUIREMENTS as SUPPORTED_REQUIREMENTS
from .model import Domain as Domain
from .model import Problem as Problem
from .model import Schema as Schema
from .plans import Step as Step
from .plans import parse_strips_plan as parse_strips_plan
from .reader import PddlInputError as PddlInputError
from .reader import UnsupportedRequirementError as UnsupportedRequirementError
from .reader import read_domain as read_domain
from .reader import read_problem as read_problem
from .simulate import simulate as simulate
from .simulate import validate_strips_dict as validate_strips_dict
from .syntax import PddlSyntaxError as PddlSyntaxError
from .text import planbench_verdict as planbench_verdict
from .validate import ENGINES as ENGINES
from .validate import validate_pddl_dict as validate_pddl_dict

__all__ = [
    "Domain",
    "ENGINES",
    "PddlInputError",
    "PddlSyntaxError",
    "Problem",
    "SUPPORTED_REQUIREMENTS",
    "Schema",
    "Step",
    "UnsupportedRequirementError",
    "parse_strips_plan",
    "planbench_verdict",
    "read_domain",
    "read_problem",
    "simulate",
    "validate_pddl_dict",
    "validate_strips_dict",
]
