"""The object dictionary D: canonical names, their properties and synonyms.

Properties drive every constraint (a cup goes `in` a bowl only if bowl is a
container), so the validator, the simulator and perception all read them from here.
"""

from __future__ import annotations

import difflib
import json
import re
from collections import OrderedDict
from collections.abc import Callable
from functools import cache
from importlib import resources
from pathlib import Path
from typing import TYPE_CHECKING, Annotated, Any

import yaml
from pydantic import (
    BaseModel,
    ConfigDict,
    Field,
    PrivateAttr,
    StringConstraints,
    ValidationError,
    field_validator,
    model_validator,
)
from pydantic_core import PydanticCustomError

from verigraph.errors import DictionaryError, InputFileError
from verigraph.graph.behavior import BEHAVIOR, behavior_dictionary
from verigraph.reporting import STATE_WORDS

if TYPE_CHECKING:  # the graph model imports this module; a graph is only read here
    from verigraph.graph.model import SceneGraph

BUILTIN_DICTIONARIES = ("blocks", "kitchen", "tableware", "tangram", "household")
# The paper's worlds: their union is what applies when a scene names no dictionary (or
# "all"). `household` is not among them: its states and relations apply only to a scene
# that names it, so a scene without a dictionary reads and solves as it always did.
UNION_DICTIONARIES = ("blocks", "kitchen", "tableware", "tangram")
# The relations by which one object rests on or in another (tangram's `touches` is not one):
# they carry the object, so they count against the target's capacity.
SUPPORT_RELATIONS = ("on", "in")
# Every placement of a movable object: resting on or in its target, or under or next to
# a reference object (these two carry nothing and count against no capacity; the object
# stands where its reference stands). A movable object has exactly one of them.
PLACEMENT_RELATIONS = ("on", "in", "under", "nextto")
# Furniture (a fixed object) in a room; not a placement of a movable object, whose room
# is the room of the furniture its placements lead down to.
ROOM_RELATION = "inroom"
# The relations of a household world (the household dictionary's R).
HOUSEHOLD_RELATIONS = (*PLACEMENT_RELATIONS, ROOM_RELATION)
# Object states and the role a kind needs to have one (BEHAVIOR's names): an openable
# object is open or closed, a toggleable one on or off. A node without a state key has
# its default (`state_value`): closed, off.
STATE_ROLES = {"open": "openable", "toggled_on": "toggleable"}
# Physical processes (BEHAVIOR's thermal states): a cookable object is raw or cooked, a
# heatable one hot or not, a freezable one frozen or not; default false. They change by
# the process actions (cook, heat, freeze, cool, thaw) on or in a heat or cold source.
THERMAL_ROLES = {"cooked": "cookable", "hot": "heatable", "frozen": "freezable"}
STATE_ROLES.update(THERMAL_ROLES)
# Roles of the sources those actions need (a heat source must be on when toggleable).
SOURCE_ROLES = ("heat_source", "cold_source")

# Bounds of a dictionary given inline by a client: it is stored with the episode and
# shown in texts and prompts, so it stays the size of a tabletop's vocabulary.
MAX_USER_LABELS = 200
MAX_LABEL_LENGTH = 64
MAX_SYNONYMS = 16
MAX_INLINE_BYTES = 32_768
ROLE_KEYS = ("movable", "surface", "container")
# Roles a kind may have beyond where things rest: a state it keeps (STATE_ROLES) and
# whether it is a room (furniture stands `inroom` it).
STATE_ROLE_KEYS = ("openable", "toggleable", *THERMAL_ROLES.values(), *SOURCE_ROLES)
# The properties that make a kind (what constraints read), as opposed to how it looks.
KIND_KEYS = ("movable", "surface", "container", "capacity", "openable", "toggleable", "room")
# Bounds of every size the simulator, the renderer and perception build from, whichever
# way it comes in (a built-in or inline dictionary, a dictionary file, a node's attrs):
# widths and heights in the simulator's units (a built-in cup is 6 wide, a desk 60),
# capacities in objects, tangram sides and rotational symmetry (a goal check tries every
# rotation of every piece, so symmetry is bounded by the built-in pieces' largest).
MIN_SIZE = 1.0
MAX_SIZE = 500.0
MAX_CAPACITY = 1000
MAX_SIDES = 16
MAX_SYMMETRY = 4
PROPERTY_BOUNDS = {
    "width": f"a finite number from {MIN_SIZE:g} to {MAX_SIZE:g}",
    "height": f"a finite number from {MIN_SIZE:g} to {MAX_SIZE:g}",
    "capacity": f"an integer from 0 to {MAX_CAPACITY}, or null for unlimited",
    "sides": f"an integer from 3 to {MAX_SIDES}",
    "symmetry": f"an integer from 1 to {MAX_SYMMETRY} that divides sides",
    "movable": "true or false", "surface": "true or false", "container": "true or false",
    "openable": "true or false", "toggleable": "true or false", "room": "true or false",
    "cookable": "true or false", "heatable": "true or false", "freezable": "true or false",
    "heat_source": "true or false", "cold_source": "true or false",
    "color": "a colour name of at most 32 characters",
    "shape": "a shape name of at most 32 characters",
}

_SEPARATORS = re.compile(r"[\s\-]+")
_NUMBER_SUFFIX = re.compile(r"_\d+$")


class ObjectProperties(BaseModel):
    """What the validator needs to know about one kind of object."""

    model_config = ConfigDict(extra="forbid", frozen=True)

    synonyms: tuple[str, ...] = ()
    movable: bool = True
    surface: bool = False
    container: bool = False
    capacity: int | None = Field(
        default=None, ge=0, le=MAX_CAPACITY,
        description="how many objects it can carry on or in it at once; null = unlimited")
    openable: bool = Field(default=False, description="open or closed (state `open`)")
    toggleable: bool = Field(default=False, description="on or off (state `toggled_on`)")
    room: bool = Field(default=False, description="a room: furniture stands `inroom` it")
    cookable: bool = Field(default=False, description="raw or cooked (state `cooked`)")
    heatable: bool = Field(default=False, description="hot or not (state `hot`)")
    freezable: bool = Field(default=False, description="frozen or not (state `frozen`)")
    heat_source: bool = Field(default=False, description="cooks and heats what is on or in it")
    cold_source: bool = Field(default=False, description="freezes what is on or in it")
    # Descriptive properties used by the simulator, renderer and perception; bounded
    # here so that no way in (a dictionary or a node's attrs) reaches them unbounded.
    width: float | None = Field(default=None, ge=MIN_SIZE, le=MAX_SIZE, allow_inf_nan=False)
    height: float | None = Field(default=None, ge=MIN_SIZE, le=MAX_SIZE, allow_inf_nan=False)
    color: str | None = Field(default=None, max_length=32)
    shape: str | None = Field(default=None, max_length=32)
    sides: int | None = Field(default=None, ge=3, le=MAX_SIDES,
                              description="tangram: number of sides")
    symmetry: int = Field(default=1, ge=1, le=MAX_SYMMETRY,
                          description="tangram: rotational symmetry order")

    @model_validator(mode="after")
    def _symmetry_divides_sides(self) -> ObjectProperties:
        if self.sides is not None and self.sides % self.symmetry:
            raise ValueError(f"symmetry {self.symmetry} does not divide sides {self.sides}")
        return self

    def overridden(self, attrs: dict[str, object]) -> ObjectProperties:
        """Properties with a node's `attrs` applied on top (only known property names).

        The overrides get the same bounds as a dictionary's properties (PROPERTY_BOUNDS);
        a value out of them is a DictionaryError naming `attrs.<property>` and the bound.
        """
        known = {k: v for k, v in attrs.items() if k in type(self).model_fields and k != "synonyms"}
        if not known:
            return self
        try:
            return type(self).model_validate({**self.model_dump(), **known})
        except ValidationError as exc:
            err = exc.errors()[0]
            field = ".".join(str(p) for p in err["loc"]) or "symmetry"
            bound = PROPERTY_BOUNDS.get(field)
            shown = str(known.get(field))[:32]
            if bound is None:
                raise DictionaryError(f"bad property override: {err['msg']}",
                                      field=f"attrs.{field}", value=shown,
                                      fix="use the property's type, e.g. capacity: 2, "
                                          "movable: false") from None
            raise DictionaryError(f"attrs.{field} = {shown} is not accepted: {field} must be "
                                  f"{bound}", field=f"attrs.{field}", value=shown,
                                  fix=f"give {field} as {bound}") from None


def canonical_token(name: str) -> str:
    """`Cutting Board` -> `cutting_board`: the form names are compared in."""
    return _SEPARATORS.sub("_", name.strip().lower())


def kind_token(name: str) -> str:
    """The kind a label names: its canonical form without a number suffix (`Widget 2` ->
    `widget`), as `Dictionary.resolve` reads `plate_2` as `plate`."""
    token = canonical_token(name)
    return _NUMBER_SUFFIX.sub("", token) or token


def properties_text(props: ObjectProperties) -> str:
    """`fixed surface, capacity 3`, `movable container, capacity 1`, `movable`."""
    return _props_text(props)


def _props_text(props: ObjectProperties) -> str:
    if props.room:
        return "room"
    kinds = [k for k, on in (("surface", props.surface), ("container", props.container)) if on]
    text = " ".join(["movable" if props.movable else "fixed", *kinds])
    if kinds:
        text += f", capacity {'unlimited' if props.capacity is None else props.capacity}"
    if props.openable:
        text += ", openable"
    if props.toggleable:
        text += ", toggleable"
    for role in (*THERMAL_ROLES.values(), *SOURCE_ROLES):
        if getattr(props, role):
            text += f", {role.replace('_', ' ')}"
    return text


def state_value(state: dict[str, bool], key: str) -> bool:
    """A node's state `key` (`open`, `toggled_on`), its default when the node has none:
    an openable object is closed and a toggleable one off unless its state says so."""
    return state.get(key, False)


def state_text(props: ObjectProperties, state: dict[str, bool]) -> str:
    """`closed (default), on`: each state the kind has, `(default)` where the node does
    not set it (an openable object is closed, a toggleable one off); empty for a kind
    with no state."""
    words = []
    for key, role in STATE_ROLES.items():
        if getattr(props, role):
            word = STATE_WORDS[key][state_value(state, key)]
            words.append(word if key in state else f"{word} (default)")
    return ", ".join(words)


def open_label_properties(attrs: dict[str, Any]) -> ObjectProperties | None:
    """Properties of a label no dictionary knows, from the role its node's attrs declare.

    None when the attrs declare no role (none of movable, surface, container). The
    defaults: movable true, surface and container false; a movable surface or container
    carries 1 object unless `capacity` says otherwise (as a block does), a fixed one any
    number (as a table does). Raises DictionaryError for a role of the wrong type.
    """
    if not any(key in attrs for key in (*ROLE_KEYS, *STATE_ROLE_KEYS, "room")):
        return None
    base = ObjectProperties()
    if attrs.get("room") is True and "movable" not in attrs:  # a room stays where it is
        base = ObjectProperties(movable=False)
    movable = attrs.get("movable", True)
    if "capacity" not in attrs and movable is True and (
            attrs.get("surface") is True or attrs.get("container") is True):
        base = ObjectProperties(capacity=1)
    return base.overridden(attrs)


LabelName = Annotated[str, StringConstraints(
    strict=True, min_length=1, max_length=MAX_LABEL_LENGTH, pattern=r"^[A-Za-z0-9][\w \-]*$")]


class UserObject(BaseModel):
    """One kind of object a client defines: its role, synonyms and how it looks."""

    model_config = ConfigDict(extra="forbid", frozen=True)

    synonyms: tuple[LabelName, ...] = Field(default=(), max_length=MAX_SYNONYMS)
    movable: bool = Field(default=True, strict=True)
    surface: bool = Field(default=False, strict=True)
    container: bool = Field(default=False, strict=True)
    capacity: int | None = Field(default=None, ge=0, le=MAX_CAPACITY, strict=True)
    openable: bool = Field(default=False, strict=True)
    toggleable: bool = Field(default=False, strict=True)
    room: bool = Field(default=False, strict=True)
    cookable: bool = Field(default=False, strict=True)
    heatable: bool = Field(default=False, strict=True)
    freezable: bool = Field(default=False, strict=True)
    heat_source: bool = Field(default=False, strict=True)
    cold_source: bool = Field(default=False, strict=True)
    width: float | None = Field(default=None, ge=MIN_SIZE, le=MAX_SIZE, allow_inf_nan=False)
    height: float | None = Field(default=None, ge=MIN_SIZE, le=MAX_SIZE, allow_inf_nan=False)
    color: str | None = Field(default=None, max_length=32)
    shape: str | None = Field(default=None, max_length=32)

    @field_validator("synonyms", mode="before")
    @classmethod
    def _strings(cls, value: Any) -> Any:
        if isinstance(value, list | tuple):
            for item in value:
                if not isinstance(item, str):
                    raise ValueError(f"synonyms are words, got {str(item)[:32]!r} (fix: write "
                                     'each synonym as a string, e.g. ["notebook computer"])')
        return value


def _json_size(value: object) -> int:
    try:
        return len(json.dumps(value, default=str))
    except (TypeError, ValueError, RecursionError):
        return MAX_INLINE_BYTES + 1


class InlineDictionary(BaseModel):
    """A dictionary D given by the client: its own labels, optionally extending a built-in.

    `{"extends": "tableware", "objects": {"laptop": {"surface": true, "capacity": 1}}}`.
    Without `extends` only the client's labels are known. A label or synonym may not give
    a built-in word other properties (one name, one kind: a node overrides properties in
    its attrs instead).
    """

    model_config = ConfigDict(extra="forbid", frozen=True)

    name: str | None = Field(default=None, min_length=1, max_length=32,
                             pattern=r"^[A-Za-z0-9][\w\-]*$", strict=True,
                             description="shown in texts; default: <extends>+yours")
    extends: str | None = Field(default=None, max_length=32, strict=True,
                                description=f"{', '.join(BUILTIN_DICTIONARIES)}, all or behavior")
    objects: dict[LabelName, UserObject] = Field(min_length=1)

    @model_validator(mode="before")
    @classmethod
    def _bounded(cls, data: Any) -> Any:
        """Refuse a huge dictionary before its labels are validated one by one."""
        if not isinstance(data, dict):
            return data
        objects = data.get("objects")
        if isinstance(objects, dict) and any(not isinstance(k, str) for k in objects):
            raise ValueError("every label in objects must be a string (fix: name each kind "
                             'as text, e.g. "laptop")')
        if isinstance(objects, dict) and len(objects) > MAX_USER_LABELS:
            raise ValueError(f"objects has {len(objects)} labels; at most {MAX_USER_LABELS} "
                             "are accepted (fix: keep the labels of this scene only)")
        size = _json_size(data)
        if size > MAX_INLINE_BYTES:
            raise ValueError(f"the dictionary is {size} bytes as JSON; at most "
                             f"{MAX_INLINE_BYTES} are accepted (fix: fewer labels or synonyms, "
                             f"at most {MAX_SYNONYMS} synonyms each)")
        return data

    @field_validator("extends")
    @classmethod
    def _known_base(cls, value: str | None) -> str | None:
        if value is not None and value not in (*BUILTIN_DICTIONARIES, "all", BEHAVIOR):
            raise ValueError(f"no built-in dictionary '{value[:32]}' to extend (fix: use one "
                             f"of {', '.join(BUILTIN_DICTIONARIES)}, all, {BEHAVIOR}, or leave "
                             "extends out)")
        return value

    @model_validator(mode="after")
    def _one_name_one_kind(self) -> InlineDictionary:
        """One word, one kind: two of the client's labels may not share a word, and no
        word may end in a number suffix (`cup_2`): a node labelled `cup_2` reads as `cup`
        (the suffix tells objects apart), so such a word could never name a kind of its
        own. A built-in word is the client's to take (see `replacements`)."""
        mine: dict[str, str] = {}
        for label, obj in self.objects.items():
            for word in (label, *obj.synonyms):
                token = canonical_token(word)
                what = "label" if word == label else f"synonym of {label}"
                if _NUMBER_SUFFIX.search(token):
                    stem = _NUMBER_SUFFIX.sub("", token)
                    raise ValueError(
                        f"{what} '{word}' ends in a number suffix: a node labelled {token} "
                        f"reads as {stem}, the suffix telling objects of one kind apart "
                        f"(fix: name the kind without the suffix, e.g. {stem}, and number "
                        f"the node ids instead, e.g. {stem}_1, {stem}_2)")
                if token in mine and mine[token] != label:
                    raise ValueError(f"'{word}' names both {mine[token]} and {label} (fix: "
                                     "give each word to one label only)")
                mine[token] = label
        return self

    def replacements(self) -> dict[str, list[str]]:
        """Label -> what its words take the place of among the built-ins, e.g. `shelf` ->
        [`replaces the built-in shelf: fixed surface, capacity 3 (tableware dictionary)`].

        What the client declares wins, with or without `extends`: a built-in word the
        client uses names the client's kind in this dictionary, and the texts say so.
        A label of the same kind (role and capacity) as the built-in replaces nothing.
        """
        words = _builtin_words()
        out: dict[str, list[str]] = {}
        for label, obj in self.objects.items():
            props = ObjectProperties(**obj.model_dump())
            mine = canonical_token(label)
            notes: dict[str, list[str]] = {}
            for word in (label, *obj.synonyms):
                for home, canonical, theirs in words.get(canonical_token(word), ()):
                    if canonical == mine and _same_kind(props, theirs):
                        continue  # the built-in kind itself (a synonym it has, or no change)
                    if word == label and canonical == mine:
                        note = f"the built-in {canonical}: {_props_text(theirs)}"
                    else:
                        note = (f"'{word}' as the built-in {canonical}: "
                                f"{_props_text(theirs)}")
                    notes.setdefault(note, []).append(home)
            if notes:
                out[canonical_token(label)] = [
                    f"replaces {note} ({' and '.join(homes)} dictionary)"
                    for note, homes in notes.items()]
        return out

    def build(self) -> Dictionary:
        return _built(self.model_dump_json())


def _same_kind(a: ObjectProperties, b: ObjectProperties) -> bool:
    keys = ("movable", "surface", "container", "capacity", "openable", "toggleable", "room",
            *THERMAL_ROLES.values(), *SOURCE_ROLES)
    return all(getattr(a, k) == getattr(b, k) for k in keys)


@cache
def _builtin_words() -> dict[str, tuple[tuple[str, str, ObjectProperties], ...]]:
    """Every built-in word (name or synonym) -> (dictionary, canonical name, properties);
    a kind the household takes unchanged from the paper's worlds is theirs only."""
    words: dict[str, list[tuple[str, str, ObjectProperties]]] = {}
    for name in (*UNION_DICTIONARIES, *(n for n in BUILTIN_DICTIONARIES
                                        if n not in UNION_DICTIONARIES)):
        d = builtin_dictionary(name)
        for canonical, props in d.objects.items():
            for word in (canonical, *props.synonyms):
                homes = words.setdefault(canonical_token(word), [])
                if not any(c == canonical and p == props for _, c, p in homes):
                    homes.append((name, canonical, props))
    return {k: tuple(v) for k, v in words.items()}


_BUILT: OrderedDict[str, Dictionary] = OrderedDict()
_MAX_BUILT = 64


def _built(spec_json: str) -> Dictionary:
    """The Dictionary of an inline spec; the last few are kept (texts rebuild it often)."""
    hit = _BUILT.get(spec_json)
    if hit is not None:
        _BUILT.move_to_end(spec_json)
        return hit
    spec = InlineDictionary.model_validate_json(spec_json)
    base = load_dictionary(spec.extends) if spec.extends is not None else None
    objects = dict(base.objects) if base is not None else {}
    user = []
    for label, obj in spec.objects.items():
        canonical = canonical_token(label)
        props = ObjectProperties(**obj.model_dump())
        replaced = objects.get(canonical)
        if replaced is not None:  # the base's synonyms of a label it replaces stay its own
            kept = tuple(w for w in replaced.synonyms if w not in props.synonyms)
            props = props.model_copy(update={"synonyms": (*props.synonyms, *kept)})
        objects[canonical] = props
        user.append(canonical)
    name = spec.name or (f"{spec.extends}+yours" if spec.extends else "yours")
    built = Dictionary(name=name, relations=base.relations if base else SUPPORT_RELATIONS,
                       objects=objects, inline=spec, user_labels=tuple(user),
                       ambiguous=dict(base.ambiguous) if base else {})
    _BUILT[spec_json] = built
    while len(_BUILT) > _MAX_BUILT:
        _BUILT.popitem(last=False)
    return built


_KINDS = {dict: "an object", list: "a list", str: "text", bool: "a boolean", int: "a number",
          float: "a number", type(None): "null"}


def _inline_problem(exc: ValidationError) -> tuple[str, str, str]:
    """(where, reason, fix) of the first problem of an inline dictionary."""
    err = exc.errors()[0]
    where = ".".join(str(p) for p in err["loc"])
    message = str(err["msg"]).removeprefix("Value error, ")
    fix = "see docs/worlds.md, e.g. {\"extends\": \"tableware\", \"objects\": " \
          "{\"laptop\": {\"surface\": true, \"capacity\": 1}}}"
    if " (fix: " in message:
        message, fix = message.split(" (fix: ", 1)
        fix = fix.removesuffix(")")
    elif err["type"] not in ("value_error", "assertion_error"):
        got = _KINDS.get(type(err.get("input")), type(err.get("input")).__name__)
        message = f"{message[:1].lower()}{message[1:]} (got {got})"
        if where == "extends":
            fix = (f"give extends as the name of a built-in dictionary: "
                   f"{', '.join(BUILTIN_DICTIONARIES)} or all (or leave it out)")
        elif where == "objects":
            fix = ("give objects as an object of label -> properties, e.g. "
                   "{\"laptop\": {\"surface\": true, \"capacity\": 1}}")
    return where, message, fix


def inline_or_name(value: Any) -> Any:
    """Pydantic before-validator of a dictionary field: an object is read as an inline
    dictionary here, so that its first problem is reported with its own field and reason
    (`extends: input should be a valid string (got an object)`) instead of as a failed
    match of every member of the name-or-object union."""
    if not isinstance(value, dict):
        return value
    try:
        return InlineDictionary.model_validate(value)
    except ValidationError as exc:
        where, message, fix = _inline_problem(exc)
        text = f"dictionary.{where}: {message}" if where else message
        raise PydanticCustomError("inline_dictionary", "{reason}",
                                  {"reason": f"{text} (fix: {fix})"}) from None


def parse_inline(data: object, *, field: str = "dictionary") -> InlineDictionary:
    """An InlineDictionary from JSON data, or a DictionaryError naming the field and fix."""
    try:
        return InlineDictionary.model_validate(data)
    except ValidationError as exc:
        sub, message, fix = _inline_problem(exc)
        where = f"{field}.{sub}" if sub else field
        raise DictionaryError(message, field=where, value=None, fix=fix) from None


class Dictionary(BaseModel):
    """A named set of object kinds with synonyms and the relations R that go with them."""

    model_config = ConfigDict(extra="forbid", frozen=True)

    name: str
    relations: tuple[str, ...] = SUPPORT_RELATIONS
    objects: dict[str, ObjectProperties]
    inline: InlineDictionary | None = Field(
        default=None, description="the client's own dictionary this one was built from")
    user_labels: tuple[str, ...] = Field(
        default=(), description="labels the client defined (inline or in a node's attrs)")
    ambiguous: dict[str, tuple[str, ...]] = Field(
        default_factory=dict, description="words that name different kinds in the "
                                          "dictionaries merged here -> the choices")
    _lookup: dict[str, str] = PrivateAttr(default_factory=dict)

    def model_post_init(self, __context: object) -> None:
        lookup: dict[str, str] = {}
        for canonical, props in self.objects.items():
            lookup[canonical_token(canonical)] = canonical
            for synonym in props.synonyms:
                lookup.setdefault(canonical_token(synonym), canonical)
        # The client's words win over the base's (see InlineDictionary.replacements):
        # its synonyms, then its labels, take the words they name.
        user = [label for label in self.user_labels if label in self.objects]
        for canonical in user:
            for synonym in self.objects[canonical].synonyms:
                lookup[canonical_token(synonym)] = canonical
        for canonical in user:
            lookup[canonical_token(canonical)] = canonical
        mine = set(user)
        for token in self.ambiguous:
            if token not in self.objects and lookup.get(token) not in mine:
                lookup.pop(token, None)
        self._lookup = lookup

    @property
    def names(self) -> list[str]:
        return sorted(self.objects)

    def reference(self) -> str | InlineDictionary | None:
        """What a scene graph names this dictionary by (the union: nothing)."""
        if self.inline is not None:
            return self.inline
        return None if self.name == "all" else self.name

    def resolve(self, name: str) -> str | None:
        """Canonical name for `name` (synonyms, case, spaces, `_2` suffixes), or None.

        None also for a word that names different kinds here (see `choices`)."""
        lookup = self._lookup
        token = canonical_token(name)
        if token in lookup:
            return lookup[token]
        stripped = _NUMBER_SUFFIX.sub("", token)
        return lookup.get(stripped)

    def choices(self, name: str) -> tuple[str, ...]:
        """The kinds an ambiguous word may mean (empty when it is not ambiguous)."""
        token = canonical_token(name)
        return self.ambiguous.get(token) or self.ambiguous.get(
            _NUMBER_SUFFIX.sub("", token), ())

    def reading(self, name: str) -> str | None:
        """How a label was read when it is not written as its canonical name, e.g.
        `box read as block (synonym, blocks dictionary)`; None when nothing changed."""
        canonical = self.resolve(name)
        if canonical is None or name == canonical:
            return None
        token = canonical_token(name)
        stripped = _NUMBER_SUFFIX.sub("", token)
        if token == canonical or (token not in self._lookup and stripped == canonical):
            how = "case and spacing" if token == canonical else "number suffix dropped"
        else:
            how = "synonym"
        return f"{name} read as {canonical} ({how}, {self.home(canonical)})"

    def home(self, canonical: str) -> str:
        """`your label`, or the dictionary a label comes from (`kitchen dictionary`)."""
        if canonical in self.user_labels:
            return "your label"
        if self.name in (*BUILTIN_DICTIONARIES, BEHAVIOR):
            return f"{self.name} dictionary"
        homes = _homes(lambda d: canonical in d.objects)
        return f"{' and '.join(homes) or self.name} dictionary"

    def with_open_labels(self, labels: dict[str, ObjectProperties]) -> Dictionary:
        """This dictionary plus labels that nodes declared in their attrs."""
        new = {k: v for k, v in labels.items() if k not in self.objects}
        if not new:
            return self
        # Built anew (not model_copy): the word lookup is made at construction.
        return Dictionary(name=self.name, relations=self.relations,
                          objects={**self.objects, **new}, inline=self.inline,
                          user_labels=(*self.user_labels, *new), ambiguous=self.ambiguous)

    def user_lines(self, limit: int = 20) -> list[str]:
        """`laptop: movable surface, capacity 1` for each of the client's labels, and what
        a label takes the place of among the built-ins: `shelf: fixed surface, capacity 2
        (yours; replaces the built-in shelf: fixed surface, capacity 3 (tableware
        dictionary))`."""
        replaced = self.inline.replacements() if self.inline is not None else {}
        lines = []
        for label in self.user_labels[:limit]:
            if label not in self.objects:
                continue
            line = f"{label}: {_props_text(self.objects[label])}"
            if label in replaced:
                line += f" (yours; {'; '.join(replaced[label])})"
            lines.append(line)
        if len(self.user_labels) > limit:
            lines.append(f"... and {len(self.user_labels) - limit} more of your labels")
        return lines

    def normalise(self, name: str, *, field: str = "label") -> str:
        """Canonical name, or a DictionaryError listing the nearest known names."""
        canonical = self.resolve(name)
        if canonical is not None:
            return canonical
        choices = self.choices(name)
        if choices:
            raise DictionaryError(
                f"'{name}' is ambiguous in the {self.name} dictionary: it may mean "
                f"{' or '.join(choices)}", field=field, value=name,
                fix=f"write one of {', '.join(choices)}, or name the dictionary you mean")
        examples = self.nearest(name) or self.names[:5]
        raise DictionaryError(
            f"'{name}' is not in the {self.name} dictionary", field=field, value=name,
            fix=f"use a known name such as {', '.join(examples)}")

    def nearest(self, name: str, n: int = 3) -> list[str]:
        """Closest canonical names to an unknown one, for suggestions."""
        lookup = self._lookup
        hits = difflib.get_close_matches(canonical_token(name), list(lookup), n=n * 2, cutoff=0.5)
        seen: list[str] = []
        for hit in hits:
            if lookup[hit] not in seen:
                seen.append(lookup[hit])
        return seen[:n]

    def properties(self, label: str) -> ObjectProperties:
        return self.objects[self.normalise(label)]


def merge_dictionaries(name: str, parts: list[Dictionary]) -> Dictionary:
    """Several dictionaries as one. A word (name or synonym) that names different kinds
    in different parts is kept as ambiguous with its choices, never mapped one way."""
    objects: dict[str, ObjectProperties] = {}
    relations: list[str] = []
    meanings: dict[str, dict[str, None]] = {}
    for d in parts:
        for rel in d.relations:
            if rel not in relations:
                relations.append(rel)
        for label, props in d.objects.items():
            objects.setdefault(label, props)
            for word in (label, *props.synonyms):
                meanings.setdefault(canonical_token(word), {})[label] = None
    ambiguous = {token: tuple(kinds) for token, kinds in meanings.items() if len(kinds) > 1}
    return Dictionary(name=name, relations=tuple(relations), objects=objects,
                      ambiguous=ambiguous)


@cache
def builtin_dictionary(name: str) -> Dictionary:
    """One of the dictionaries shipped in `verigraph/graph/data`.

    A file may start from other built-ins (`extends: [kitchen, tableware]`): their
    merge, then the file's `relations` (if given) and its `objects`, each entry either a
    new kind or properties that change the base's kind of that name
    (`stove: {toggleable: true}`). So a dictionary that adds to another repeats nothing.
    """
    if name not in BUILTIN_DICTIONARIES:
        raise DictionaryError(f"no built-in dictionary named '{name}'", field="dictionary",
                              value=name, fix=f"use one of {', '.join(BUILTIN_DICTIONARIES)} "
                              "or a path to a YAML/JSON dictionary file")
    text = resources.files("verigraph.graph").joinpath("data", f"{name}.yaml").read_text()
    data: dict[str, Any] = yaml.safe_load(text)
    bases: list[str] = data.pop("extends", [])
    if not bases:
        return Dictionary.model_validate(data)
    base = merge_dictionaries(name, [builtin_dictionary(b) for b in bases])
    own = {label: ObjectProperties.model_validate(
               {**base.objects[label].model_dump(), **entry} if label in base.objects
               else entry)
           for label, entry in data.get("objects", {}).items()}
    part = Dictionary(name=name, relations=tuple(data.get("relations", base.relations)),
                      objects=own)
    return merge_dictionaries(name, [part, base])


@cache
def union_dictionary() -> Dictionary:
    """The paper's worlds merged (UNION_DICTIONARIES): what applies when a scene names
    none or names "all"."""
    return merge_dictionaries("all", [builtin_dictionary(n) for n in UNION_DICTIONARIES])


def load_dictionary(spec: str | Path | Dictionary | InlineDictionary | None) -> Dictionary:
    """Resolve a dictionary given by built-in name, file path, model, inline spec, or None
    (the union)."""
    if spec is None:
        return union_dictionary()
    if isinstance(spec, Dictionary):
        return spec
    if isinstance(spec, InlineDictionary):
        return spec.build()
    if isinstance(spec, str) and spec in BUILTIN_DICTIONARIES:
        return builtin_dictionary(spec)
    if isinstance(spec, str) and spec == "all":
        return union_dictionary()
    if isinstance(spec, str) and spec == BEHAVIOR:  # read on first use (3,299 kinds)
        behavior: Dictionary = behavior_dictionary()
        return behavior
    path = Path(spec)
    if not path.is_file():
        raise DictionaryError(f"dictionary '{spec}' is neither built in nor a file",
                              field="dictionary", value=str(spec),
                              fix=f"use one of {', '.join(BUILTIN_DICTIONARIES)}, all, "
                                  f"{BEHAVIOR} or a file path")
    try:
        data = yaml.safe_load(path.read_text())
        return Dictionary.model_validate(data)
    except (yaml.YAMLError, ValidationError, UnicodeDecodeError) as exc:
        raise InputFileError(f"cannot read dictionary file: {exc}", field="dictionary",
                             value=str(path), fix="give a YAML/JSON mapping with 'name' and "
                             "'objects: {name: {movable: ..., surface: ...}}'") from None


def named_dictionary(reference: str | InlineDictionary | None) -> Dictionary:
    """The dictionary a graph names (`SceneGraph.dictionary`), for a text about it: a
    built-in, the client's inline one, the union for none or "all", and the union too
    for a name that is not built in (a file's, a PDDL domain's): never a file read,
    never an error."""
    if isinstance(reference, str) and reference not in (*BUILTIN_DICTIONARIES, "all",
                                                        BEHAVIOR):
        return union_dictionary()
    return load_dictionary(reference)


def _homes(knows: Callable[[Dictionary], bool]) -> list[str]:
    """The paper's worlds that know a word; only when none does, the other built-ins
    that do (`pan` is the kitchen's, though the household extends the kitchen)."""
    homes = [name for name in UNION_DICTIONARIES if knows(builtin_dictionary(name))]
    return homes or [name for name in BUILTIN_DICTIONARIES
                     if name not in UNION_DICTIONARIES and knows(builtin_dictionary(name))]


def builtin_homes(label: str) -> list[str]:
    """The built-in dictionaries that know `label` (by name, synonym or `_2` suffix):
    the paper's worlds that do, or else the household if it does."""
    return _homes(lambda d: d.resolve(label) is not None)


def _quoted(labels: list[str]) -> str:
    names = [f"`{label}`" for label in labels]
    return names[0] if len(names) == 1 else f"{', '.join(names[:-1])} and {names[-1]}"


def wrong_dictionary_advice(labels: list[str], chosen: str, every_label: list[str]
                            ) -> tuple[str, str, list[str]] | None:
    """Where labels unknown to dictionary `chosen` live among the other built-ins.

    Returns (message, fix, labels it covers), e.g. "`table` and `tray` are in the
    tableware dictionary; use it, or omit `dictionary` to use all built-ins"; None when
    no other built-in knows any of them (a spelling matter: the nearest names help more).
    One dictionary that knows them all is preferred; else the fewest that do. "use it"
    only when that dictionary also knows `every_label` of the scene.
    """
    elsewhere = {label: [h for h in builtin_homes(label) if h != chosen]
                 for label in dict.fromkeys(labels)}
    elsewhere = {label: homes for label, homes in elsewhere.items() if homes}
    if not elsewhere:
        return None
    groups: dict[str, list[str]] = {}
    remaining = list(elsewhere)
    while remaining:
        candidates = {h for label in remaining for h in elsewhere[label]}
        best = max(sorted(candidates), key=lambda h: sum(h in elsewhere[x] for x in remaining))
        groups[best] = [label for label in remaining if best in elsewhere[label]]
        remaining = [label for label in remaining if label not in groups[best]]
    ((home, known),) = list(groups.items())[:1]
    home_dictionary = builtin_dictionary(home)
    if len(groups) == 1 and all(home_dictionary.resolve(x) is not None for x in every_label):
        verb = "is" if len(known) == 1 else "are"
        if home not in UNION_DICTIONARIES:  # the household: only by its name
            return (f"{_quoted(known)} {verb} in the {home} dictionary; use it",
                    f'set "dictionary": "{home}"', list(elsewhere))
        return (f"{_quoted(known)} {verb} in the {home} dictionary; use it, or omit "
                "`dictionary` to use all built-ins",
                f'set "dictionary": "{home}" or leave it out', list(elsewhere))
    parts = "; ".join(f"{_quoted(labels_)} in {name}" for name, labels_ in groups.items())
    return (f"these labels are not in the {chosen} dictionary ({parts}); omit `dictionary` "
            "to use all built-ins", "leave \"dictionary\" out", list(elsewhere))


MAX_APPLIED = 12
# What a built-in property is: an assumption about a kind, not a fact about the user's
# object; the user decides, and a node's attrs win over it.
DEFAULTS_NOTE = ("These are built-in defaults, assumed: confirm them with the user; a "
                 "node's attrs win over them")


def applied_properties(graph: SceneGraph | None, dictionary: Dictionary,
                       *more: SceneGraph | None, limit: int = MAX_APPLIED) -> list[str]:
    """The built-in properties a check applies to the graphs' nodes, once per kind:
    `shelf: fixed surface, capacity 3 (tableware dictionary)`; a node whose attrs
    change a role or capacity gets its own entry (`cup: movable container, capacity 2
    (tableware dictionary; capacity from cup_2's attrs)`). The client's own labels are
    left out (the client declared them), and so is a kind that is only movable (a fork,
    a tangram piece): it carries nothing, and nothing about it needs confirming. At most
    `limit` entries, then a count."""
    entries: dict[str, None] = {}
    for written in (graph, *more):
        for node in written.nodes if written is not None else ():
            label = dictionary.resolve(node.label)
            if label is None or label in dictionary.user_labels:
                continue
            props = dictionary.objects[label]
            changed: list[str] = []
            if not node.attrs.keys().isdisjoint(KIND_KEYS):  # its attrs change its kind
                try:
                    mine = props.overridden(node.attrs)
                except DictionaryError:
                    mine = props
                changed = [k for k in KIND_KEYS if getattr(mine, k) != getattr(props, k)]
                props = mine
            if not changed and not (props.surface or props.container or not props.movable):
                continue  # a plain movable thing: nothing about it for anyone to confirm
            where = dictionary.home(label)
            if changed:
                where += f"; {', '.join(changed)} from {node.id}'s attrs"
            entries.setdefault(f"{label}: {properties_text(props)} ({where})")
    found = list(entries)
    if len(found) > limit:
        found = [*found[:limit], f"... and {len(found) - limit} more"]
    return found


def applied_line(graph: SceneGraph | None, *more: SceneGraph | None,
                 dictionary: Dictionary | None = None) -> str:
    """`built-in properties applied (dictionary: all built-ins, none named): shelf: fixed
    surface, capacity 3 (tableware dictionary); ...`, or empty when none apply. A check
    without a stored episode shows what it assumed about each built-in kind.
    `dictionary`: the one the graphs were read with; None: the one the first graph
    names (`named_dictionary`)."""
    written = graph
    for written in (graph, *more):  # the first graph given
        if written is not None:
            break
    if dictionary is None:
        dictionary = named_dictionary(written.dictionary if written is not None else None)
    entries = applied_properties(graph, dictionary, *more)
    if not entries:
        return ""
    named = ("all built-ins, none named" if written is None or written.dictionary is None
             else dictionary.name)
    text = "; ".join(entries)  # "capacity" within one entry is within the text, and back
    note = f". {DEFAULTS_NOTE}" if "capacity" in text else ""
    return f"built-in properties applied (dictionary: {named}): " + text + note
