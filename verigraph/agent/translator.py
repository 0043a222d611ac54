"""A rule-based instruction-to-goal translator for block-world instructions.

The named baseline for the language group: it reads only the instruction text and the
scene graph (what a planner's prompt shows) and writes a partial goal graph (the edges
the instruction asks for). Its grammar, case-insensitive:

    clause  := VERB NP PLACE NP | NP ("should be" | "should end up" | "belongs") PLACE NP
             | "build a tower of the C1, C2 and C3 blocks with the C1 one at the bottom ..."
    NP      := "the table" | "the C block" | "the block (under|beneath|below) the C block"
             | "the block (that is)? on (top of)? the C block" | "(all the|every|each) C block(s)"
             | "every block that is not C" | "all blocks except the C ones"
    PLACE   := "on" | "onto" | "on top of" | "to"

with clauses joined by ", then", "; " or ". ". Referents are resolved once, on the scene
the instruction was given in (the first request), so "the block under the green one"
keeps meaning that block after it moves. Anything outside the grammar is reported as
untranslated; the accuracy the benchmark reports is the share of instructions whose
translation equals the ground-truth goal.
"""

from __future__ import annotations

import re

from verigraph.agent.models import PlannerRequest
from verigraph.graph.goal import Goal
from verigraph.graph.model import Edge, SceneGraph
from verigraph.graph.state import WorldState

_C = r"([a-z]+)"
NP_PATTERNS: tuple[tuple[str, str], ...] = (
    ("table", r"the table"),
    ("under", rf"the block (?:under|beneath|below) the {_C} (?:block|one)"),
    ("above", rf"the block (?:that is |sitting )?on (?:top of )?the {_C} (?:block|one)"),
    ("all", rf"(?:all the|all|every|each) {_C} blocks?"),
    ("not", rf"(?:every|each|any) block that is(?: not|n't) {_C}"),
    ("except", rf"all (?:the )?blocks except the {_C} ones"),
    ("the", rf"the {_C} (?:block|one)"),
)
PLACE = r"(?:on top of|onto|on|to)"
VERB = r"(?:put|move|place|set|stack)"
SHOULD = r"(?:should be|should end up|should sit|belongs?)"


class TranslationError(ValueError):
    """The instruction (or a part of it) is outside the translator's grammar."""


def _np_regex() -> str:
    return "|".join(f"(?:{p})" for _, p in NP_PATTERNS)


def _resolve(phrase: str, state: WorldState) -> list[str]:
    """The objects a noun phrase names in `state`."""
    colours = {o: str(i.attrs.get("color", "")) for o, i in state.objects.items()
               if i.props.movable}
    for kind, pattern in NP_PATTERNS:
        m = re.fullmatch(pattern, phrase)
        if m is None:
            continue
        if kind == "table":
            tables = [o for o, i in state.objects.items() if not i.props.movable]
            return tables[:1]
        colour = m.group(1)
        named = sorted(o for o, c in colours.items() if c == colour)
        if kind == "all":
            return named
        if kind in ("not", "except"):
            return sorted(o for o, c in colours.items() if c != colour)
        if len(named) != 1:
            raise TranslationError(f"'{phrase}' does not name exactly one block")
        if kind == "the":
            return named
        if kind == "under":
            below = state.support.get(named[0])
            if below is None or below[1] not in colours:
                raise TranslationError(f"nothing block-like is under the {colour} block")
            return [below[1]]
        above = list(state.carried[named[0]])
        if len(above) != 1:
            raise TranslationError(f"no single block is on the {colour} block")
        return above
    raise TranslationError(f"'{phrase}' is not a noun phrase I know")


def _clause(clause: str, state: WorldState) -> list[tuple[str, str]]:
    np = _np_regex()
    tower = re.fullmatch(rf"build a tower of the {_C}, {_C} and {_C} blocks with the \1 one at "
                         r"the bottom(?: and the \3 one on top)?", clause)
    if tower is not None:
        a, b, c = (_resolve(f"the {g} block", state)[0] for g in tower.groups())
        table = _resolve("the table", state)[0]
        return [(a, table), (b, a), (c, b)]
    shape = re.fullmatch(rf"{VERB} (?:{np}) {PLACE} (?:{np})", clause) or re.fullmatch(
        rf"(?:{np}) {SHOULD} {PLACE} (?:{np})", clause)
    if shape is None:
        raise TranslationError(f"cannot read '{clause}'")
    # the destination is the last "PLACE NP" that runs to the end; the subject is before it
    dest = next((m for m in re.finditer(rf"\b{PLACE} ({np})$", clause)), None)
    if dest is None:
        raise TranslationError(f"no place in '{clause}'")
    place = dest.group(1)
    head = clause[:dest.start()].strip()
    head = re.sub(rf"^{VERB} ", "", head)
    subject = re.sub(rf" {SHOULD}$", "", head)
    targets = _resolve(place, state)
    if len(targets) != 1:
        raise TranslationError(f"'{place}' must name one place")
    return [(o, targets[0]) for o in _resolve(subject, state) if o != targets[0]]


def translate(instruction: str, graph: SceneGraph) -> Goal:
    """The partial goal graph `instruction` asks for on `graph`; TranslationError if unread."""
    state = WorldState.from_graph(graph)
    text = instruction.strip().lower().rstrip(".")
    text = re.sub(r"\s+leave everything else as it is$", "", text).rstrip(".")
    clauses = [c.strip() for c in re.split(r",? then |; |\. ", text) if c.strip()]
    wanted: dict[str, str] = {}
    for clause in clauses:
        for obj, target in _clause(clause, state):
            wanted[obj] = target
    if not wanted:
        raise TranslationError("the instruction asks for nothing I can check")
    edges = [Edge(source=o, relation="on", target=t) for o, t in sorted(wanted.items())]
    return Goal(graph=SceneGraph(nodes=list(graph.nodes), edges=edges,
                                 dictionary=graph.dictionary),
                partial=True, instruction=instruction)


def same_goal(a: Goal, b: Goal) -> bool:
    """Whether two graph goals ask for the same edges (the translation-accuracy check)."""
    return a.graph is not None and b.graph is not None and a.partial == b.partial \
        and a.graph.edge_keys() == b.graph.edge_keys()


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
