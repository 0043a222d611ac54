"""VeriGraph: scene graphs as an execution verifier for LLM robot planning.

The public names are loaded on first use (`lazy_loader.attach_stub`; the list is
`__init__.pyi`, which type checkers read), so that `import verigraph.<something>` runs no
more than that something needs: checking one PDDL plan from the shell does not pay for
the pydantic models of the scene-graph path. `from verigraph import validate_plan` and
`verigraph.SceneGraph` work as usual; every package below does the same.
"""

import lazy_loader

__version__ = "0.1.0"
__getattr__, __dir__, __all__ = lazy_loader.attach_stub(__name__, __file__)
