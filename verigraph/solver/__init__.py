"""Reference planning: the optimal solver and PDDL export for cross-checking."""

from verigraph.solver.search import SolveResult, solve

__all__ = ["SolveResult", "solve"]
