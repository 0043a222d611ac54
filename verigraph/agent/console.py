"""Human-readable lines for each iteration and the final verdict (the CLI's output)."""

from __future__ import annotations

from typing import TextIO

from verigraph.planning.models import EpisodeTrace, IterationRecord

VERDICT_WORDS = {
    "clean": "all executed",
    "violation": "REFUSED by the verifier",
    "malformed": "MALFORMED answer",
    "premature_done": "done REFUSED: goal not reached",
    "end_token": "end token accepted",
    "planner_error": "PLANNER FAILED",
}


def iteration_lines(record: IterationRecord) -> list[str]:
    """Proposal, verdict, feedback and tau of one iteration."""
    proposed = ", ".join(record.proposed) or "(nothing)"
    lines = [f"[{record.iteration}] proposed: {proposed}"]
    if record.dropped:
        lines.append(f"    dropped (beyond k or after done): {', '.join(record.dropped)}")
    lines.append(f"    verdict: {VERDICT_WORDS[record.verdict]}; executed: "
                 f"{', '.join(record.executed) or 'nothing'}")
    if record.feedback is not None:
        lines.append(f"    feedback: {record.feedback.text}")
    goal = {True: "holds", False: "not yet", None: "not checkable"}[record.goal_satisfied]
    lines.append(f"    tau={record.tau}; goal {goal}; {record.seconds:.2f} s")
    if record.note:
        lines.append(f"    note: {record.note}")
    return lines


def print_iteration(record: IterationRecord, stream: TextIO) -> None:
    stream.write("\n".join(iteration_lines(record)) + "\n")
    stream.flush()


def header_lines(trace: EpisodeTrace) -> list[str]:
    lines = [f"episode {trace.episode_id} over {trace.transport}: planner {trace.planner}, "
             f"mode {trace.mode}, k={trace.k}, t={trace.threshold}, "
             f"done policy {trace.done_policy}"]
    if trace.initial_graph is not None:
        lines.append("start: " + ("; ".join(trace.initial_graph.sentences()) or "no edges"))
    if trace.instruction:
        lines.append(f"instruction: {trace.instruction}")
    if trace.goal is not None:
        if trace.goal.graph is not None:
            lines.append("goal: " + "; ".join(trace.goal.graph.sentences()))
        if trace.goal.predicate:
            lines.append(f"goal predicate: {trace.goal.predicate}")
        if trace.goal.formula is not None:
            lines.append(f"goal formula: {trace.goal.formula_text()}")
    return lines


def verdict_line(trace: EpisodeTrace) -> str:
    detail = f" ({trace.verdict_summary})" if trace.verdict_summary and not trace.success \
        else ""
    return trace.summary() + detail
