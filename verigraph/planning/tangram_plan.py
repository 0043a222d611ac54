"""Fewest align actions back to a tangram figure: the reference solver's goal-directed
breadth-first search (`verigraph.solver.tangram`), which the oracle planner and the
tangram suite use as the solve tool does."""

from __future__ import annotations

from verigraph.solver.tangram import (
    MAX_DEPTH,
    MAX_NODES,
    Contacts,
    contact_key,
    missing_contacts,
    tangram_plan,
)

__all__ = ["MAX_DEPTH", "MAX_NODES", "Contacts", "contact_key", "missing_contacts",
           "tangram_plan"]
