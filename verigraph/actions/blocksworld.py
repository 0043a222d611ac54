"""The blocks-world engine's library form, where docs/validator.md names it.

The engine is `verigraph.pddl.blocksworld`; its report as a `ValidationReport` is
`verigraph.actions.pddl.validate_pddl_plan`, re-exported here under the documented path
`verigraph.actions.blocksworld.validate_pddl_plan`.
"""

from verigraph.actions.pddl import validate_pddl_plan

__all__ = ["validate_pddl_plan"]
