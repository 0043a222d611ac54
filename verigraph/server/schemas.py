"""Compact wire schemas for tools/list: the same contract in fewer bytes.

Every chat turn sends tools/list to the model, so its size is a cost per turn. The
pydantic models stay the single source of truth and still validate every call (the
call path, verigraph.server.tools) and every result (the SDK); these only rewrite what is
*published*:

- inputs: no per-property `title` (it repeats the name), no `examples`, no string
  length, pattern or numeric bounds (the server checks them and answers with the
  field, the allowed range and the fix), no `null` branch for optional arguments (omit
  them instead), nested unions flattened into one `anyOf` without the OpenAPI-only
  `discriminator`, the action kinds merged into one `Action` shape, a description on
  every top-level property (lifted from its union member when only that member had
  one; the member's own words, such as "from load_scene", only where tools/list first
  sends them), and the fields of a shared definition described only where tools/list first
  defines it;
- outputs: structure only (types, properties, `$defs`, unions, consts and short
  enums). The text content and the input descriptions carry the meaning; an output
  schema is what a client validates results with, so it stays exact about shapes and
  never stricter than the results; a shape repeated across its fields (a list of
  strings) is written once under `$defs`.
"""

from __future__ import annotations

import json
from typing import Any

Schema = dict[str, Any]

_NAME_MAPS = ("properties", "$defs", "patternProperties")
_SCHEMA_LISTS = ("anyOf", "oneOf", "allOf", "prefixItems")
_SCHEMA_VALUES = ("items", "not", "contains", "propertyNames")
_NEVER = ("title", "examples", "discriminator")
_INPUT_DROPPED = (*_NEVER, "minLength", "maxLength", "pattern", "maxItems", "minItems",
                  "minimum", "maximum", "exclusiveMinimum", "exclusiveMaximum")
_OUTPUT_KEPT = ("type", "properties", "items", "$defs", "$ref", "anyOf", "oneOf",
                "allOf", "const", "enum", "additionalProperties", "prefixItems")
NULL: Schema = {"type": "null"}
_INNER = "x-type-description"  # working mark only, never published
# Longer enums (constraint ids) are dropped from outputs; the action tags of a state
# action (open ... thaw: 9) stay, or a move would also match StateAction's shape.
MAX_OUTPUT_ENUM = 9


def _walk(schema: Any, node: Any) -> Any:
    """Apply `node` to every subschema, children first."""
    if not isinstance(schema, dict):
        return schema
    out: Schema = {}
    for key, value in schema.items():
        if key in _NAME_MAPS and isinstance(value, dict):
            out[key] = {name: _walk(sub, node) for name, sub in value.items()}
        elif key in _SCHEMA_LISTS and isinstance(value, list):
            out[key] = [_walk(sub, node) for sub in value]
        elif (key in _SCHEMA_VALUES or key == "additionalProperties") and isinstance(value, dict):
            out[key] = _walk(value, node)
        else:
            out[key] = value
    result: Schema = node(out)
    return result


def _flatten_unions(schema: Schema) -> Schema:
    """`anyOf: [{oneOf: [a, b]}, c]` -> `anyOf: [a, b, c]` (members already disjoint)."""
    for key in ("anyOf", "oneOf"):
        members = schema.get(key)
        if not isinstance(members, list):
            continue
        flat: list[Any] = []
        for member in members:
            inner = [k for k in ("anyOf", "oneOf") if k in member] if isinstance(member, dict) \
                else []
            if inner and set(member) <= {"anyOf", "oneOf", "description"}:
                flat.extend(member[inner[0]])
            else:
                flat.append(member)
        schema[key] = flat
    return schema


def _merge_single(schema: Schema, key: str) -> Schema:
    """A union of one member is that member, keeping the outer description first."""
    (member,) = schema.pop(key)
    outer = schema.pop("description", None)
    inner = member.get("description")
    merged = {**schema, **member}
    if outer and inner and inner != outer:
        merged["description"] = f"{outer}; {inner}"
        merged[_INNER] = inner  # the type's own words: sent once (compact_input_schema)
    elif outer or inner:
        merged["description"] = outer or inner
    return merged


def _input_node(schema: Schema) -> Schema:
    for key in _INPUT_DROPPED:
        schema.pop(key, None)
    if "default" in schema and (schema["default"] is None or "const" in schema):
        del schema["default"]
    if isinstance(schema.get("additionalProperties"), bool):
        del schema["additionalProperties"]
    kinds = schema.get("type")
    if isinstance(kinds, list) and "null" in kinds and len(kinds) > 1:
        schema["type"] = [k for k in kinds if k != "null"]  # omit the argument instead
    schema = _flatten_unions(schema)
    for key in ("anyOf", "oneOf"):
        if key in schema:
            schema[key] = [m for m in schema[key] if m != NULL]
            if len(schema[key]) == 1:
                schema = _merge_single(schema, key)
    return schema


def _output_node(schema: Schema) -> Schema:
    kept = {k: v for k, v in schema.items() if k in _OUTPUT_KEPT}
    if isinstance(kept.get("additionalProperties"), bool):
        del kept["additionalProperties"]
    if len(kept.get("enum", ())) > MAX_OUTPUT_ENUM:
        del kept["enum"]  # e.g. constraint ids: listed by verigraph://constraints
    kept = _flatten_unions(kept)
    members = kept.get("anyOf")
    # `anyOf: [{type: T}, {type: null}]` -> `type: [T, null]`
    if (isinstance(members, list) and len(members) == 2 and NULL in members
            and set(kept) == {"anyOf"}):
        other = members[0] if members[1] == NULL else members[1]
        if set(other) == {"type"} and isinstance(other["type"], str):
            return {"type": [other["type"], "null"]}
    return kept


def _unmarked(schema: Schema) -> Schema:
    schema.pop(_INNER, None)
    return schema


def _without_repeats(schema: Any, seen: set[str]) -> Any:
    """Drop every description already in `seen`; add the others to it."""
    def node(sub: Schema) -> Schema:
        text = sub.get("description")
        if isinstance(text, str):
            if text in seen:
                del sub["description"]
            else:
                seen.add(text)
        return sub
    return _walk(schema, node)


def _tag(definition: Schema) -> tuple[str, list[Any]] | None:
    """(property, values) when the object is told apart by one const property (or an
    enum of them: `open`, `close`, ... are one kind of action)."""
    consts = [(name, [sub["const"]] if "const" in sub else list(sub["enum"]))
              for name, sub in definition.get("properties", {}).items()
              if isinstance(sub, dict) and ("const" in sub or "enum" in sub)]
    return consts[0] if len(consts) == 1 else None


def _merge_tagged(schema: Schema) -> Schema:
    """`anyOf: [$ref MoveAction, $ref AlignAction, $ref DoneAction, ...]` -> one object
    `Action` whose tag property is an enum: one shape for the model to fill instead of
    three. The published input is looser (a field of another kind is not refused by the
    schema); the server still validates each kind and names the field and the fix."""
    definitions: Schema = schema.get("$defs", {})

    def node(sub: Schema) -> Schema:
        members = sub.get("anyOf")
        if not isinstance(members, list):
            return sub
        refs = [m for m in members if set(m) == {"$ref"}]
        tagged = [(m, definitions[m["$ref"].rsplit("/", 1)[-1]]) for m in refs]
        tags = [_tag(d) for _, d in tagged]
        if len(tagged) < 2 or None in tags or len({t[0] for t in tags if t}) != 1:
            return sub
        prop = tags[0][0] if tags[0] else ""
        merged_name = prop.capitalize()
        if merged_name not in definitions:
            properties: Schema = {}
            for _, definition in tagged:
                for name, field in definition["properties"].items():
                    properties.setdefault(name, field)
            first = properties[prop]
            properties[prop] = {"enum": [v for t in tags if t for v in t[1]], **{
                k: v for k, v in first.items() if k not in ("const", "default", "enum")}}
            defaults = [d["properties"][prop].get("default") for _, d in tagged]
            if defaults[0] is not None:
                properties[prop]["default"] = defaults[0]
            definitions[merged_name] = {"properties": properties, "type": "object"}
        rest = [m for m in members if m not in refs]
        sub["anyOf"] = [{"$ref": f"#/$defs/{merged_name}"}, *rest]
        return sub

    out: Schema = _walk(schema, node)
    out["$defs"] = definitions
    used = json.dumps({k: v for k, v in out.items() if k != "$defs"}) + json.dumps(definitions)
    for name in [n for n in definitions if f'"#/$defs/{n}"' not in used]:
        del definitions[name]
    return out


def compact_input_schema(schema: Schema, documented: set[str] | None = None) -> Schema:
    """The published inputSchema of a tool (see the module docstring).

    `documented` holds the nested descriptions (fields of SceneGraph, Goal, Action, the
    text form of an action...) that an earlier tool in tools/list already sent: a model
    reads the whole list, so the words are sent once and later tools repeat only the
    shape. A top-level argument always keeps its own description.
    """
    out: Schema = _walk(schema, _input_node)
    if "$defs" in out:
        out = _merge_tagged(out)
    for definition in out.get("$defs", {}).values():
        definition.pop("description", None)  # class docstrings; the properties say it
    for prop in out.get("properties", {}).values():
        inner = prop.pop(_INNER, None)
        if documented is not None and inner is not None:
            if inner in documented:  # "from load_scene", the scene ids, the image format
                prop["description"] = prop["description"].removesuffix(f"; {inner}")
            documented.add(inner)
    out = _walk(out, _unmarked)
    if documented is None:
        return out
    out["$defs"] = {name: _without_repeats(definition, documented)
                    for name, definition in out.get("$defs", {}).items()} or None
    for name, prop in out.get("properties", {}).items():
        own = prop.get("description")
        nested = _without_repeats({k: v for k, v in prop.items() if k != "description"},
                                  documented)
        out["properties"][name] = {**nested, **({"description": own} if own else {})}
    if out["$defs"] is None:
        del out["$defs"]
    return out


# Shapes that recur across one result's fields (lists of edge texts, node ids, labels):
# written once under `$defs` and referenced, the same contract in fewer bytes.
SHARED_OUTPUT_SHAPES: dict[str, Schema] = {"Strings": {"items": {"type": "string"},
                                                       "type": "array"}}


def _share_shapes(schema: Schema) -> Schema:
    """Each shape of SHARED_OUTPUT_SHAPES used twice or more becomes one `$ref`."""
    text = json.dumps(schema, sort_keys=True)
    used = {name: shape for name, shape in SHARED_OUTPUT_SHAPES.items()
            if text.count(json.dumps(shape, sort_keys=True)) >= 2
            and name not in schema.get("$defs", {})}
    if not used:
        return schema
    refs = {json.dumps(shape, sort_keys=True): {"$ref": f"#/$defs/{name}"}
            for name, shape in used.items()}

    def node(sub: Schema) -> Schema:
        return refs.get(json.dumps(sub, sort_keys=True), sub)

    out: Schema = _walk(schema, node)
    out["$defs"] = {**out.get("$defs", {}), **used}
    return out


def compact_output_schema(schema: Schema) -> Schema:
    """The published outputSchema of a tool: the result's shape, nothing stricter.

    No `required`: every result carries all of its fields (null when unset), so the list
    would only repeat the property names.
    """
    out: Schema = _share_shapes(_walk(schema, _output_node))
    return out


def without_openapi_keywords(schema: Schema) -> Schema:
    """The schema minus `discriminator` (OpenAPI; strict JSON Schema validators refuse it)."""
    def node(sub: Schema) -> Schema:
        sub.pop("discriminator", None)
        return sub
    out: Schema = _walk(schema, node)
    return out
