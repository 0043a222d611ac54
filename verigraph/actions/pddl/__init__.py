"""PDDL plans in general: STRIPS with typing, negative preconditions, equality, constants.

Layer: part of `actions` (uses `graph` and the blocks-world package beside it, whose
S-expression reader and plan-line forms it shares). `validate_pddl_dict` picks the
engine: the native blocks world for any domain that is one up to renaming, the STRIPS
simulator for the rest. See docs/validator.md.
"""

from verigraph.actions.pddl.conversion import as_validation_report
from verigraph.actions.pddl.model import SUPPORTED_REQUIREMENTS, Domain, Problem, Schema
from verigraph.actions.pddl.plans import Step, parse_strips_plan
from verigraph.actions.pddl.reader import (
    PddlInputError,
    UnsupportedRequirementError,
    read_domain,
    read_problem,
)
from verigraph.actions.pddl.simulate import simulate, validate_strips_dict
from verigraph.actions.pddl.text import planbench_verdict, report_text
from verigraph.actions.pddl.validate import ENGINES, validate_pddl_dict

__all__ = [
    "ENGINES", "SUPPORTED_REQUIREMENTS", "Domain", "PddlInputError", "Problem", "Schema", "Step",
    "UnsupportedRequirementError", "as_validation_report", "parse_strips_plan",
    "planbench_verdict", "read_domain", "read_problem", "report_text", "simulate",
    "validate_pddl_dict", "validate_strips_dict",
]
