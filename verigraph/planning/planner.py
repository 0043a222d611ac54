"""The one small interface every planner backend implements.

A planner turns a `PlannerRequest` into a `PlannerReply`. It never talks to the verifier
itself: the loop does, so every backend is checked by exactly the same tools.

Privilege is declared, not promised: a planner whose class sets `privileged = True`
(only the oracle, the ceiling of every table) receives the ground-truth goal in
`PlannerRequest.privileged_goal`; every other planner gets None there, so it cannot
read what it must not. Wrappers (retries, transcripts, latency) pass the flag through.
"""

from __future__ import annotations

from typing import Protocol, runtime_checkable

from verigraph.planning.models import PlannerReply, PlannerRequest


@runtime_checkable
class Planner(Protocol):
    """Proposes actions for the current graph; `name` appears in traces and tables."""

    name: str

    def propose(self, request: PlannerRequest) -> PlannerReply:
        """At most `request.k` actions (or a whole plan when k is None), or the end token."""
        ...

    def close(self) -> None:
        """Release connections or subprocesses; a closed planner is not used again."""
        ...


def is_privileged(planner: object) -> bool:
    """Whether `planner` declared itself privileged (`privileged = True`); default no."""
    return getattr(planner, "privileged", False) is True
