"""Blocks-world plans: `(op args)` lines (VAL's format) or PlanBench's English sentences.

Accepted per line, mixed freely:

    (unstack b a)            0: (pick-up c) [1]        ; comments, blank lines
    unstack the red block from on top of the blue block
    pick up the orange block / put down the red block / stack the red block on top of the blue block

PlanBench names its objects a, b, c... and writes them as colours (a = red, b = blue, ...);
a colour resolves to its letter unless the problem declares an object of that name.
A line that is no action, names an unknown operator or has the wrong number of arguments
is bad input (PlanParseError naming the line), never a verdict.
"""

from __future__ import annotations

import re
from typing import NamedTuple

from verigraph.actions.blocksworld.domain import BlocksDomain
from verigraph.errors import PlanParseError

PLANBENCH_COLOURS = {"red": "a", "blue": "b", "orange": "c", "yellow": "d", "white": "e",
                     "magenta": "f", "black": "g", "cyan": "h", "green": "i", "violet": "j",
                     "silver": "k", "gold": "l"}
ROLE_ARITY = {"pick-up": 1, "put-down": 1, "stack": 2, "unstack": 2, "move-b-to-b": 3,
              "move-b-to-t": 2, "move-t-to-b": 2}
_IDENTITY = {0: (), 1: (0,), 2: (0, 1), 3: (0, 1, 2)}
_STEP_PREFIX = re.compile(r"^\s*(?:\d+(?:\.\d+)?\s*:|\d+[.)]|[-*])\s*")
_DURATION = re.compile(r"\s*\[[\d.]+\]\s*$")
_ENGLISH = [
    ("unstack", re.compile(r"^unstack\s+(?P<x>.+?)\s+from(?:\s+on)?(?:\s+top)?(?:\s+of)?\s+"
                           r"(?P<y>.+)$")),
    ("stack", re.compile(r"^stack\s+(?P<x>.+?)\s+on(?:\s+top\s+of)?\s+(?P<y>.+)$")),
    ("pick-up", re.compile(r"^pick[\s_-]*up\s+(?P<x>.+)$")),
    ("put-down", re.compile(r"^put[\s_-]*down\s+(?P<x>.+)$")),
]
_VERBS = re.compile(r"^(unstack|stack|pick[\s_-]*up|put[\s_-]*down)\b")
FORMS = ("(op arg ...) with the domain's operators, or PlanBench text such as "
         "'unstack the red block from on top of the blue block'")


class PlanStep(NamedTuple):
    """One action: template role, arguments in template order, how it was written."""

    role: str
    args: tuple[str, ...]
    text: str
    line: int


def _object(phrase: str, declared: set[str]) -> str:
    words = phrase.strip().rstrip(".").split()
    if words and words[0] == "the":
        words = words[1:]
    if len(words) > 1 and words[-1] == "block":
        words = words[:-1]
    elif len(words) > 1 and words[0] == "block":
        words = words[1:]
    name = "_".join(words)
    if name in declared:
        return name
    return PLANBENCH_COLOURS.get(name, name)


def _sexpr_step(body: str, number: int, raw: str, domain: BlocksDomain) -> PlanStep:
    inner = body[1:-1].split()
    if not inner or not body.endswith(")"):
        raise PlanParseError("not an action", line=number, column=1, text=raw, expected=FORMS)
    name, args = inner[0], inner[1:]
    op = domain.operators.get(name)
    if op is None:
        raise PlanParseError(f"unknown operator '{name}'", line=number, column=2, text=raw,
                             expected=f"one of {', '.join(domain.operators)}")
    if len(args) != len(op.order):
        raise PlanParseError(f"{name} takes {len(op.order)} argument(s), got {len(args)}",
                             line=number, column=2, text=raw,
                             expected=f"({name} "
                             + " ".join(f"?arg{i + 1}" for i in range(len(op.order))) + ")")
    if op.order == _IDENTITY[len(args)]:
        return PlanStep(op.role, tuple(args), f"({name} {' '.join(args)})", number)
    slots = [""] * len(args)
    for i, a in enumerate(args):
        slots[op.order[i]] = a
    return PlanStep(op.role, tuple(slots), f"({name} {' '.join(args)})", number)


def _english_step(body: str, number: int, raw: str, domain: BlocksDomain,
                  declared: set[str]) -> PlanStep:
    if domain.family != "4op":
        raise PlanParseError("PlanBench sentences describe the hand operators; this domain "
                             "moves blocks directly", line=number, column=1, text=raw,
                             expected="(op arg ...) lines")
    for role, pattern in _ENGLISH:
        match = pattern.match(body)
        if match:
            args = tuple(_object(match.group(k), declared) for k in ("x", "y")[:ROLE_ARITY[role]])
            op = domain.by_role(role)
            return PlanStep(role, args, f"({op.name} {' '.join(args)})", number)
    verb = _VERBS.match(body)
    if verb:
        role = re.sub(r"[\s_-]+", "-", verb.group(1))
        raise PlanParseError(f"'{verb.group(1)}' takes {ROLE_ARITY[role]} block(s)", line=number,
                             column=1, text=raw, expected=FORMS)
    raise PlanParseError("not an action", line=number, column=1, text=raw, expected=FORMS)


def parse_blocks_plan(text: str, domain: BlocksDomain, declared: set[str]) -> list[PlanStep]:
    """Every action line of a plan, in order; an empty plan is valid input."""
    steps: list[PlanStep] = []
    for number, raw in enumerate(text.splitlines(), start=1):
        body = raw.split(";", 1)[0].strip().lower()
        if not body or body.startswith("[plan"):
            continue
        if not (body[0] == "(" and body[-1] == ")"):  # prefixes, durations, full stops
            body = _DURATION.sub("", _STEP_PREFIX.sub("", body)).rstrip(".").strip()
            if not body:
                continue
        if body[0] == "(":
            steps.append(_sexpr_step(body, number, raw, domain))
        else:
            steps.append(_english_step(body, number, raw, domain, declared))
    return steps
