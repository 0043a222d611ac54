"""PDDL blocks world in: the 4-operator hand domain and the 3-operator move domain.

Layer: part of `pddl` (it reads PDDL with `pddl.syntax`): a recognised domain and
problem become a native scene (blocks, a table, and a hand that holds one block), and
the plan is checked by the hand model in `hand.py`. The report is plain data; the
`ValidationReport` form is `actions.pddl.validate_pddl_plan`.

The names are loaded on first use (`lazy_loader.attach_stub`; the list is `__init__.pyi`,
which type checkers read), so importing one module of the package runs only what it needs.
"""

import lazy_loader

__getattr__, __dir__, __all__ = lazy_loader.attach_stub(__name__, __file__)
