"""Recognise a blocks-world domain: the 4-operator hand family and the 3-operator move family.

A domain is accepted only when every action, after renaming predicates to their roles
(on, ontable, clear, handempty, holding), has exactly the preconditions and effects of
one template below, in any parameter order. The name of an action does not matter
(pick-up, pickup, pick_up). Anything else is refused with "unsupported domain: ...",
so a plan is never judged under rules the native model does not implement.
Inequality preconditions `(not (= ?x ?y))` are allowed; the only one that can change a
verdict is "a block is not moved onto itself" in the 3-operator family, recorded in
`self_move_forbidden`.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import lru_cache
from itertools import permutations

from verigraph.errors import VeriGraphError
from verigraph.pddl.syntax import SExpr, define_body, typed_names

ROLE_NAMES = {"on": "on", "ontable": "ontable", "clear": "clear", "handempty": "handempty",
              "armempty": "handempty", "emptyhand": "handempty", "holding": "holding",
              "held": "holding"}
ROLE_ARITY = {"on": 2, "ontable": 1, "clear": 1, "handempty": 0, "holding": 1}
ALLOWED_REQUIREMENTS = {":strips", ":typing", ":equality", ":action-costs"}

Atom = tuple[str, tuple[int, ...]]
# role -> (preconditions, add effects, delete effects), over parameter indices 0, 1, 2.
TEMPLATES: dict[str, tuple[frozenset[Atom], frozenset[Atom], frozenset[Atom]]] = {
    "pick-up": (frozenset({("clear", (0,)), ("ontable", (0,)), ("handempty", ())}),
                frozenset({("holding", (0,))}),
                frozenset({("ontable", (0,)), ("clear", (0,)), ("handempty", ())})),
    "put-down": (frozenset({("holding", (0,))}),
                 frozenset({("clear", (0,)), ("handempty", ()), ("ontable", (0,))}),
                 frozenset({("holding", (0,))})),
    "stack": (frozenset({("holding", (0,)), ("clear", (1,))}),
              frozenset({("clear", (0,)), ("handempty", ()), ("on", (0, 1))}),
              frozenset({("holding", (0,)), ("clear", (1,))})),
    "unstack": (frozenset({("on", (0, 1)), ("clear", (0,)), ("handempty", ())}),
                frozenset({("holding", (0,)), ("clear", (1,))}),
                frozenset({("on", (0, 1)), ("clear", (0,)), ("handempty", ())})),
    # 3 operators: block -> block (x, from, to), block -> table (x, from), table -> block (x, to)
    "move-b-to-b": (frozenset({("clear", (0,)), ("clear", (2,)), ("on", (0, 1))}),
                    frozenset({("on", (0, 2)), ("clear", (1,))}),
                    frozenset({("clear", (2,)), ("on", (0, 1))})),
    "move-b-to-t": (frozenset({("clear", (0,)), ("on", (0, 1))}),
                    frozenset({("ontable", (0,)), ("clear", (1,))}),
                    frozenset({("on", (0, 1))})),
    "move-t-to-b": (frozenset({("clear", (0,)), ("clear", (1,)), ("ontable", (0,))}),
                    frozenset({("on", (0, 1))}),
                    frozenset({("clear", (1,)), ("ontable", (0,))})),
}
FOUR_OPS = ("pick-up", "put-down", "stack", "unstack")
THREE_OPS = ("move-b-to-b", "move-b-to-t", "move-t-to-b")
# (role, index of the moved block, index of the target) for the self-move check
SELF_MOVE = {"move-b-to-b": (0, 2), "move-t-to-b": (0, 1)}


class UnsupportedDomainError(VeriGraphError):
    """A PDDL domain outside the blocks-world family: refused, never judged."""

    def __init__(self, reason: str) -> None:
        super().__init__(f"unsupported domain: {reason}", field="domain", value=None,
                         fix="give a blocks-world domain (pick-up/put-down/stack/unstack with a "
                             "hand, or the 3-operator move domain)")


@dataclass(slots=True)
class Operator:
    """One domain action mapped to its template role; `order[i]` = template slot of arg i."""

    name: str
    role: str
    order: tuple[int, ...]
    self_move_forbidden: bool = True


@dataclass(slots=True)
class BlocksDomain:
    """A recognised domain: its family, operators by PDDL name and predicate roles."""

    name: str
    family: str  # "4op" or "3op"
    operators: dict[str, Operator]
    predicates: dict[str, str]  # PDDL name -> role
    block_types: set[str] = field(default_factory=set)

    def by_role(self, role: str) -> Operator:
        return next(op for op in self.operators.values() if op.role == role)

    def call(self, role: str, *slots: str) -> str:
        """The action of template `role` on template arguments `slots`, in the domain's own
        names and parameter order: `call("unstack", "a", "b")` -> `(feast a b)`."""
        op = self.by_role(role)
        return "(" + " ".join((op.name, *(slots[op.order[i]] for i in range(len(slots))))) + ")"

    def atom(self, role: str, *args: str) -> str:
        """A fact in the domain's own predicate names: `atom("on", "a", "b")` -> `(craves a b)`."""
        name = next(p for p, r in self.predicates.items() if r == role)
        return "(" + " ".join((name, *args)) + ")"


def _role(name: str) -> str | None:
    return ROLE_NAMES.get(name.replace("-", "").replace("_", ""))


def _conjuncts(expr: SExpr, where: str) -> list[SExpr]:
    if isinstance(expr, list) and expr and expr[0] == "and":
        return list(expr[1:])
    if isinstance(expr, list) and not expr:
        return []
    return [expr]


RawAction = tuple[str, list[str], set[Atom], set[Atom], set[Atom], set[frozenset[int]]]


def _read_action(body: list[SExpr], arity: dict[str, int]) -> RawAction:
    """An action's parameters and atoms over parameter indices, predicates by PDDL name."""
    name = body[1] if len(body) > 1 and isinstance(body[1], str) else "?"
    keys = {body[i]: body[i + 1] for i in range(2, len(body) - 1, 2) if isinstance(body[i], str)}
    params_expr = keys.get(":parameters", [])
    if not isinstance(params_expr, list):
        raise UnsupportedDomainError(f"action {name} has malformed :parameters")
    params = [p for p, _ in typed_names(params_expr, what="domain")]
    index = {p: i for i, p in enumerate(params)}

    def atom(expr: SExpr) -> Atom:
        if not (isinstance(expr, list) and expr and all(isinstance(a, str) for a in expr)):
            raise UnsupportedDomainError(f"action {name} uses {_show(expr)}; only plain atoms, "
                                         "negated effects and (not (= ?x ?y)) are supported")
        pred = str(expr[0])
        if arity.get(pred) != len(expr) - 1 or any(a not in index for a in expr[1:]):
            raise UnsupportedDomainError(f"action {name} uses {_show(expr)}, which is not a "
                                         "blocks-world predicate over the action's parameters")
        return pred, tuple(index[str(a)] for a in expr[1:])

    pre: set[Atom] = set()
    distinct: set[frozenset[int]] = set()
    for c in _conjuncts(keys.get(":precondition", []), name):
        if isinstance(c, list) and len(c) == 2 and c[0] == "not" and isinstance(c[1], list) \
                and len(c[1]) == 3 and c[1][0] == "=":
            a, b = c[1][1], c[1][2]
            if a not in index or b not in index:
                raise UnsupportedDomainError(f"action {name}: {_show(c)} names no parameter")
            distinct.add(frozenset((index[str(a)], index[str(b)])))
        else:
            pre.add(atom(c))
    add: set[Atom] = set()
    delete: set[Atom] = set()
    for c in _conjuncts(keys.get(":effect", []), name):
        if isinstance(c, list) and c and c[0] == "increase":
            continue  # action costs do not change validity
        if isinstance(c, list) and len(c) == 2 and c[0] == "not":
            delete.add(atom(c[1]))
        else:
            add.add(atom(c))
    return str(name), params, pre, add, delete, distinct


def _role_assignments(arity: dict[str, int]) -> list[dict[str, str]]:
    """Every way to give the predicates blocks-world roles that fits their arities.

    The conventional spelling (on, ontable, clear, ...) is tried first; then, because a
    renamed domain (PlanBench's Mystery Blocksworld: craves, planet, province, harmony,
    pain) is the same domain, every assignment by arity: one binary predicate is `on`,
    a nullary one `handempty`, and the two or three unary ones are permuted (at most 6
    tries, each checked against the operator templates).
    """
    out: list[dict[str, str]] = []
    by_name = {p: _role(p) for p in arity}
    if all(r is not None and ROLE_ARITY[r] == arity[p] for p, r in by_name.items()) \
            and len(set(by_name.values())) == len(by_name):
        out.append({p: str(r) for p, r in by_name.items()})
    binary = [p for p, a in arity.items() if a == 2]
    nullary = [p for p, a in arity.items() if a == 0]
    unary = [p for p, a in arity.items() if a == 1]
    if len(binary) != 1 or len(nullary) > 1 or len(arity) != len(binary + nullary + unary):
        return out
    roles = ("ontable", "clear", "holding") if nullary else ("ontable", "clear")
    if len(unary) != len(roles):
        return out
    for chosen in permutations(roles):
        assignment = {binary[0]: "on", **dict(zip(unary, chosen, strict=True))}
        if nullary:
            assignment[nullary[0]] = "handempty"
        if assignment not in out:
            out.append(assignment)
    return out


def _operators(raw: list[RawAction], roles: dict[str, str]) -> dict[str, Operator] | None:
    """The operators under one role assignment, or None when an action fits no template."""
    operators: dict[str, Operator] = {}
    for op_name, params, pre, add, delete, distinct in raw:
        def named(atoms: set[Atom]) -> set[Atom]:
            return {(roles[p], args) for p, args in atoms}
        matched = _match(params, named(pre), named(add), named(delete))
        if matched is None:
            return None
        role, order = matched
        slots = {order[i]: i for i in range(len(order))}  # template slot -> param index
        forbidden = True
        if role in SELF_MOVE:
            a, b = SELF_MOVE[role]
            forbidden = frozenset((slots[a], slots[b])) in distinct
        operators[op_name] = Operator(op_name, role, order, forbidden)
    return operators


def _family(operators: dict[str, Operator]) -> str | None:
    roles = sorted(op.role for op in operators.values())
    if roles == sorted(FOUR_OPS):
        return "4op"
    if roles == sorted(THREE_OPS):
        return "3op"
    return None


def _match(params: list[str], pre: set[Atom], add: set[Atom], delete: set[Atom]
           ) -> tuple[str, tuple[int, ...]] | None:
    for role, (t_pre, t_add, t_del) in TEMPLATES.items():
        arity = 1 + max(i for _, args in t_pre | t_add | t_del for i in args)
        if arity != len(params):
            continue
        for order in permutations(range(arity)):
            def mapped(atoms: set[Atom], order: tuple[int, ...] = order) -> frozenset[Atom]:
                return frozenset((r, tuple(order[i] for i in args)) for r, args in atoms)
            if (mapped(pre), mapped(add), mapped(delete)) == (t_pre, t_add, t_del):
                return role, order
    return None


def _show(expr: SExpr) -> str:
    if isinstance(expr, str):
        return expr
    return "(" + " ".join(_show(e) for e in expr) + ")"


def recognise_domain(text: str) -> BlocksDomain:
    """The blocks-world domain in `text`, or UnsupportedDomainError saying what differs.

    Recognition is by structure: predicates and actions may have any names.
    """
    name, sections = define_body(text, what="domain", kind="domain")
    arity: dict[str, int] = {}
    block_types: set[str] = set()
    actions: list[list[SExpr]] = []
    for section in sections:
        if not isinstance(section, list) or not section or not isinstance(section[0], str):
            raise UnsupportedDomainError(f"unexpected {_show(section)[:60]} in the domain")
        head = section[0]
        if head == ":requirements":
            extra = [str(r) for r in section[1:] if r not in ALLOWED_REQUIREMENTS]
            if extra:
                raise UnsupportedDomainError(f"requirement {', '.join(extra)} is outside STRIPS "
                                             "blocks world")
        elif head == ":types":
            block_types.update(n for n, _ in typed_names(section[1:], what="domain"))
        elif head == ":predicates":
            for pred in section[1:]:
                if not isinstance(pred, list) or not pred or not isinstance(pred[0], str):
                    raise UnsupportedDomainError(f"malformed predicate {_show(pred)}")
                arity[pred[0]] = len(typed_names(pred[1:], what="domain"))
        elif head == ":functions":
            if section[1:] != [["total-cost"]]:
                raise UnsupportedDomainError("only the (total-cost) function is supported")
        elif head == ":action":
            actions.append(section)
        else:
            raise UnsupportedDomainError(f"section {head} is outside STRIPS blocks world")
    assignments = _role_assignments(arity)
    if not assignments:
        shown = ", ".join(f"{p}/{a}" for p, a in arity.items())
        raise UnsupportedDomainError(
            f"predicate set ({shown}) is not blocks-world shaped: one binary predicate (on), "
            "two or three unary ones (on-table, clear, holding) and at most one nullary one "
            "(hand empty), under any names")
    raw = [_read_action(body, arity) for body in actions]
    for roles in assignments:
        operators = _operators(raw, roles)
        if operators is None:
            continue
        family = _family(operators)
        if family is not None:
            return BlocksDomain(name, family, operators, roles, block_types)
    if _operators(raw, assignments[0]) is None:
        raise UnsupportedDomainError(
            "an action is not pick-up, put-down, stack, unstack or a 3-operator move with the "
            "standard preconditions and effects (under any names): "
            + ", ".join(str(r[0]) for r in raw))
    raise UnsupportedDomainError(f"the actions ({', '.join(str(r[0]) for r in raw) or 'none'}) "
                                 "are not the four hand operators or the three move operators")


@lru_cache(maxsize=64)
def cached_domain(text: str) -> BlocksDomain:
    """Domains repeat across a batch: recognise each text once."""
    return recognise_domain(text)
