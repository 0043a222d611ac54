"""STRIPS plans: one `(action arg ...)` per line, as planners and VAL write them.

Accepted per line: `(drive-truck t1 l1 l2 c1)`, `0: (drive-truck ...) [1]`, `1. (...)`,
`;` comments, blank lines and `[PLAN]` markers; and a sentence that starts with an action
name, filler words dropped (`load-truck p1 into t1 at l1`). An unknown action or a wrong
number of arguments is bad input (PlanParseError naming the line), never a verdict; an
undeclared object is a verdict at its step (VAL's semantics), decided by the simulator.
"""

from __future__ import annotations

import re
from typing import NamedTuple

from verigraph.actions.blocksworld.plans import _DURATION, _STEP_PREFIX, _ascii_names
from verigraph.actions.pddl.model import Domain
from verigraph.errors import PlanParseError

FILLER = frozenset({"object", "the", "from", "on", "top", "of", "onto", "to", "into", "at",
                    "in", "with", "and", "a", "an"})
MAX_STEPS = 1_000_000
_PLAIN_LINE = re.compile(r"^\(([^\s()]+)((?: [^\s()]+)*)\)$", re.MULTILINE)


class Step(NamedTuple):
    """One plan action: the schema name, its arguments as written, its source line."""

    name: str
    args: tuple[str, ...]
    line: int

    def text(self) -> str:
        return "(" + " ".join((self.name, *self.args)) + ")"


def parse_strips_plan(text: str, domain: Domain) -> list[Step]:
    """Every action line of a plan, in order; an empty plan is valid input."""
    if not text.isascii():
        _ascii_names(text)
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
        body = raw.split(";", 1)[0].strip().lower()
        if not body or body.startswith("[plan"):
            continue
        if not (body[0] == "(" and body[-1] == ")"):
            body = _DURATION.sub("", _STEP_PREFIX.sub("", body)).rstrip(".").strip()
            if not body:
                continue
        if body[0] == "(":
            if not body.endswith(")") or "(" in body[1:]:
                raise PlanParseError("not an action", line=number, column=1, text=raw[:80],
                                     expected="(action arg ...)")
            words = body[1:-1].split()
        else:
            words = body.split()
            words = words[:1] + [w for w in words[1:] if w not in FILLER]
        if not words:
            raise PlanParseError("not an action", line=number, column=1, text=raw[:80],
                                 expected="(action arg ...)")
        schema = schemas.get(words[0])
        if schema is None:
            names = ", ".join(list(schemas)[:12])
            raise PlanParseError(f"unknown action '{words[0][:40]}'", line=number, column=2,
                                 text=raw[:80], expected=f"one of {names}")
        args = tuple(words[1:])
        if len(args) != len(schema.params):
            raise PlanParseError(f"{schema.name} takes {len(schema.params)} argument(s), got "
                                 f"{len(args)}", line=number, column=2, text=raw[:80],
                                 expected="(" + " ".join((schema.name, *schema.params)) + ")")
        steps.append(Step(schema.name, args, number))
        if len(steps) > MAX_STEPS:
            raise PlanParseError(f"the plan has more than {MAX_STEPS:,} actions", line=number,
                                 column=1, text="", expected=f"at most {MAX_STEPS:,} actions")
    return steps
