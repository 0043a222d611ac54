"""The `rule-based` planner: the instruction translator in front of the reference solver.

The named language baseline: it reads the goal its prompt shows or, when the prompt
shows only words, the rule-based translator's goal (`translator.py`), and plans it
optimally. Where the goal graph is shown it plans exactly like the oracle; on language
tasks its success is bounded by the translation accuracy, which the benchmark reports
separately.
"""

from __future__ import annotations

from verigraph.planning.goal_reader import GoalReader
from verigraph.planning.models import PlannerReply, PlannerRequest
from verigraph.planning.oracle import chunk, reference_plan


class RuleBasedPlanner:
    """Translated (or shown) goal, optimal plan, first k actions."""

    name = "rule-based"

    def __init__(self) -> None:
        self.reader = GoalReader()

    def propose(self, request: PlannerRequest) -> PlannerReply:
        goal, note = self.reader.read(request)
        plan, why = reference_plan(request, goal)
        return PlannerReply(actions=chunk(plan, request.k),
                            note=note if goal is None else why or note)

    def close(self) -> None:
        return None
