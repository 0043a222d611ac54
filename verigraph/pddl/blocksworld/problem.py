"""Read a blocks-world problem into the native scene: blocks, a table and (4-op) a hand.

The hand is a fixed holder of capacity one (`block in hand` = holding), the table a fixed
surface without a capacity limit, every block a movable surface of capacity one.
The initial state must be a real blocks-world state (each block on the table, on one
block or held; `clear` exactly where nothing rests and nothing is held; the hand empty
exactly when it holds nothing): a state the scene graph cannot represent is refused
with a message naming the fact, rather than judged differently from a PDDL validator.
"""

from __future__ import annotations

from dataclasses import dataclass

from verigraph.graph.support import SupportIndex
from verigraph.pddl.blocksworld.domain import BlocksDomain, UnsupportedDomainError
from verigraph.pddl.syntax import PddlSyntaxError, SExpr, define_body, typed_names

GoalAtom = tuple[str, tuple[str, ...]]  # (role, args)


@dataclass(slots=True)
class BlocksProblem:
    """Objects, the initial support of each block and the goal atoms (by role)."""

    name: str
    blocks: list[str]
    on: dict[str, str]  # block -> block below
    ontable: set[str]
    held: str | None
    goal: list[GoalAtom]
    table: str
    hand: str | None


def _fresh(base: str, taken: set[str]) -> str:
    name, k = base, 2
    while name in taken:
        name, k = f"{base}_{k}", k + 1
    return name


def _atoms(expr: SExpr, domain: BlocksDomain, where: str) -> list[GoalAtom]:
    """The atoms of a conjunction (or of one atom); a plain known atom takes one dict
    lookup, anything else (and every error) the checks below."""
    items = expr[1:] if isinstance(expr, list) and expr and expr[0] == "and" else [expr]
    roles = domain.predicates
    out: list[GoalAtom] = []
    for item in items:
        if type(item) is list and item:
            role = roles.get(item[0]) if type(item[0]) is str else None
            args = item[1:]
            if role is not None and all(type(a) is str for a in args):
                out.append((role, tuple(args)))  # type: ignore[arg-type]
                continue
        if not (isinstance(item, list) and item and all(isinstance(a, str) for a in item)):
            raise UnsupportedDomainError(f"the {where} holds {item!r}; only positive "
                                         "blocks-world atoms are supported")
        role = domain.predicates.get(str(item[0]))
        if role is None:
            raise UnsupportedDomainError(f"the {where} uses predicate '{item[0]}', which the "
                                         "domain does not declare")
        out.append((role, tuple(str(a) for a in item[1:])))
    return out


def _init_atoms(items: list[SExpr], domain: BlocksDomain) -> list[GoalAtom]:
    """The initial atoms; a plain known atom takes one dict lookup, anything else (and
    every error) goes through `_atoms`. `(= (total-cost) 0)` is skipped."""
    roles = domain.predicates
    out: list[GoalAtom] = []
    for item in items:
        if isinstance(item, list) and item:
            role = roles.get(item[0]) if isinstance(item[0], str) else None
            args = item[1:]
            if role is not None and all(type(a) is str for a in args):
                out.append((role, tuple(args)))  # type: ignore[arg-type]
                continue
            if item[0] == "=":
                continue
        out.extend(_atoms(item, domain, "initial state"))
    return out


def read_blocks_problem(text: str, domain: BlocksDomain) -> BlocksProblem:
    """Parse and check a problem file's text against a recognised domain."""
    name, sections = define_body(text, what="problem", kind="problem")
    objects: list[tuple[str, str | None]] = []
    init: list[GoalAtom] = []
    goal: list[GoalAtom] | None = None
    for section in sections:
        if not isinstance(section, list) or not section:
            continue
        head = section[0]
        if head == ":objects":
            objects = typed_names(section[1:], what="problem")
        elif head == ":init":
            init = _init_atoms(section[1:], domain)
        elif head == ":goal":
            goal = _atoms(section[1] if len(section) > 1 else [], domain, "goal")
        elif head in (":domain", ":requirements", ":metric"):
            continue
        else:
            raise UnsupportedDomainError(f"problem section {head} is outside blocks world")
    if goal is None:
        raise PddlSyntaxError("the problem has no (:goal ...)", field="problem", value=name,
                              fix="add (:goal (and ...))")
    wrong_type = [o for o, t in objects if t is not None and domain.block_types
                  and t not in domain.block_types]
    if wrong_type:
        raise UnsupportedDomainError(f"objects of types the domain does not declare: "
                                     f"{', '.join(wrong_type)}")
    blocks = list(dict.fromkeys(o for o, _ in objects))
    if len(blocks) != len(objects):  # the later declaration never silently wins
        seen: set[str] = set()
        for o, _ in objects:
            if o in seen:
                raise PddlSyntaxError(f"object {o} is declared twice", field="problem", value=o,
                                      fix=f"declare {o} once: remove or rename the second {o}")
            seen.add(o)
    return _check_state(name, blocks, init, goal, domain)


def _check_state(name: str, blocks: list[str], init: list[GoalAtom], goal: list[GoalAtom],
                 domain: BlocksDomain) -> BlocksProblem:
    known = set(blocks)

    def bad(reason: str) -> UnsupportedDomainError:
        return UnsupportedDomainError(f"the initial state is not a blocks-world state: {reason}")

    on: dict[str, str] = {}
    ontable: set[str] = set()
    clear: set[str] = set()
    held: list[str] = []
    handempty = False
    for role, args in [*init, *goal]:
        for a in args:
            if a not in known:
                raise PddlSyntaxError(f"{domain.atom(role, *args)} names '{a}', which "
                                      "(:objects ...) does not declare", field="problem",
                                      value=a, fix=f"declare {a} in :objects")
    for role, args in init:
        if role == "on":
            if args[0] in on:
                raise bad(f"{args[0]} is on both {on[args[0]]} and {args[1]}")
            on[args[0]] = args[1]
        elif role == "ontable":
            ontable.add(args[0])
        elif role == "clear":
            clear.add(args[0])
        elif role == "holding":
            held.append(args[0])
        else:
            handempty = True
    below_count: dict[str, int] = {}
    for below in on.values():
        below_count[below] = below_count.get(below, 0) + 1
    for b in blocks:
        places = (b in on) + (b in ontable) + (b in held)
        if places != 1:
            raise bad(f"{b} is in {places} places (on a block, on the table, held)")
        if below_count.get(b, 0) > 1:
            raise bad(f"more than one block is on {b}")
        should_be_clear = not below_count.get(b) and b not in held
        if should_be_clear != (b in clear):
            state = "missing" if should_be_clear else "stated"
            raise bad(f"{domain.atom('clear', b)} is {state} though "
                      f"{'nothing is on it' if should_be_clear else 'it is covered or held'}")
    if domain.family == "4op":
        if len(held) > 1:
            raise bad(f"the hand holds {len(held)} blocks")
        if handempty == bool(held):
            raise bad(f"{domain.atom('handempty')} must hold exactly when nothing is held")
    for b in blocks:  # cycles: walk down from every block
        seen: set[str] = set()
        cur: str | None = b
        while cur is not None and cur in on:
            if cur in seen:
                raise bad(f"{cur} rests on itself through a cycle")
            seen.add(cur)
            cur = on[cur]
    taken = set(blocks)
    table = _fresh("table", taken)
    hand = _fresh("hand", taken | {table}) if domain.family == "4op" else None
    return BlocksProblem(name, blocks, on, ontable, held[0] if held else None, goal, table,
                         hand)


class BlocksState(SupportIndex):
    """The scene the hand model works on, as plain dicts: each object's label, its support
    (`block -> (relation, target)`: `on` a block or the table, `in` the hand) and what
    each object carries. It is `graph.state.WorldState`'s support index without the
    scene-graph dictionary and its pydantic models, so checking a blocks-world plan from
    the shell loads neither (docs/validator.md, Start-up)."""

    __slots__ = ("objects",)

    def __init__(self) -> None:
        super().__init__()
        self.objects: dict[str, str] = {}  # id -> label: table, gripper or block


def native_state(problem: BlocksProblem) -> BlocksState:
    """The scene the problem describes, indexed for the validator (no pydantic model)."""
    state = BlocksState()
    state.objects[problem.table] = "table"
    state.carried[problem.table] = {}
    if problem.hand is not None:
        state.objects[problem.hand] = "gripper"
        state.carried[problem.hand] = {}
    for b in problem.blocks:
        state.objects[b] = "block"
        state.carried[b] = {}
    for b in problem.blocks:
        if b in problem.on:
            state.set_support(b, "on", problem.on[b])
        elif b in problem.ontable:
            state.set_support(b, "on", problem.table)
        elif problem.hand is not None:
            state.set_support(b, "in", problem.hand)
    return state
