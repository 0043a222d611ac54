"""STRIPS plans: one `(action arg ...)` per line, as planners and VAL write them.

Accepted per line: `(drive-truck t1 l1 l2 c1)`, `0: (drive-truck ...) [1]`, `1. (...)`,
`;` comments, blank lines and `[PLAN]` markers; and a sentence that starts with an action
name, filler words dropped (`load-truck p1 into t1 at l1`). Every other non-blank line is
a step that fails with `malformed_action` (VAL's and PlanBench's graders count such a
plan invalid at that step), its message naming the line and what is wrong: an unknown
action (the fix names the closest actions), the wrong number of arguments (the fix shows
the action's parameters), or a line that is no action at all (`(no plan possible)` is an
unknown action `no`; `(1) (feast d b)` is no action, and the fix is the action it holds).
An undeclared object is a verdict at its step too, decided by the simulator. Only a plan
that cannot be read at all is bad input (PlanParseError): a non-ASCII name, more than
`MAX_STEPS` actions.
"""

from __future__ import annotations

import difflib
import re
from collections.abc import Callable
from typing import NamedTuple

from verigraph.errors import PlanParseError
from verigraph.pddl.model import Domain
from verigraph.pddl.syntax import DURATION, STEP_PREFIX, ascii_names

FILLER = frozenset({"object", "the", "from", "on", "top", "of", "onto", "to", "into", "at",
                    "in", "with", "and", "a", "an"})
MAX_STEPS = 1_000_000
_PLAIN_LINE = re.compile(r"^\(([^\s()]+)((?: [^\s()]+)*)\)$", re.MULTILINE)
_INNER_ACTION = re.compile(r"\(([^()]+)\)\s*$")


class Step(NamedTuple):
    """One plan action: the schema name, its arguments as written, its source line; for a
    line that is no action of the domain, the line as `name` and the failure as
    `problem` (constraint, message, fix)."""

    name: str
    args: tuple[str, ...]
    line: int
    problem: tuple[str, str, str] | None = None

    def text(self) -> str:
        if self.problem is not None:
            return self.name
        return "(" + " ".join((self.name, *self.args)) + ")"


def _malformed(raw: str, number: int, constraint: str, message: str, fix: str) -> Step:
    shown = raw.strip()[:80]
    return Step(shown, (), number, (constraint, f"line {number}: {message}", fix))


def _read_line(raw: str, body: str, number: int, domain: Domain) -> Step:
    schemas = domain.schemas
    if body[0] == "(":
        if not body.endswith(")") or "(" in body[1:]:
            inner = _INNER_ACTION.search(body)
            fix = (f"write the action alone, ({inner.group(1).strip()})" if inner and
                   inner.start() > 0 else "write one (action arg ...) per line")
            return _malformed(raw, number, "malformed_action", f"{raw.strip()[:60]} is not an "
                              "action", fix)
        words = body[1:-1].split()
    else:
        words = body.split()
        words = words[:1] + [w for w in words[1:] if w not in FILLER]
    if not words:
        return _malformed(raw, number, "malformed_action", f"{raw.strip()[:60]} is not an "
                          "action", "write (action arg ...)")
    schema = schemas.get(words[0])
    if schema is None:
        near = difflib.get_close_matches(words[0], list(schemas), n=3, cutoff=0.6)
        names = ", ".join(near or list(schemas)[:12])
        return _malformed(raw, number, "malformed_action", f"the domain has no action "
                          f"'{words[0][:40]}'", f"use {'' if near else 'one of '}{names}")
    args = tuple(words[1:])
    if len(args) != len(schema.params):
        return _malformed(raw, number, "malformed_action", f"{schema.name} takes "
                          f"{len(schema.params)} argument(s), got {len(args)}",
                          "write (" + " ".join((schema.name, *schema.params)) + ")")
    return Step(schema.name, args, number)


def read_step(raw: str, number: int, domain: Domain) -> Step | None:
    """Line `number` of a plan, `raw` as written: its Step (a malformed one for a line
    that is no action of the domain), or None for a line that holds no step (blank, a
    comment, a `[PLAN]` marker, a bare `0:` prefix)."""
    body = raw.split(";", 1)[0].strip().lower()
    if not body or body.startswith("[plan"):
        return None
    if not (body[0] == "(" and body[-1] == ")"):
        body = DURATION.sub("", STEP_PREFIX.sub("", body)).rstrip(".").strip()
        if not body:
            return None
    return _read_line(raw, body, number, domain)


def line_reader(text: str, lowered: list[str], domain: Domain
                ) -> Callable[[int], Step | None]:
    """Reads the plan's line at a position (0-based) as `parse_strips_plan` reads it;
    `lowered` is `text.lower().splitlines()`. A plain `(action arg ...)` line of the
    action's arity (printable, one space between words) is split at once; any other
    goes through `read_step`."""
    schemas = domain.schemas
    original: list[str] = []

    def step_at(position: int) -> Step | None:
        line = lowered[position]
        inner = line[1:-1]
        if line[:1] == "(" and line[-1:] == ")" and inner.isprintable() \
                and "(" not in inner and ")" not in inner:
            words = inner.split(" ")  # `_PLAIN_LINE`'s words, when none is empty
            schema = schemas.get(words[0])
            if schema is not None and len(schema.params) == len(words) - 1 \
                    and "" not in words:
                return Step(words[0], tuple(words[1:]), position + 1)
        if not original:
            original.extend(text.splitlines())
        return read_step(original[position], position + 1, domain)

    return step_at


def parse_strips_plan(text: str, domain: Domain) -> list[Step]:
    """Every action line of a plan, in order; an empty plan is valid input."""
    if not text.isascii():
        ascii_names(text)
    schemas = domain.schemas
    lowered = text.lower()
    matches = _PLAIN_LINE.findall(lowered)
    if len(matches) == lowered.count("\n") + (0 if lowered.endswith("\n") else 1) \
            and len(matches) <= MAX_STEPS:  # every line a plain (action args): one pass
        arity = {name: len(s.params) for name, s in schemas.items()}
        plain = [Step(name, tuple(rest.split()), number)
                 for number, (name, rest) in enumerate(matches, start=1)]
        if all(arity.get(s.name) == len(s.args) for s in plain):
            return plain
    steps: list[Step] = []
    for number, raw in enumerate(text.splitlines(), start=1):
        step = read_step(raw, number, domain)
        if step is None:
            continue
        steps.append(step)
        if len(steps) > MAX_STEPS:
            raise PlanParseError(f"the plan has more than {MAX_STEPS:,} actions", line=number,
                                 column=1, text="", expected=f"at most {MAX_STEPS:,} actions")
    return steps
