"""PDDL plans in general: STRIPS with typing, negative preconditions, equality, constants.

Layer: `pddl`, below `actions` (docs/architecture.md): it imports `errors`, `budget` and
two import-free modules of `graph` (`graph.bulk`, the process-wide collector pause, and
`graph.support`, the support index the blocks world shares with `WorldState`), nothing
else. `syntax` owns the S-expression reader and the plan-line forms both engines read;
`blocksworld/` is the native blocks-world engine. `validate_pddl_dict` picks the engine:
the native blocks world for any domain that is one up to renaming, the STRIPS simulator
for the rest. Reports are plain dicts; `actions.pddl.as_validation_report` makes the
pydantic model at the MCP boundary. See docs/validator.md.

The names are loaded on first use (`lazy_loader.attach_stub`; the list is `__init__.pyi`,
which type checkers read), so importing one module of the package runs only what it needs.
"""

import lazy_loader

__getattr__, __dir__, __all__ = lazy_loader.attach_stub(__name__, __file__)
