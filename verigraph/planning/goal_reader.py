"""The goal a non-privileged planner works towards, read from its prompt.

The rule-based translator itself (grammar, `translate`, `read_instruction`) is a pure
function of words and a scene graph and lives in `verigraph.graph.translator`, where the
set_goal tool uses it too.
"""

from __future__ import annotations

from verigraph.graph.goal import Goal
from verigraph.graph.translator import TranslationError, translate
from verigraph.planning.models import PlannerRequest

__all__ = ["GoalReader"]


class GoalReader:
    """The goal a non-privileged planner works towards: the one its prompt shows, else the
    translation of the instruction, made once on the first scene it sees."""

    def __init__(self) -> None:
        self._translated: dict[str, tuple[Goal | None, str | None]] = {}

    def read(self, request: PlannerRequest) -> tuple[Goal | None, str | None]:
        """(goal, note): the note says why there is none or that it was translated."""
        if request.goal is not None:
            return request.goal, None
        if not request.instruction:
            return None, "the prompt shows no goal and no instruction"
        if request.instruction not in self._translated:
            try:
                goal: Goal | None = translate(request.instruction, request.graph)
                note = "goal translated from the instruction"
            except TranslationError as exc:
                goal, note = None, f"instruction not understood: {exc}"
            self._translated[request.instruction] = (goal, note)
        return self._translated[request.instruction]
