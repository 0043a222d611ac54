"""A rule-based instruction-to-goal translator: words plus a scene graph -> a goal.

A pure function of the instruction and the graph it was given on, so the planners (the
named baseline for the language group) and the set_goal tool (a goal proposal the
client confirms) read words the same way. Its grammar, case-insensitive:

    clause  := VERB? NP PLACE NP | NP SHOULD PLACE NP
             | "build a tower of the C1, C2 and C3 blocks with the C1 one at the bottom ..."
             | STATE                                  (an object state)
             | "no" KIND ("may" "stay")? PLACE ("any" | "a" | "the")? NP   (a formula)
    STATE   := ("turn" | "switch") ("on" | "off") NP | ("turn" | "switch") NP ("on" | "off")
             | ("open" | "close" | "shut" | "cook" | "heat" | "freeze") NP
             | ("keep" | "leave") NP WORD | NP ("should be" | "must be" | "stays" ...) WORD
    WORD    := "open" | "closed" | "on" | "off" | "cooked" | "hot" | "frozen"
    NP      := "the table" | "the C block" | "the block (under|beneath|below) the C block"
             | "the block (that is)? on (top of)? the C block" | "(all the|every|each) C block(s)"
             | "every block that is not C" | "all blocks except the C ones"
             | "(all the|every|each) KIND(s)" | "(the)? NAME" (an id or label, spaces for
               underscores) | NP "and" NP
    PLACE   := "on" | "onto" | "on top of" | "to"   (relation on)
             | "in" | "into" | "inside"            (relation in)
             | "under" | "underneath" | "beneath" | "below"   (relation under)
             | "next to" | "beside"                (relation nextto)

with clauses joined by ", then", "; ", ". ", ", " or "and" before a verb. Referents are
resolved once, on the scene the instruction was given in, so "the block under the green
one" keeps meaning that block after it moves. A place word is read only as a relation the
scene's world has (a tabletop has no `under`), a state only on an object with its role
(a plate is not openable): anything else is reported as not understood, clause by clause
(`read_instruction`); `translate` refuses the whole instruction if any clause is outside
it. "No cup on any plate" has no goal graph (a graph cannot say "not"), so an
instruction with such a clause reads as one formula (`Reading.goal`).
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field

from verigraph.graph.dictionary import STATE_ROLES
from verigraph.graph.goal import Goal
from verigraph.graph.model import Edge, SceneGraph
from verigraph.graph.state import WorldState
from verigraph.reporting import STATE_WORDS

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
UNDER_WORDS = r"(?:underneath|under|beneath|below)"
NEXT_WORDS = r"(?:next to|beside)"
PLACE = rf"(?:{ON_WORDS}|{IN_WORDS}|{UNDER_WORDS}|{NEXT_WORDS})"
VERB = r"(?:put|move|place|set|stack)"
SHOULD = (r"(?:should be|should end up|should sit|should go|must be|must go|has to be|"
          r"have to be|needs? to be|goes|go|belongs?)")
# Object states: the verbs that set one, and the words that name one (as
# `reporting.STATE_WORDS` writes them, and `shut`).
STATE_VERBS = {"turn on": ("toggled_on", True), "switch on": ("toggled_on", True),
               "turn off": ("toggled_on", False), "switch off": ("toggled_on", False),
               "open": ("open", True), "close": ("open", False), "shut": ("open", False),
               "cook": ("cooked", True), "heat up": ("hot", True), "heat": ("hot", True),
               "warm up": ("hot", True), "freeze": ("frozen", True)}
STATE_ADJECTIVES = {"open": ("open", True), "closed": ("open", False),
                    "shut": ("open", False), "on": ("toggled_on", True),
                    "off": ("toggled_on", False), "cooked": ("cooked", True),
                    "hot": ("hot", True), "frozen": ("frozen", True)}
_ADJ = "|".join(STATE_ADJECTIVES)
_SET_VERB = "|".join(sorted((v for v in STATE_VERBS if not v.startswith(("turn", "switch"))),
                            key=len, reverse=True))
STATE_PATTERNS = (
    re.compile(r"(?:turn|switch) (?P<turn>on|off) (?P<np>.+)"),
    re.compile(r"(?:turn|switch) (?P<np>.+) (?P<turn>on|off)"),
    re.compile(rf"(?P<verb>{_SET_VERB}) (?P<np>.+)"),
    re.compile(rf"(?:keep|leave|have) (?P<np>.+) (?P<adj>{_ADJ})"),
    re.compile(rf"(?P<np>.+?) (?:should|must|has to|have to|needs? to|will)? ?"
               rf"(?:be|stay|remain|stays|remains|is|are) (?P<adj>{_ADJ})"),
)
# "no cup (may stay) on any plate": a kind kept off every object of a kind, or off one.
NO_PATTERN = re.compile(
    rf"no ([a-z_ ]+?) (?:(?:may|should|must|can|will) )?(?:(?:be|stay|stays|remain|remains|"
    rf"sit|sits|stand|stands|lie|lies|is|are|left) )?({PLACE}) (?:(any|a|an|the|one) )?"
    r"([a-z0-9_ ]+)")
# A place word's relation, and the formula's word for it.
FORMULA_WORD = {"on": "ontop", "in": "inside", "under": "under", "nextto": "nextto"}
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
    # (object, state key, value): `stove on` is ("stove", "toggled_on", True).
    states: list[tuple[str, str, bool]] = field(default_factory=list)
    # Clauses no goal graph can say ("no cup on any plate"), as formulas.
    formulas: list[str] = field(default_factory=list)
    understood: list[str] = field(default_factory=list)
    not_understood: list[tuple[str, str]] = field(default_factory=list)  # (clause, why)
    # Edges read but left out of `edges` because the scene cannot hold them all at once
    # (more objects on a place than its capacity): (edge sentence, why). Never silent.
    unplaced: list[tuple[str, str]] = field(default_factory=list)

    def asks(self) -> bool:
        """Whether anything checkable was read."""
        return bool(self.edges or self.states or self.formulas)

    def state_sentences(self) -> list[str]:
        """`stove on`, `fridge closed`: the states as set_goal's edges text writes them."""
        return [f"{obj} {STATE_WORDS[key][value]}" for obj, key, value in self.states]

    def formula(self) -> str:
        """Everything read, as one formula: the edges and states as atoms, then the
        formula clauses (`(and (in milk fridge) (toggled_on stove) (forall ...))`)."""
        parts = [f"({e.relation} {e.source} {e.target})" for e in self.edges]
        parts += [f"({key} {obj})" if value else f"(not ({key} {obj}))"
                  for obj, key, value in self.states]
        parts += self.formulas
        return parts[0] if len(parts) == 1 else f"(and {' '.join(parts)})"

    def goal(self, graph: SceneGraph, instruction: str) -> Goal | None:
        """The partial goal read on `graph` (None when nothing was): a goal graph with
        the edges and node states, or, with a formula clause, one formula of it all."""
        if not self.asks():
            return None
        if self.formulas:
            return Goal(formula=self.formula(), partial=True, instruction=instruction)
        states: dict[str, dict[str, bool]] = {}
        for obj, key, value in self.states:
            states.setdefault(obj, {})[key] = value
        nodes = [n.model_copy(update={"state": states[n.id]}) if n.id in states else n
                 for n in graph.stateless_nodes()]
        return Goal(graph=SceneGraph(nodes=nodes, edges=self.edges,
                                     dictionary=graph.dictionary),
                    partial=True, instruction=instruction)


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
    every = re.fullmatch(r"(?:all (?:of )?(?:the )?|every |each )(.+)", phrase)
    if every is not None:
        kind = _kind(every.group(1), state)
        return sorted(o for o, i in state.objects.items() if i.label == kind)
    by_name = _named(phrase, state)
    if by_name:
        return by_name
    raise TranslationError(f"'{phrase}' is not a noun phrase I know")


def _kind(word: str, state: WorldState) -> str:
    """The label a kind word names in the scene (`cups` -> `cup`, a synonym -> its
    label); TranslationError when the scene has no object of that kind."""
    word = word.strip().replace(" ", "_")
    for form in (word, word.removesuffix("s"), word.removesuffix("es")):
        label = state.dictionary.resolve(form) or form
        if any(i.label == label for i in state.objects.values()):
            return label
    raise TranslationError(f"no {word.replace('_', ' ')} in the scene")


Wanted = list[tuple[str, str, str]]  # (object, relation, target)
States = list[tuple[str, str, bool]]  # (object, state key, value)


@dataclass
class _Read:
    """One clause's reading: placements, states and formula clauses."""

    edges: Wanted = field(default_factory=list)
    states: States = field(default_factory=list)
    formulas: list[str] = field(default_factory=list)


def _relation(word: str, state: WorldState) -> str:
    """The relation a place word asks for, if the scene's world has it."""
    relation = ("in" if re.fullmatch(IN_WORDS, word) else
                "under" if re.fullmatch(UNDER_WORDS, word) else
                "nextto" if re.fullmatch(NEXT_WORDS, word) else "on")
    if relation not in state.move_relations:
        raise TranslationError(f"'{word}' asks for {relation}, which this scene's world does "
                               f"not have (objects go {', '.join(state.move_relations)})")
    return relation


def _state_clause(clause: str, state: WorldState) -> States | None:
    """`turn on the stove`, `keep the fridge closed`: the states asked for; None when the
    clause is not a state clause."""
    for pattern in STATE_PATTERNS:
        m = pattern.fullmatch(clause)
        if m is None:
            continue
        said = m.groupdict()
        key, value = (STATE_VERBS[f"turn {said['turn']}"] if said.get("turn") else
                      STATE_VERBS[said["verb"]] if said.get("verb") else
                      STATE_ADJECTIVES[said["adj"]])
        phrase = said["np"]
        try:
            objs = _resolve(phrase, state)
        except TranslationError:
            continue  # "put the pot on the stove" is no state clause: read it as a placement
        role = STATE_ROLES[key]
        for obj in objs:
            info = state.objects[obj]
            if not getattr(info.props, role):
                raise TranslationError(f"{obj} ({info.label}) is not {role}, so it cannot be "
                                       f"{STATE_WORDS[key][value]}")
        return [(obj, key, value) for obj in objs]
    return None


def _no_clause(clause: str, state: WorldState) -> str | None:
    """`no cup on any plate` as `(forall (?c - cup) (not (exists (?p - plate) (ontop ?c
    ?p))))` (`no cup on the tray`: `(forall (?c - cup) (not (ontop ?c tray)))`); None when
    the clause does not start with "no"."""
    m = NO_PATTERN.fullmatch(clause)
    if m is None:
        return None
    kind = _kind(m.group(1), state)
    word = FORMULA_WORD[_relation(m.group(2), state)]
    if m.group(3) == "the":
        places = _resolve(f"the {m.group(4)}", state)
        if len(places) != 1:
            raise TranslationError(f"'the {m.group(4)}' must name one place")
        return f"(forall (?x - {kind}) (not ({word} ?x {places[0]})))"
    other = _kind(m.group(4), state)
    return f"(forall (?x - {kind}) (not (exists (?y - {other}) ({word} ?x ?y))))"


def _clause(clause: str, state: WorldState) -> _Read:
    if len(clause) > MAX_CLAUSE:  # each place word is tried against the rest: quadratic
        raise TranslationError(f"a clause is at most {MAX_CLAUSE} characters; this one has "
                               f"{len(clause)}")
    if (formula := _no_clause(clause, state)) is not None:
        return _Read(formulas=[formula])
    if (states := _state_clause(clause, state)) is not None:
        return _Read(states=states)
    return _Read(edges=_placement(clause, state))


def _placement(clause: str, state: WorldState) -> Wanted:
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
    relation = _relation(dest.group(1), state)
    place = clause[dest.end():]
    head = clause[:dest.start()].strip()
    head = re.sub(rf"^{VERB} ", "", head)
    subject = re.sub(rf" {SHOULD}$", "", head)
    targets = _resolve(place, state)
    if len(targets) != 1:
        raise TranslationError(f"'{place}' must name one place")
    return [(o, relation, targets[0]) for o in _resolve(subject, state) if o != targets[0]]


# "and" starts a new clause before one of these verbs ("put the pot on the stove and turn
# it on" is two clauses; "the pot and the pan" stays one noun phrase).
CLAUSE_VERBS = r"(?:put|move|place|set|stack|turn|switch|open|close|shut|keep|leave|cook|" \
               r"heat|warm|freeze)"


def _clauses(text: str) -> list[str]:
    return [c.strip() for c in re.split(rf",? then |; |\. |: |,? and (?={CLAUSE_VERBS} )", text)
            if c.strip()]


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
        if re.search(rf"\b{PLACE} ", part) is None and \
                re.match(rf"(?:{CLAUSE_VERBS}|no) ", part) is None and \
                re.search(rf" (?:{_ADJ})$", part) is None:  # no place, verb or state of its own
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


def _and_parts(clause: str, state: WorldState) -> list[tuple[str, _Read]] | None:
    """"put the bread next to the bowl and the cup under the table" as its two
    placements (the verb carried over), at the first "and" where both sides read; None
    when there is no such "and"."""
    verb = re.match(rf"{VERB} ", clause)
    for m in re.finditer(r" and ", clause):
        left, right = clause[:m.start()], clause[m.end():]
        if re.search(rf"\b{PLACE} ", left) is None or re.search(rf"\b{PLACE} ", right) is None:
            continue
        try:
            first = _clause(left, state)
        except TranslationError:
            continue
        # "the cup under the table" reads alone; with the verb, for "the cup to ..."
        for said in (right, *((f"{verb.group(0)}{right}",) if verb else ())):
            try:
                return [(left, first), (right, _clause(said, state))]
            except TranslationError:
                continue
    return None


def _read_clause(clause: str, state: WorldState) -> list[tuple[str, _Read | str]]:
    """(clause, its reading or why not); a clause that fails whole is tried at an "and"
    between two placements, then at its commas."""
    try:
        return [(clause, _clause(clause, state))]
    except TranslationError as exc:
        if len(clause) <= MAX_CLAUSE and (pair := _and_parts(clause, state)) is not None:
            return [*pair]
        parts = _comma_parts(clause)
        if len(parts) < 2 and parts == [clause]:
            return [(clause, str(exc))]
        read: list[tuple[str, _Read | str]] = []
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
    states: dict[tuple[str, str], bool] = {}
    reading = Reading()
    for clause in _clauses(text):
        for part, result in _read_clause(clause, state):
            if isinstance(result, str):
                reading.not_understood.append((part, result))
                continue
            reading.understood.append(part)
            for obj, relation, target in result.edges:
                wanted[obj] = (relation, target)
            for obj, key, value in result.states:
                states[obj, key] = value
            reading.formulas.extend(f for f in result.formulas if f not in reading.formulas)
    reading.unplaced = _over_capacity(wanted, state)
    reading.edges = [Edge(source=o, relation=r, target=t)
                     for o, (r, t) in sorted(wanted.items())]
    reading.states = [(obj, key, value) for (obj, key), value in sorted(states.items())]
    return reading


def translate(instruction: str, graph: SceneGraph) -> Goal:
    """The partial goal `instruction` asks for on `graph` (`Reading.goal`); TranslationError
    if any of it is unread."""
    reading = read_instruction(instruction, graph)
    if reading.not_understood:
        clause, why = reading.not_understood[0]
        raise TranslationError(why if clause in why else f"{why} (in '{clause}')")
    if reading.unplaced:
        edge, why = reading.unplaced[0]
        raise TranslationError(f"cannot place '{edge}': {why}")
    goal = reading.goal(graph, instruction)
    if goal is None:
        raise TranslationError("the instruction asks for nothing I can check")
    return goal


def same_goal(a: Goal, b: Goal) -> bool:
    """Whether two graph goals ask for the same edges (the translation-accuracy check)."""
    return a.graph is not None and b.graph is not None and a.partial == b.partial \
        and a.graph.edge_keys() == b.graph.edge_keys()
