"""PDDL plans in general: STRIPS with typing, negative preconditions, equality, constants.

Layer: part of `actions` (uses `graph` and the blocks-world package beside it, whose
S-expression reader and plan-line forms it shares). `validate_pddl_dict` picks the
engine: the native blocks world for any domain that is one up to renaming, the STRIPS
simulator for the rest. See docs/validator.md.

The names are loaded on first use (`lazy_loader.attach_stub`; the list is `__init__.pyi`,
which type checkers read), so importing one module of the package runs only what it needs.
"""

import lazy_loader

__getattr__, __dir__, __all__ = lazy_loader.attach_stub(__name__, __file__)
