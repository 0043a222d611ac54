"""A rule-based instruction-to-goal translator: words plus a scene graph -> goal edges.

A pure function of the instruction and the graph it was given on, so the planners (the
named baseline for the language group) and the set_goal tool (a goal proposal the
client confirms) read words the same way. Its grammar, case-insensitive:

    clause  := VERB? NP PLACE NP | NP ("should be" | "should end up" | "belongs") PLACE NP
             | "build a tower of the C1, C2 and C3 blocks with the C1 one at the bottom ..."
    NP      := "the table" | "the C block" | "the block (under|beneath|below) the C block"
             | "the block (that is)? on (top of)? the C block" | "(all the|every|each) C block(s)"
             | "every block that is not C" | "all blocks except the C ones"
             | "(the)? NAME" (an object id or label, spaces for underscores) | NP "and" NP
    PLACE   := "on" | "onto" | "on top of" | "to"   (relation on)
             | "in" | "into" | "inside"            (relation in)

with clauses joined by ", then", "; ", ". " or ", ". Referents are resolved once, on
the scene the instruction was given in, so "the block under the green one" keeps
meaning that block after it moves. Anything outside the grammar is reported as not
understood, clause by clause (`read_instruction`); `translate` refuses the whole
instruction if any clause is outside it.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field

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
ON_WORDS = r"(?:on top of|onto|on|to)"
IN_WORDS = r"(?:into|inside|in)"
PLACE = rf"(?:{ON_WORDS}|{IN_WORDS})"
VERB = r"(?:put|move|place|set|stack)"
SHOULD = r"(?:should be|should end up|should sit|belongs?)"
NAME = r"(?:the )?[a-z0-9_][a-z0-9_ ,]*?"  # commas: a list ("the pot, the pan and the kettle")
# "the board on the counter with the knife on it": the second object's place is the first.
WITH_IT = re.compile(rf"(.+?) ({PLACE}) (.+?) with (.+?) ({PLACE}) it")
MAX_CLAUSE = 400  # characters of one clause; a spoken clause is a small fraction of it


class TranslationError(ValueError):
    """The instruction (or a part of it) is outside the translator's grammar."""


@dataclass
class Reading:
    """What the translator made of an instruction, clause by clause."""

    edges: list[Edge] = field(default_factory=list)
    understood: list[str] = field(default_factory=list)
    not_understood: list[tuple[str, str]] = field(default_factory=list)  # (clause, why)
    # Edges read but left out of `edges` because the scene cannot hold them all at once
    # (more objects on a place than its capacity): (edge sentence, why). Never silent.
    unplaced: list[tuple[str, str]] = field(default_factory=list)


def _np_regex() -> str:
    return "|".join(f"(?:{p})" for _, p in NP_PATTERNS)


def _named(phrase: str, state: WorldState) -> list[str] | None:
    """Objects named by id or label ("the cutting board", "kettle and pot"), or None."""
    parts = [p.strip() for p in re.split(r",? and |, ", phrase) if p.strip()]
    found: list[str] = []
    for part in parts:
        name = re.sub(r"^the ", "", part).replace(" ", "_")
        if name in state.objects:
            found.append(name)
            continue
        label = state.dictionary.resolve(name)
        same = [o for o, i in state.objects.items() if label is not None and i.label == label]
        if len(same) > 1:
            raise TranslationError(f"'{part}' could be any of {', '.join(sorted(same))}")
        if not same:
            return None
        found.append(same[0])
    return found or None


def _resolve(phrase: str, state: WorldState) -> list[str]:
    """The objects a noun phrase names in `state`."""
    colours = {o: str(i.attrs.get("color", "")) for o, i in state.objects.items()
               if i.props.movable}
    for kind, pattern in NP_PATTERNS:
        m = re.fullmatch(pattern, phrase)
        if m is None:
            continue
        if kind == "table":
            if "table" in state.objects:
                return ["table"]
            tables = [o for o, i in state.objects.items() if not i.props.movable]
            return tables[:1]
        colour = m.group(1)
        named = sorted(o for o, c in colours.items() if c == colour)
        if kind == "all":
            return named
        if kind in ("not", "except"):
            return sorted(o for o, c in colours.items() if c != colour)
        if len(named) != 1:
            if kind == "the" and (by_name := _named(phrase, state)):
                return by_name
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
    by_name = _named(phrase, state)
    if by_name:
        return by_name
    raise TranslationError(f"'{phrase}' is not a noun phrase I know")


Wanted = list[tuple[str, str, str]]  # (object, relation, target)


def _clause(clause: str, state: WorldState) -> Wanted:
    if len(clause) > MAX_CLAUSE:  # each place word is tried against the rest: quadratic
        raise TranslationError(f"a clause is at most {MAX_CLAUSE} characters; this one has "
                               f"{len(clause)}")
    np = _np_regex()
    tower = re.fullmatch(rf"build a tower of the {_C}, {_C} and {_C} blocks with the \1 one at "
                         r"the bottom(?: and the \3 one on top)?", clause)
    if tower is not None:
        a, b, c = (_resolve(f"the {g} block", state)[0] for g in tower.groups())
        table = _resolve("the table", state)[0]
        return [(a, "on", table), (b, "on", a), (c, "on", b)]
    phrase = rf"(?:{np}|{NAME})"
    shape = re.fullmatch(rf"(?:{VERB} )?{phrase} {PLACE} {phrase}", clause) or re.fullmatch(
        rf"{phrase} {SHOULD} {PLACE} {phrase}", clause)
    if shape is None:
        raise TranslationError(f"cannot read '{clause}'")
    # the destination is the last "PLACE NP" that runs to the end; the subject is before it
    dest = None
    why = f"no place I know in '{clause}'"
    for m in re.finditer(rf"\b({PLACE}) ", clause):
        rest = clause[m.end():]
        if not re.fullmatch(phrase, rest):
            continue
        try:
            if len(_resolve(rest, state)) == 1:
                dest = m
                break
            why = f"'{rest}' must name one place"
        except TranslationError as exc:
            why = str(exc)
    if dest is None:
        raise TranslationError(why)
    relation = "in" if re.fullmatch(IN_WORDS, dest.group(1)) else "on"
    place = clause[dest.end():]
    head = clause[:dest.start()].strip()
    head = re.sub(rf"^{VERB} ", "", head)
    subject = re.sub(rf" {SHOULD}$", "", head)
    targets = _resolve(place, state)
    if len(targets) != 1:
        raise TranslationError(f"'{place}' must name one place")
    return [(o, relation, targets[0]) for o in _resolve(subject, state) if o != targets[0]]


def _clauses(text: str) -> list[str]:
    return [c.strip() for c in re.split(r",? then |; |\. |: ", text) if c.strip()]


def _comma_parts(clause: str) -> list[str]:
    """A clause's comma-separated parts, a list item without a place of its own kept with
    the part after it ("the pot, the pan and the kettle on the stove" stays whole), a
    leading "and" dropped, and "A on B with C on it" read as "A on B" and "C on A"."""
    parts: list[str] = []
    waiting = ""
    for raw in clause.split(", "):
        part = re.sub(r"^(?:and|then) ", "", raw.strip()) if not waiting else raw.strip()
        if not part:
            continue
        part = f"{waiting}, {part}" if waiting else part
        if re.search(rf"\b{PLACE} ", part) is None:
            waiting = part
            continue
        waiting = ""
        parts.extend(_with_it(part))
    if waiting:
        parts.append(waiting)
    return parts


def _with_it(part: str) -> list[str]:
    # WITH_IT's three open groups are cubic in the text: a part past a clause's length is
    # left whole (and refused by name as one clause).
    m = WITH_IT.fullmatch(part) if len(part) <= MAX_CLAUSE else None
    if m is None:
        return [part]
    subject = re.sub(rf"^{VERB} ", "", m.group(1))
    return [f"{m.group(1)} {m.group(2)} {m.group(3)}", f"{m.group(4)} {m.group(5)} {subject}"]


def _read_clause(clause: str, state: WorldState) -> list[tuple[str, Wanted | str]]:
    """(clause, wanted edges or why not); a clause that fails whole is tried at its commas."""
    try:
        return [(clause, _clause(clause, state))]
    except TranslationError as exc:
        parts = _comma_parts(clause)
        if len(parts) < 2 and parts == [clause]:
            return [(clause, str(exc))]
        read: list[tuple[str, Wanted | str]] = []
        for part in parts:
            try:
                read.append((part, _clause(part, state)))
            except TranslationError as inner:
                read.append((part, str(inner)))
        if all(isinstance(w, str) for _, w in read):
            return [(clause, str(exc))]
        return read


def _over_capacity(wanted: dict[str, tuple[str, str]], state: WorldState
                   ) -> list[tuple[str, str]]:
    """The wanted edges a place cannot take (more objects than its capacity), in the
    order they were asked for after the first `capacity` ones; removed from `wanted`."""
    by_target: dict[str, list[str]] = {}
    for obj, (_, target) in wanted.items():
        by_target.setdefault(target, []).append(obj)
    unplaced = []
    for target, objs in by_target.items():
        info = state.objects.get(target)
        capacity = info.props.capacity if info is not None else None
        if capacity is None or len(objs) <= capacity:
            continue
        label = info.label if info is not None else target
        for obj in objs[capacity:]:
            relation = wanted.pop(obj)[0]
            unplaced.append((
                f"{obj} {relation} {target}",
                f"{target} holds {capacity} (what the scene says a {label} holds; a built-in "
                "default unless the scene's attrs gave it) and the words put "
                f"{len(objs)} objects there ({', '.join(objs)}): ask the user which to leave "
                "out, or whether the real one holds more"))
    return unplaced


def read_instruction(instruction: str, graph: SceneGraph) -> Reading:
    """Every clause the grammar reads (with its goal edges) and every one it does not."""
    state = WorldState.from_graph(graph)
    # Single spaces: the patterns below then read each run of spaces once, not once per
    # space (a long run of spaces was quadratic).
    text = " ".join(instruction.lower().split()).rstrip(".")
    text = re.sub(r" leave everything else as it is$", "", text).rstrip(".")
    text = re.sub(r"\s*\([^)]*\)", lambda m: ". " + m.group(0).strip()[1:-1] + ". ", text)
    text = re.sub(rf" (?:lying|sitting|standing|resting)(?= {PLACE} )", "", text)
    wanted: dict[str, tuple[str, str]] = {}
    reading = Reading()
    for clause in _clauses(text):
        for part, result in _read_clause(clause, state):
            if isinstance(result, str):
                reading.not_understood.append((part, result))
                continue
            reading.understood.append(part)
            for obj, relation, target in result:
                wanted[obj] = (relation, target)
    reading.unplaced = _over_capacity(wanted, state)
    reading.edges = [Edge(source=o, relation=r, target=t)
                     for o, (r, t) in sorted(wanted.items())]
    return reading


def translate(instruction: str, graph: SceneGraph) -> Goal:
    """The partial goal graph `instruction` asks for on `graph`; TranslationError if unread."""
    reading = read_instruction(instruction, graph)
    if reading.not_understood:
        clause, why = reading.not_understood[0]
        raise TranslationError(why if clause in why else f"{why} (in '{clause}')")
    if reading.unplaced:
        edge, why = reading.unplaced[0]
        raise TranslationError(f"cannot place '{edge}': {why}")
    if not reading.edges:
        raise TranslationError("the instruction asks for nothing I can check")
    return Goal(graph=SceneGraph(nodes=graph.stateless_nodes(), edges=reading.edges,
                                 dictionary=graph.dictionary),
                partial=True, instruction=instruction)


def same_goal(a: Goal, b: Goal) -> bool:
    """Whether two graph goals ask for the same edges (the translation-accuracy check)."""
    return a.graph is not None and b.graph is not None and a.partial == b.partial \
        and a.graph.edge_keys() == b.graph.edge_keys()
