"""The object dictionary D: canonical names, their properties and synonyms.

Properties drive every constraint (a cup goes `in` a bowl only if bowl is a
container), so the validator, the simulator and perception all read them from here.
"""

from __future__ import annotations

import difflib
import re
from functools import cache
from importlib import resources
from pathlib import Path

import yaml
from pydantic import BaseModel, ConfigDict, Field, PrivateAttr, ValidationError

from verigraph.errors import DictionaryError, InputFileError

BUILTIN_DICTIONARIES = ("blocks", "kitchen", "tableware", "tangram")
KNOWN_RELATIONS = ("on", "in", "touches")

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
        default=None, ge=0,
        description="how many objects it can carry on or in it at once; null = unlimited")
    # Descriptive properties used by the simulator, renderer and perception.
    width: float | None = None
    height: float | None = None
    color: str | None = None
    shape: str | None = None
    sides: int | None = Field(default=None, ge=3, description="tangram: number of sides")
    symmetry: int = Field(default=1, ge=1, description="tangram: rotational symmetry order")

    def overridden(self, attrs: dict[str, object]) -> ObjectProperties:
        """Properties with a node's `attrs` applied on top (only known property names)."""
        known = {k: v for k, v in attrs.items() if k in type(self).model_fields and k != "synonyms"}
        if not known:
            return self
        try:
            return type(self).model_validate({**self.model_dump(), **known})
        except ValidationError as exc:
            err = exc.errors()[0]
            field = ".".join(str(p) for p in err["loc"])
            raise DictionaryError(f"bad property override: {err['msg']}", field=f"attrs.{field}",
                                  value=known.get(field), fix="use the property's type, "
                                  "e.g. capacity: 2, movable: false") from None


def canonical_token(name: str) -> str:
    """`Cutting Board` -> `cutting_board`: the form names are compared in."""
    return _SEPARATORS.sub("_", name.strip().lower())


class Dictionary(BaseModel):
    """A named set of object kinds with synonyms and the relations R that go with them."""

    model_config = ConfigDict(extra="forbid", frozen=True)

    name: str
    relations: tuple[str, ...] = ("on", "in")
    objects: dict[str, ObjectProperties]
    _lookup: dict[str, str] = PrivateAttr(default_factory=dict)

    def model_post_init(self, __context: object) -> None:
        lookup: dict[str, str] = {}
        for canonical, props in self.objects.items():
            lookup[canonical_token(canonical)] = canonical
            for synonym in props.synonyms:
                lookup.setdefault(canonical_token(synonym), canonical)
        self._lookup = lookup

    @property
    def names(self) -> list[str]:
        return sorted(self.objects)

    def resolve(self, name: str) -> str | None:
        """Canonical name for `name` (synonyms, case, spaces, `_2` suffixes), or None."""
        lookup = self._lookup
        token = canonical_token(name)
        if token in lookup:
            return lookup[token]
        stripped = _NUMBER_SUFFIX.sub("", token)
        return lookup.get(stripped)

    def normalise(self, name: str, *, field: str = "label") -> str:
        """Canonical name, or a DictionaryError listing the nearest known names."""
        canonical = self.resolve(name)
        if canonical is not None:
            return canonical
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


@cache
def builtin_dictionary(name: str) -> Dictionary:
    """One of the dictionaries shipped in `verigraph/graph/data`."""
    if name not in BUILTIN_DICTIONARIES:
        raise DictionaryError(f"no built-in dictionary named '{name}'", field="dictionary",
                              value=name, fix=f"use one of {', '.join(BUILTIN_DICTIONARIES)} "
                              "or a path to a YAML/JSON dictionary file")
    text = resources.files("verigraph.graph").joinpath("data", f"{name}.yaml").read_text()
    return Dictionary.model_validate(yaml.safe_load(text))


@cache
def union_dictionary() -> Dictionary:
    """All built-in dictionaries merged: what applies when a scene names none."""
    objects: dict[str, ObjectProperties] = {}
    relations: list[str] = []
    for name in BUILTIN_DICTIONARIES:
        d = builtin_dictionary(name)
        for rel in d.relations:
            if rel not in relations:
                relations.append(rel)
        for label, props in d.objects.items():
            objects.setdefault(label, props)
    return Dictionary(name="all", relations=tuple(relations), objects=objects)


def load_dictionary(spec: str | Path | Dictionary | None) -> Dictionary:
    """Resolve a dictionary given by built-in name, file path, model, or None (the union)."""
    if spec is None:
        return union_dictionary()
    if isinstance(spec, Dictionary):
        return spec
    if isinstance(spec, str) and spec in BUILTIN_DICTIONARIES:
        return builtin_dictionary(spec)
    if isinstance(spec, str) and spec == "all":
        return union_dictionary()
    path = Path(spec)
    if not path.is_file():
        raise DictionaryError(f"dictionary '{spec}' is neither built in nor a file",
                              field="dictionary", value=str(spec),
                              fix=f"use one of {', '.join(BUILTIN_DICTIONARIES)} or a file path")
    try:
        data = yaml.safe_load(path.read_text())
        return Dictionary.model_validate(data)
    except (yaml.YAMLError, ValidationError, UnicodeDecodeError) as exc:
        raise InputFileError(f"cannot read dictionary file: {exc}", field="dictionary",
                             value=str(path), fix="give a YAML/JSON mapping with 'name' and "
                             "'objects: {name: {movable: ..., surface: ...}}'") from None


def builtin_homes(label: str) -> list[str]:
    """The built-in dictionaries that know `label` (by name, synonym or `_2` suffix)."""
    return [name for name in BUILTIN_DICTIONARIES
            if builtin_dictionary(name).resolve(label) is not None]


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
        return (f"{_quoted(known)} {verb} in the {home} dictionary; use it, or omit "
                "`dictionary` to use all built-ins",
                f'set "dictionary": "{home}" or leave it out', list(elsewhere))
    parts = "; ".join(f"{_quoted(labels_)} in {name}" for name, labels_ in groups.items())
    return (f"these labels are not in the {chosen} dictionary ({parts}); omit `dictionary` "
            "to use all built-ins", "leave \"dictionary\" out", list(elsewhere))
