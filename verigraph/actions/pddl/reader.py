"""Read a STRIPS domain and problem (PDDL text) into the model, refusing what it cannot judge.

Supported: `:strips`, `:typing`, `:negative-preconditions`, `:equality`, `:action-costs`
(`(increase (total-cost) N)` effects are read and ignored: costs do not change validity).
Anything else (`:conditional-effects`, `:disjunctive-preconditions`, `:fluents`, ...)
is refused with the requirement named, and so is a construct that needs one (`or`,
`forall`, `when`), so a plan is never judged under rules this model does not implement.
Static errors (an undeclared predicate, type, object or parameter; a wrong arity; an
initial atom whose objects have the wrong type) are refused with the name at fault.
The S-expression reader bounds nesting depth and refuses non-ASCII names with the line.
"""

from __future__ import annotations

from verigraph.actions.blocksworld.sexpr import SExpr, define_body, typed_names
from verigraph.actions.pddl.model import (
    ROOT_TYPE,
    SUPPORTED_REQUIREMENTS,
    Domain,
    GroundAtom,
    Literal,
    Problem,
    Schema,
    Term,
)
from verigraph.errors import VeriGraphError

MAX_OBJECTS = 100_000
MAX_INIT_ATOMS = 2_000_000
# constructs outside STRIPS -> the requirement a domain would need for them
NEEDS = {"or": ":disjunctive-preconditions", "imply": ":disjunctive-preconditions",
         "exists": ":existential-preconditions", "forall": ":universal-preconditions",
         "when": ":conditional-effects", "either": ":typing with (either ...) types",
         "assign": ":numeric-fluents", "increase": ":numeric-fluents",
         "decrease": ":numeric-fluents", "scale-up": ":numeric-fluents",
         "scale-down": ":numeric-fluents", "at": ":durative-actions", "over": ":durative-actions",
         "<": ":numeric-fluents", ">": ":numeric-fluents", "<=": ":numeric-fluents",
         ">=": ":numeric-fluents"}
SUPPORTED_TEXT = " ".join(SUPPORTED_REQUIREMENTS)


class PddlInputError(VeriGraphError):
    """A domain or problem that is readable but wrong (undeclared name, arity, type)."""


class UnsupportedRequirementError(VeriGraphError):
    """PDDL outside the supported STRIPS fragment; names the requirement."""

    def __init__(self, requirement: str, where: str, what: str) -> None:
        super().__init__(f"unsupported requirement {requirement} ({what} in the {where}); "
                         f"supported: {SUPPORTED_TEXT}", field=where, value=requirement,
                         fix="give a STRIPS domain with typing, negative preconditions and "
                             "equality, or compile the feature away")


def _show(expr: SExpr) -> str:
    if isinstance(expr, str):
        return expr
    return "(" + " ".join(_show(e) for e in expr) + ")"


def _types(domain: Domain, items: list[SExpr], where: str) -> list[tuple[str, str]]:
    for item in items:
        if isinstance(item, list):
            head = item[0] if item and isinstance(item[0], str) else "?"
            raise UnsupportedRequirementError(NEEDS.get(head, ":typing"), where, _show(item)[:60])
    out = []
    for name, kind in typed_names(items, what=where):
        kind = kind or ROOT_TYPE
        if kind != ROOT_TYPE and kind not in domain.parents:
            raise PddlInputError(f"type '{kind}' (of {name}) is not declared in (:types ...)",
                                 field=where, value=kind, fix=f"declare {kind} in :types")
        out.append((name, kind))
    return out


class _ActionReader:
    """Turns one `(:action ...)` into a Schema, checking names against the domain."""

    def __init__(self, domain: Domain, body: list[SExpr]) -> None:
        self.domain = domain
        self.name = body[1] if len(body) > 1 and isinstance(body[1], str) else "?"
        self.keys: dict[str, SExpr] = {}
        for i in range(2, len(body) - 1, 2):
            key = body[i]
            if not isinstance(key, str) or not key.startswith(":"):
                raise PddlInputError(f"action {self.name}: expected a :keyword, got "
                                     f"{_show(key)[:40]}", field="domain", value=self.name,
                                     fix="write :parameters (...) :precondition (...) "
                                         ":effect (...)")
            self.keys[key] = body[i + 1]
        params = self.keys.get(":parameters", [])
        if not isinstance(params, list):
            raise PddlInputError(f"action {self.name} has malformed :parameters",
                                 field="domain", value=self.name, fix="write :parameters (?x - t)")
        typed = _types(domain, params, "domain")
        self.params = [p for p, _ in typed]
        self.types = [t for _, t in typed]
        self.index = {p: i for i, p in enumerate(self.params)}
        if len(self.index) != len(self.params):
            raise PddlInputError(f"action {self.name} declares a parameter twice",
                                 field="domain", value=self.name, fix="rename the parameter")

    def term(self, arg: SExpr, literal: SExpr) -> Term:
        if not isinstance(arg, str):
            raise PddlInputError(f"action {self.name}: {_show(literal)[:60]} has a nested "
                                 "term; STRIPS terms are parameters and constants",
                                 field="domain", value=self.name, fix="use ?params or constants")
        if arg.startswith("?"):
            if arg not in self.index:
                raise PddlInputError(f"action {self.name} uses {arg} in {_show(literal)[:60]} "
                                     "but does not declare it", field="domain", value=arg,
                                     fix=f"add {arg} to the action's :parameters")
            return self.index[arg]
        if arg not in self.domain.constants:
            raise PddlInputError(f"action {self.name} names '{arg}', which is neither a "
                                 "parameter nor a declared constant", field="domain",
                                 value=arg,
                                 fix=f"declare {arg} in (:constants ...) or write ?{arg}")
        return arg

    def atom(self, expr: SExpr) -> Literal:
        if not (isinstance(expr, list) and expr and isinstance(expr[0], str)):
            raise PddlInputError(f"action {self.name}: {_show(expr)[:60]} is not an atom",
                                 field="domain", value=self.name, fix="write (predicate ?x ...)")
        head = expr[0]
        if head in NEEDS and head not in self.domain.predicates:
            raise UnsupportedRequirementError(NEEDS[head], "domain",
                                              f"({head} ...) in action {self.name}")
        terms = tuple(self.term(a, expr) for a in expr[1:])
        if head == "=":
            if len(terms) != 2:
                raise PddlInputError(f"action {self.name}: (= ...) takes two terms",
                                     field="domain", value=self.name, fix="write (= ?x ?y)")
            return head, terms
        signature = self.domain.predicates.get(head)
        if signature is None:
            raise PddlInputError(f"action {self.name} uses predicate '{head}', which "
                                 "(:predicates ...) does not declare", field="domain",
                                 value=head, fix=f"declare ({head} ...) in :predicates")
        if len(signature) != len(terms):
            raise PddlInputError(f"action {self.name}: {_show(expr)[:60]} has {len(terms)} "
                                 f"argument(s); {head} takes {len(signature)}", field="domain",
                                 value=head, fix=f"give {head} {len(signature)} argument(s)")
        return head, terms

    def literals(self, expr: SExpr, where: str) -> tuple[list[Literal], list[Literal]]:
        """(positive, negative) literals of a conjunction."""
        items = expr[1:] if isinstance(expr, list) and expr and expr[0] == "and" else \
            ([] if expr == [] else [expr])
        pos: list[Literal] = []
        neg: list[Literal] = []
        for item in items:
            if isinstance(item, list) and item and item[0] == "and":
                p, n = self.literals(item, where)
                pos += p
                neg += n
            elif isinstance(item, list) and len(item) == 2 and item[0] == "not":
                neg.append(self.atom(item[1]))
            elif where == "effect" and isinstance(item, list) and item \
                    and item[0] == "increase" and len(item) == 3 \
                    and item[1] == ["total-cost"]:
                continue  # action costs: read, not judged
            else:
                pos.append(self.atom(item))
        return pos, neg

    def schema(self) -> Schema:
        pre_pos, pre_neg = self.literals(self.keys.get(":precondition", []), "precondition")
        add, delete = self.literals(self.keys.get(":effect", []), "effect")
        if any(p == "=" for p, _ in add + delete):
            raise PddlInputError(f"action {self.name} has an equality effect", field="domain",
                                 value=self.name, fix="effects are atoms and (not atom)")
        return Schema(self.name, self.params, self.types, pre_pos, pre_neg, add, delete)


def read_domain(text: str) -> Domain:
    """The STRIPS domain in `text`, or an error naming the requirement or name at fault."""
    name, sections = define_body(text, what="domain", kind="domain")
    domain = Domain(name, [], {}, {}, {}, {})
    actions: list[list[SExpr]] = []
    for section in sections:
        if not isinstance(section, list) or not section or not isinstance(section[0], str):
            raise PddlInputError(f"unexpected {_show(section)[:60]} in the domain",
                                 field="domain", value=None, fix="sections start with :keyword")
        head, rest = section[0], section[1:]
        if head == ":requirements":
            for req in rest:
                if req not in SUPPORTED_REQUIREMENTS:
                    raise UnsupportedRequirementError(_show(req), "domain", "declared")
                domain.requirements.append(str(req))
        elif head == ":types":
            for item in rest:
                if isinstance(item, list):
                    raise UnsupportedRequirementError(NEEDS["either"], "domain", _show(item))
            for child, parent in typed_names(rest, what="domain"):
                domain.parents[child] = parent or ROOT_TYPE
            domain.parents.pop(ROOT_TYPE, None)
        elif head == ":constants":
            domain.constants.update(_types(domain, rest, "domain"))
        elif head == ":predicates":
            for pred in rest:
                if not isinstance(pred, list) or not pred or not isinstance(pred[0], str):
                    raise PddlInputError(f"malformed predicate {_show(pred)[:60]}",
                                         field="domain", value=None,
                                         fix="write (name ?x - type ...)")
                domain.predicates[pred[0]] = [t for _, t in _types(domain, pred[1:], "domain")]
        elif head == ":functions":
            if rest != [["total-cost"]] and rest != [["total-cost"], "-", "number"]:
                raise UnsupportedRequirementError(":numeric-fluents", "domain", "(:functions)")
        elif head == ":action":
            actions.append(section)
        else:
            need = {":derived": ":derived-predicates", ":durative-action": ":durative-actions",
                    ":process": ":time", ":event": ":time",
                    ":constraints": ":constraints"}.get(head, head)
            raise UnsupportedRequirementError(need, "domain", f"section {head}")
    for parent in set(domain.parents.values()) - set(domain.parents) - {ROOT_TYPE}:
        domain.parents[parent] = ROOT_TYPE  # a parent used but not listed is an object
    for body in actions:
        schema = _ActionReader(domain, body).schema()
        if schema.name in domain.schemas:
            raise PddlInputError(f"action {schema.name} is defined twice", field="domain",
                                 value=schema.name, fix="rename one of them")
        domain.schemas[schema.name] = schema
    return domain


def _ground(domain: Domain, objects: dict[str, str], expr: SExpr, where: str) -> GroundAtom:
    if not (isinstance(expr, list) and expr and all(isinstance(a, str) for a in expr)):
        head = expr[0] if isinstance(expr, list) and expr and isinstance(expr[0], str) else ""
        if head in NEEDS:
            raise UnsupportedRequirementError(NEEDS[head], "problem",
                                              f"({head} ...) in the {where}")
        raise PddlInputError(f"the {where} holds {_show(expr)[:60]}, which is not a ground atom",
                             field="problem", value=None, fix="write (predicate obj ...)")
    head, args = str(expr[0]), [str(a) for a in expr[1:]]
    if head == "=":
        if len(args) != 2:
            raise PddlInputError(f"the {where}: (= ...) takes two objects", field="problem",
                                 value=None, fix="write (= a b)")
    else:
        signature = domain.predicates.get(head)
        if signature is None:
            raise PddlInputError(f"the {where} uses predicate '{head}', which the domain does "
                                 "not declare", field="problem", value=head,
                                 fix=f"declare ({head} ...) in the domain's :predicates")
        if len(signature) != len(args):
            raise PddlInputError(f"the {where}: {_show(expr)[:60]} has {len(args)} argument(s); "
                                 f"{head} takes {len(signature)}", field="problem", value=head,
                                 fix=f"give {head} {len(signature)} argument(s)")
    for i, a in enumerate(args):
        kind = objects.get(a)
        if kind is None:
            raise PddlInputError(f"{_show(expr)[:60]} in the {where} names '{a}', which "
                                 "(:objects ...) does not declare", field="problem", value=a,
                                 fix=f"declare {a} in :objects")
        if head != "=" and not domain.is_a(kind, domain.predicates[head][i]):
            raise PddlInputError(f"{_show(expr)[:60]} in the {where}: {a} is a {kind}, but "
                                 f"argument {i + 1} of {head} is a {domain.predicates[head][i]}",
                                 field="problem", value=a,
                                 fix=f"give {head} an object of type {domain.predicates[head][i]}")
    return (head, *args)


def read_problem(text: str, domain: Domain) -> Problem:
    """The problem in `text` against `domain`; objects include the domain's constants."""
    name, sections = define_body(text, what="problem", kind="problem")
    objects = dict(domain.constants)
    init: set[GroundAtom] = set()
    goal_pos: list[GroundAtom] = []
    goal_neg: list[GroundAtom] = []
    goal_seen = False
    raw_init: list[SExpr] = []
    raw_goal: SExpr = []
    for section in sections:
        if not isinstance(section, list) or not section:
            continue
        head = section[0]
        if head == ":objects":
            if len(section) - 1 > MAX_OBJECTS:
                raise PddlInputError(f"the problem declares {len(section) - 1:,} objects",
                                     field="problem", value=len(section) - 1,
                                     fix=f"keep it under {MAX_OBJECTS:,} objects")
            objects.update(_types(domain, section[1:], "problem"))
        elif head == ":init":
            if len(section) - 1 > MAX_INIT_ATOMS:
                raise PddlInputError(f"the initial state has {len(section) - 1:,} atoms",
                                     field="problem", value=len(section) - 1,
                                     fix=f"keep it under {MAX_INIT_ATOMS:,} atoms")
            raw_init = section[1:]
        elif head == ":goal":
            goal_seen = True
            raw_goal = section[1] if len(section) > 1 else []
        elif head in (":domain", ":requirements", ":metric"):
            continue
        else:
            raise UnsupportedRequirementError(str(head), "problem", f"section {head}")
    if not goal_seen:
        raise PddlInputError("the problem has no (:goal ...)", field="problem", value=name,
                             fix="add (:goal (and ...))")
    for item in raw_init:
        if isinstance(item, list) and item and item[0] == "=":
            continue  # (= (total-cost) 0)
        init.add(_ground(domain, objects, item, "initial state"))
    goal_items = raw_goal[1:] if isinstance(raw_goal, list) and raw_goal \
        and raw_goal[0] == "and" else ([] if raw_goal == [] else [raw_goal])
    for item in goal_items:
        if isinstance(item, list) and len(item) == 2 and item[0] == "not":
            goal_neg.append(_ground(domain, objects, item[1], "goal"))
        else:
            goal_pos.append(_ground(domain, objects, item, "goal"))
    return Problem(name, objects, init, goal_pos, goal_neg)
