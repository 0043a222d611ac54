"""Reference planning: the optimal/anytime solver under a budget, and PDDL export."""

from verigraph.solver.budget import (
    DEFAULT_MAX_EXPANSIONS,
    DEFAULT_MEMORY_LIMIT_MB,
    DEFAULT_TIME_LIMIT_S,
)
from verigraph.solver.result import SolveResult
from verigraph.solver.search import solve

__all__ = ["DEFAULT_MAX_EXPANSIONS", "DEFAULT_MEMORY_LIMIT_MB", "DEFAULT_TIME_LIMIT_S",
           "SolveResult", "solve"]
