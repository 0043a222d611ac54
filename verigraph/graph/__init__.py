"""Scene graphs, the dictionary D, relations R, goals and graph diffs.

The names are loaded on first use (`lazy_loader.attach_stub`; the list is `__init__.pyi`,
which type checkers read), so importing one module of the package runs only what it needs.
"""

import lazy_loader

__getattr__, __dir__, __all__ = lazy_loader.attach_stub(__name__, __file__)
