"""A BEHAVIOR-1K activity (a BDDL problem) as a VeriGraph scene and formula goal.

One function, `import_problem`, beneath `verigraph bddl import` and `load_scene(bddl=...)`:
the problem's objects become nodes labelled by the `behavior` dictionary (`fridge` for
`electric_refrigerator.n.01`, ids `fridge_1`), its rooms nodes of their room kind, its
initial literals edges and states, and its goal the same BDDL formula over the new ids
and labels (`(forall (?plate - plate) (inside ?plate cabinet_1))`). What BEHAVIOR leaves
open is filled in as docs/worlds.md ("BEHAVIOR-1K activities") says:

- the agent (`agent.n.01`) and the `_*` objects a scene may add are left out;
- an object placed by `inroom` is furniture: fixed, standing in its room; every other
  object is movable. Furniture the goal places (`(nextto ?chair ?desk)`) is movable,
  standing on its room's floor;
- a kind is a surface where the activity puts something `ontop` it, a container where it
  puts something `inside` it (initially or in the goal), whatever the dictionary says;
- an object the initial state places twice keeps its first placement (one activity of
  BEHAVIOR-1K 3.6.0 puts a steak both on a shelf and on another steak);
- capacities: BEHAVIOR has none, so a movable surface or container carries as many
  objects as the activity has (a bound that never binds), furniture any number.

An activity whose initial state or goal needs a predicate outside the supported set is
refused as a whole (`UnsupportedActivityError`, naming the predicate and the activity),
never half-loaded. The text is read with a small S-expression reader (BDDL is PDDL's
syntax); the package `bddl` is needed only to find an activity by name.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, TypeAlias

from verigraph.errors import VeriGraphError

if TYPE_CHECKING:
    from verigraph.graph.model import SceneGraph

# Predicates an imported activity may use, by class (docs/worlds.md).
SPATIAL = ("ontop", "inside", "inroom")
HOUSEHOLD = ("nextto", "under", "open", "toggled_on")
THERMAL = ("cooked", "hot", "frozen")
SUPPORTED = (*SPATIAL, *HOUSEHOLD, *THERMAL)
# BDDL placement predicates -> VeriGraph relations; states are node state keys.
RELATIONS = {"ontop": "on", "inside": "in", "nextto": "nextto", "under": "under",
             "inroom": "inroom"}
STATES = ("open", "toggled_on", *THERMAL)
CONNECTIVES = ("and", "or", "not", "imply", "forall", "exists", "forn", "forpairs",
               "fornpairs")
AGENT = "agent.n.01"
FLOOR = "floor.n.01"
MAX_TEXT = 262_144  # bytes of BDDL: the largest activity is about 12 KB
MAX_DEPTH = 64

Sexp: TypeAlias = "str | list[Sexp]"
_TOKEN = re.compile(r"[()]|[^\s()]+")
_OBJECT = re.compile(r"^(?P<synset>.+)_(?P<n>\d+|\*)$")


class UnsupportedActivityError(VeriGraphError):
    """A BEHAVIOR activity VeriGraph cannot load: a predicate outside the supported set,
    or a problem text that is not a BDDL problem."""

    def __init__(self, message: str, *, activity: str, predicate: str | None = None,
                 fix: str) -> None:
        super().__init__(message, field="bddl", value=predicate or activity, fix=fix)
        self.activity = activity
        self.predicate = predicate


@dataclass
class ImportedActivity:
    """What an activity becomes: the scene graph JSON, the goal formula, the name maps."""

    activity: str
    scene: dict[str, Any]
    formula: str
    ids: dict[str, str] = field(default_factory=dict)  # BEHAVIOR object -> node id
    classes: tuple[str, ...] = ()  # predicate classes used: spatial, household, thermal

    @property
    def goal(self) -> dict[str, str]:
        return {"formula": self.formula}

    def scene_graph(self) -> SceneGraph:
        """The scene as a checked SceneGraph (MalformedGraphError if it is not well formed,
        which no activity of BEHAVIOR-1K 3.6.0 within the supported predicates is)."""
        from verigraph.errors import MalformedGraphError
        from verigraph.graph.dictionary import load_dictionary
        from verigraph.graph.model import SceneGraph
        from verigraph.graph.wellformed import check_well_formed

        graph = SceneGraph.model_validate(self.scene)
        problems = check_well_formed(graph, load_dictionary("behavior"))
        if problems:
            raise MalformedGraphError(problems)
        return graph

    @property
    def predicate_class(self) -> str:
        """The widest class the activity needs: spatial, household or thermal."""
        return self.classes[-1] if self.classes else "spatial"


def read_sexp(text: str, *, activity: str = "problem") -> Sexp:
    """The S-expression of a BDDL text (comments dropped, lower case, as bddl reads it)."""
    if len(text) > MAX_TEXT:
        raise _malformed(activity, f"the text is {len(text)} characters; at most {MAX_TEXT}")
    body = re.sub(r";.*$", "", text, flags=re.MULTILINE).lower()
    stack: list[list[Sexp]] = []
    tokens: list[Sexp] = []
    for token in _TOKEN.findall(body):
        if token == "(":
            stack.append(tokens)
            if len(stack) > MAX_DEPTH:
                raise _malformed(activity, f"lists nest deeper than {MAX_DEPTH}")
            tokens = []
        elif token == ")":
            if not stack:
                raise _malformed(activity, "a ')' closes nothing")
            inner, tokens = tokens, stack.pop()
            tokens.append(inner)
        else:
            tokens.append(token)
    if stack:
        raise _malformed(activity, "a '(' is never closed")
    if len(tokens) != 1:
        raise _malformed(activity, "the text is not one (define ...) form")
    return tokens[0]


def _malformed(activity: str, why: str) -> UnsupportedActivityError:
    return UnsupportedActivityError(
        f"activity {activity}: not a BDDL problem: {why}", activity=activity,
        fix="give a BDDL problem: (define (problem NAME) (:domain omnigibson) (:objects ...) "
            "(:init ...) (:goal ...))")


def _sections(tree: Sexp, activity: str) -> tuple[str, list[Sexp], list[Sexp], Sexp]:
    if not isinstance(tree, list) or not tree or tree[0] != "define":
        raise _malformed(activity, "it does not start with (define")
    name = activity
    objects: list[Sexp] = []
    init: list[Sexp] = []
    goal: Sexp | None = None
    for group in tree[1:]:
        if not isinstance(group, list) or not group or not isinstance(group[0], str):
            continue  # a stray token (bddl's own reader skips what it does not know too)
        head = group[0]
        if head == "problem" and len(group) == 2 and isinstance(group[1], str):
            name = group[1]
        elif head == ":objects":
            objects = group[1:]
        elif head == ":init":
            init = group[1:]
        elif head == ":goal" and len(group) == 2:
            goal = group[1]
        elif head == ":goal" and len(group) > 2:  # several formulas: read as their `and`
            goal = ["and", *group[1:]]
    if goal is None:
        raise _malformed(activity, "it has no (:goal ...)")
    return re.sub(r"-\d+$", "", name), objects, init, goal


def _declared(objects: list[Sexp], activity: str) -> dict[str, str]:
    """BEHAVIOR object -> its synset, from `a b - type` groups."""
    out: dict[str, str] = {}
    pending: list[str] = []
    items = iter(objects)
    for item in items:
        if not isinstance(item, str):
            raise _malformed(activity, ":objects holds a list")
        if item == "-":
            kind = next(items, None)
            if not isinstance(kind, str):
                raise _malformed(activity, "a '-' in :objects is not followed by a type")
            out.update(dict.fromkeys(pending, kind))
            pending = []
        else:
            pending.append(item)
    for name in pending:
        match = _OBJECT.match(name)
        out[name] = match["synset"] if match else name
    return out


def _predicates(tree: Sexp, out: dict[str, None]) -> None:
    """Every predicate a goal formula names (quantifier heads and counts skipped)."""
    if not isinstance(tree, list) or not tree or not isinstance(tree[0], str):
        return
    head, rest = tree[0], tree[1:]
    if head in CONNECTIVES:
        for part in rest:
            if isinstance(part, list) and part and part[0] != "-" and not (
                    isinstance(part[0], str) and (part[0].startswith("?") or part[0].isdigit())):
                _predicates(part, out)
        return
    out.setdefault(head, None)


def _refuse(activity: str, predicate: str, where: str) -> UnsupportedActivityError:
    return UnsupportedActivityError(
        f"activity {activity} needs the predicate '{predicate}' ({where}), which VeriGraph "
        f"does not support; supported: {', '.join(SUPPORTED)}", activity=activity,
        predicate=predicate,
        fix="choose an activity within the supported predicates (verigraph bench behavior "
            "lists them) or drop what uses it")


def check_supported(init: list[Sexp], goal: Sexp, activity: str) -> tuple[str, ...]:
    """The classes of predicates used (spatial, household, thermal), or the refusal
    naming the first predicate outside them (initial state first)."""
    used: dict[str, None] = {}
    for literal in init:
        atom = literal[1] if isinstance(literal, list) and literal[:1] == ["not"] else literal
        if not isinstance(atom, list) or not atom or not isinstance(atom[0], str):
            raise _malformed(activity, "an :init literal is not a list")
        if atom[0] not in SUPPORTED:
            raise _refuse(activity, atom[0], "initial state")
        used.setdefault(atom[0], None)
    in_goal: dict[str, None] = {}
    _predicates(goal, in_goal)
    for predicate in in_goal:
        if predicate not in SUPPORTED:
            raise _refuse(activity, predicate, "goal")
    used.update(in_goal)
    return tuple(name for name, members in (("spatial", SPATIAL), ("household", HOUSEHOLD),
                                            ("thermal", THERMAL))
                 if name == "spatial" or any(p in used for p in members))


def _goal_roles(tree: Sexp, types: dict[str, str], objects: dict[str, str],
                out: dict[str, set[str]]) -> None:
    """Objects (or `type:<synset>`) the goal puts something `ontop` (surface) or `inside`
    (container), and those it places itself (placed)."""
    if not isinstance(tree, list) or not tree:
        return
    head = tree[0]
    if head in ("forall", "exists", "forn", "forpairs", "fornpairs"):
        scope = dict(types)
        for part in tree[1:-1]:
            if isinstance(part, list) and "-" in part:
                for i, token in enumerate(part):
                    if token == "-" and i + 1 < len(part):
                        for var in part[:i]:
                            if isinstance(var, str):
                                scope[var.lstrip("?")] = str(part[i + 1])
        _goal_roles(tree[-1], scope, objects, out)
        return
    if head in CONNECTIVES:
        for part in tree[1:]:
            _goal_roles(part, types, objects, out)
        return
    if head in ("ontop", "inside", "nextto", "under") and len(tree) == 3 \
            and all(isinstance(t, str) for t in tree[1:]):
        for term, role in ((str(tree[1]), "placed"),
                           (str(tree[2]), {"ontop": "surface", "inside": "container"}.get(
                               str(head), ""))):
            bare = term.lstrip("?")
            if not role:
                continue
            if bare in objects:
                out.setdefault(bare, set()).add(role)
            elif bare in types:
                out.setdefault("type:" + types[bare], set()).add(role)


def import_problem(text: str, *, activity: str | None = None) -> ImportedActivity:
    """The scene (graph JSON, dictionary `behavior`) and goal formula of a BDDL problem.

    Raises UnsupportedActivityError naming the predicate and the activity when the
    activity needs one outside SUPPORTED, and for a text that is not a BDDL problem.
    """
    from verigraph.graph.behavior import label_of_synset

    given = activity or "problem"
    tree = read_sexp(text, activity=given)
    name, objects_sexp, init, goal = _sections(tree, given)
    activity = activity or name
    classes = check_supported(init, goal, activity)
    declared = _declared(objects_sexp, activity)
    labels = label_of_synset()
    ids: dict[str, str] = {}
    node_labels: dict[str, str] = {}
    for obj, synset in declared.items():
        match = _OBJECT.match(obj)
        if synset == AGENT or (match and match["n"] == "*"):
            continue
        label = labels.get(synset) or re.sub(r"\.n\.\d+$", "", synset).replace("__", "_")
        number = match["n"] if match else "1"
        ids[obj] = f"{label}_{number}"
        node_labels[obj] = label
    left_out = {o for o in declared if o not in ids}
    edges: list[tuple[str, str, str]] = []
    states: dict[str, dict[str, bool]] = {}
    rooms: dict[str, None] = {}
    placed: dict[str, list[tuple[str, str]]] = {}
    inroom: dict[str, str] = {}
    for literal in init:
        negated = isinstance(literal, list) and literal[:1] == ["not"]
        atom = literal[1] if negated else literal
        assert isinstance(atom, list)
        predicate, args = str(atom[0]), [str(a) for a in atom[1:]]
        if any(a in left_out for a in args):
            continue
        objects = args[:-1] if predicate == "inroom" else args
        unknown = [a for a in objects if a not in ids]
        if unknown:
            raise _malformed(activity, f"({predicate} {' '.join(args)}) names "
                                       f"{unknown[0]}, which :objects does not declare")
        if predicate in STATES:
            if len(args) != 1:
                raise _malformed(activity, f"({predicate} ...) takes one object")
            states.setdefault(ids[args[0]], {})[predicate] = not negated
            continue
        if negated or len(args) != 2:
            raise _malformed(activity, f"(not ({predicate} ...)) in :init: only states are "
                                       "negated there")
        if predicate == "inroom":
            rooms.setdefault(args[1], None)
            inroom[args[0]] = args[1]
        elif args[0] not in placed:  # an object placed twice keeps its first placement
            placed[args[0]] = [(predicate, args[1])]
    roles: dict[str, set[str]] = {}
    for places in placed.values():
        for predicate, target in places:
            if predicate in ("ontop", "inside"):
                roles.setdefault(target, set()).add(
                    "surface" if predicate == "ontop" else "container")
    _goal_roles(goal, {}, {o: o for o in ids}, roles)
    # Furniture the goal places (a chair next to a desk) is movable, on its room's floor.
    floors = {room: obj for obj, room in inroom.items() if declared[obj] == FLOOR}
    for obj in [o for o in inroom if o not in floors.values()]:
        moved = "placed" in roles.get(obj, set()) | roles.get("type:" + declared[obj], set())
        if moved and inroom[obj] in floors:
            placed[obj] = [("ontop", floors[inroom.pop(obj)])]
            roles.setdefault(placed[obj][0][1], set()).add("surface")
    movable_count = sum(1 for o in ids if o not in inroom)
    room_ids = {room: _room_id(room, set(ids.values())) for room in rooms}
    nodes: list[dict[str, Any]] = []
    for obj, node_id in ids.items():
        node: dict[str, Any] = {"id": node_id, "label": node_labels[obj]}
        attrs = _attrs(obj, declared[obj], node_labels[obj], roles, obj in inroom,
                       movable_count)
        if attrs:
            node["attrs"] = attrs
        if node_id in states:
            node["state"] = states[node_id]
        nodes.append(node)
    for room, room_id in room_ids.items():
        room_label = _room_label(room)
        nodes.append({"id": room_id, "label": room_label} if room_label else
                     {"id": room_id, "label": room, "attrs": {"room": True}})
    for obj, room in inroom.items():
        edges.append((ids[obj], "inroom", room_ids[room]))
    for obj, places in placed.items():
        if obj in inroom:  # furniture stands in its room; its `ontop` the floor is not kept
            continue
        for predicate, target in places:
            edges.append((ids[obj], RELATIONS[predicate], ids[target]))
    scene = {"nodes": nodes,
             "edges": [{"source": s, "relation": r, "target": t} for s, r, t in edges],
             "dictionary": "behavior"}
    formula = render_formula(goal, ids, declared, activity)
    return ImportedActivity(activity=activity, scene=scene, formula=formula, ids=ids,
                            classes=classes)


def _room_label(room: str) -> str | None:
    """The room kind of a BEHAVIOR room type (`kitchen`, `closet_room`); None for a type
    the dictionary lacks (the node then declares itself a room in its attrs)."""
    from verigraph.graph.behavior import behavior_dictionary

    objects = behavior_dictionary().objects
    for label in (room, f"{room}_room"):
        props = objects.get(label)
        if props is not None and props.room:
            return label
    return None


def _room_id(room: str, taken: set[str]) -> str:
    return room if room not in taken else f"{room}_room"


def _attrs(obj: str, synset: str, label: str, roles: dict[str, set[str]], furniture: bool,
           movable_count: int) -> dict[str, Any]:
    """A node's overrides of its kind: the roles the activity gives it, fixed or movable."""
    from verigraph.graph.behavior import behavior_dictionary

    props = behavior_dictionary().objects.get(label)
    attrs: dict[str, Any] = {}
    # a synset the knowledge base lacks (an open label), or a kind fixed the other way
    if props is None or props.movable == furniture:
        attrs["movable"] = not furniture
    movable = not furniture
    wanted = (roles.get(obj, set()) | roles.get("type:" + synset, set())) - {"placed"}
    for role in sorted(wanted):
        if props is None or not getattr(props, role):
            attrs[role] = True
    has_role = bool(wanted) or (props is not None and (props.surface or props.container))
    if has_role:
        capacity = movable_count if movable else None
        if props is None or props.capacity != capacity:
            attrs["capacity"] = capacity
    return attrs


def render_formula(goal: Sexp, ids: dict[str, str], declared: dict[str, str],
                   activity: str) -> str:
    """The goal in BDDL over VeriGraph's names: objects by node id (`plate_1`), types by
    label (`plate`), variables by label (`?plate`); connectives and predicates kept."""
    from verigraph.graph.behavior import label_of_synset

    labels = label_of_synset()

    def kind(synset: str) -> str:
        return labels.get(synset) or re.sub(r"\.n\.\d+$", "", synset).replace("__", "_")

    def term(token: str) -> str:
        bare = token.lstrip("?")
        if bare in ids:
            return ids[bare]
        if bare in declared:
            raise UnsupportedActivityError(
                f"the goal names {bare}, an object the scene may add (BEHAVIOR's `_*`), "
                "which VeriGraph leaves out", activity=activity, predicate=None,
                fix="quantify over its kind instead")
        if token.startswith("?"):
            match = _OBJECT.match(bare)
            if match and match["n"] != "*":
                return f"?{kind(match['synset'])}_{match['n']}"
            return f"?{kind(bare)}"
        if "." in token:
            return kind(token)
        return token

    def render(tree: Sexp) -> str:
        if isinstance(tree, str):
            return term(tree)
        return "(" + " ".join(render(part) for part in tree) + ")"

    return render(goal)
