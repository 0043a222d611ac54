"""The planner prompt for one iteration, from the same templates the MCP prompts serve.

The text pieces (objects, graph, goal, actions, constraints, history) come from
`verigraph.prompts.filling`, which the server's `iterative_planner` and `direct_planner`
prompts use too, so an LLM behind this agent reads what a chat assistant reads. Only the
feedback line differs: the agent also reports malformed answers and a premature end
token, which the server never sees.
"""

from __future__ import annotations

from collections.abc import Sequence

from verigraph import prompts
from verigraph.graph.goal import Goal
from verigraph.graph.state import WorldState
from verigraph.planning.models import Feedback, Mode
from verigraph.prompts import filling as pieces

TEMPLATE = {"iterative": "iterative_planner", "direct": "direct_planner"}


def feedback_line(feedback: Feedback | None, iteration: int) -> str:
    """The 'Feedback on your previous answer' text."""
    if feedback is not None:
        return feedback.text
    return "None: this is the first answer." if iteration <= 1 else \
        "None: every action of your previous answer was executed."


def history_line(history: Sequence[str]) -> str:
    if not history:
        return "Nothing has been executed yet."
    return "Executed so far, in order:\n" + "\n".join(f"- {a}" for a in history)


def planner_prompt(mode: Mode, state: WorldState, goal: Goal | None, *, k: int | None,
                   instruction: str | None, history: Sequence[str],
                   feedback: Feedback | None, iteration: int) -> str:
    """The rendered iterative or direct planner prompt.

    `goal` is what the planner may see: for instruction tasks the caller passes None so
    that only the instruction is shown, while the episode keeps the ground truth.
    """
    relations = pieces.prompt_relations(state)
    household = pieces.speaks_household(state)
    return prompts.render(
        TEMPLATE[mode], relations=", ".join(relations), objects=pieces.objects_text(state),
        current_graph=pieces.graph_text(state), goal=pieces.goal_section(goal, instruction),
        actions=pieces.actions_text(relations, household),
        constraints=pieces.constraints_text(relations, household),
        history=history_line(history), feedback=feedback_line(feedback, iteration),
        k=k if k is not None else "all", tool_hint="")
