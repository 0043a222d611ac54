"""Blocks-world plans: `(op args)` lines (VAL's format) or PlanBench's English sentences.

Accepted per line, mixed freely:

    (unstack b a)            0: (pick-up c) [1]        ; comments, blank lines
    unstack the red block from on top of the blue block
    pick up the orange block / put down the red block / stack the red block on top of the blue block

PlanBench names its objects a, b, c... and writes them as colours (a = red, b = blue, ...);
a colour resolves to its letter unless the problem declares an object of that name.
A sentence that starts with one of the domain's own operator names is read as that
operator with the remaining words as arguments, filler words dropped: PlanBench's
Mystery Blocksworld writes `feast object b from object c` for `(feast b c)`.
Names are ASCII in every mode (as in the domain and problem files): a non-ASCII name is
bad input naming its line.
A line that is no action, names an unknown operator or has the wrong number of arguments
is bad input (PlanParseError naming the line), never a verdict; a caller may instead take
such lines as they come (`parse_blocks_plan`'s `unreadable`: `validate_pddl_dict` has the
STRIPS reader make each a failing step).

A plan whose every line is a plain `(op args)` is read with one regex pass
(`plain_actions`), possessive, and on ASCII text with its name class as byte ranges.
"""

from __future__ import annotations

import re
from collections.abc import Callable
from typing import NamedTuple

from verigraph.errors import PlanParseError
from verigraph.pddl.blocksworld.domain import BlocksDomain
from verigraph.pddl.syntax import DURATION, STEP_PREFIX, ascii_names

PLANBENCH_COLOURS = {"red": "a", "blue": "b", "orange": "c", "yellow": "d", "white": "e",
                     "magenta": "f", "black": "g", "cyan": "h", "green": "i", "violet": "j",
                     "silver": "k", "gold": "l"}
ROLE_ARITY = {"pick-up": 1, "put-down": 1, "stack": 2, "unstack": 2, "move-b-to-b": 3,
              "move-b-to-t": 2, "move-t-to-b": 2}
_IDENTITY = {0: (), 1: (0,), 2: (0, 1), 3: (0, 1, 2)}
# Every pattern here reads its text in linear time. Possessive quantifiers (`*+`, `++`)
# never give back a run the next part could not use anyway (the line forms shared with the
# STRIPS engine, `syntax.STEP_PREFIX` and `syntax.DURATION`, are read the same way);
# `_ENGLISH` reads a sentence whose spaces are single (a lazy
# name followed by `\s+from` would otherwise retry the whole run of spaces at each space).
_ENGLISH = [
    ("unstack", re.compile(r"^unstack\s+(?P<x>.+?)\s+from(?:\s+on)?(?:\s+top)?(?:\s+of)?\s+"
                           r"(?P<y>.+)$")),
    ("stack", re.compile(r"^stack\s+(?P<x>.+?)\s+on(?:\s+top\s+of)?\s+(?P<y>.+)$")),
    ("pick-up", re.compile(r"^pick[\s_-]*up\s+(?P<x>.+)$")),
    ("put-down", re.compile(r"^put[\s_-]*down\s+(?P<x>.+)$")),
]


def _plain_line(name: str) -> re.Pattern[str]:
    """One `(op a [b [c]])` per line, single spaces (what planners and VAL write), with
    `name` the character class of a name. The quantifiers are possessive (`++`, `?+`):
    a name never ends in the space or `)` that must follow it, so giving characters back
    could not make a line match, and not trying saves the regex engine a fifth of its time."""
    return re.compile(rf"^(\(({name}++) ({name}++)(?: ({name}++))?+(?: ({name}++))?+\))$",
                      re.MULTILINE)


# A name has no whitespace and no parenthesis. On ASCII text (every plan the fast run
# reads) the same set is written as byte ranges (\s there is \t-\r, \x1c-\x1f and the
# space), which the regex engine tests with one table lookup instead of a Unicode
# category test per character; other text keeps the Unicode class.
_PLAIN_LINE = _plain_line(r"[^\s()]")
_PLAIN_ASCII_LINE = _plain_line(r"[^\t-\r\x1c- ()]")

_FILLER = frozenset({"object", "the", "block", "from", "on", "top", "of", "onto", "to", "a"})
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
    body = " ".join(body.split())  # single spaces: each pattern reads it in linear time
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


def _named_step(body: str, number: int, raw: str, domain: BlocksDomain,
                declared: set[str]) -> PlanStep | None:
    """`<operator> object b from object c` -> the operator on (b, c), or None."""
    words = body.split()
    if not words or words[0] not in domain.operators or _VERBS.match(body):
        return None
    args = [w for w in words[1:] if w not in _FILLER or w in declared]
    objects = [_object(a, declared) for a in args]
    return _sexpr_step(f"({' '.join((words[0], *objects))})", number, raw, domain)


PlainLine = tuple[str, str, str, str, str]  # line, operator, up to three arguments ("" if none)


def plain_actions(lowered: str, domain: BlocksDomain) -> list[PlainLine] | None:
    """The regex matches when every line of the (lower-cased) plan is a plain `(op args)`
    with single spaces and every operator takes its arguments in template order; else
    None. Operator names and arities are not checked here."""
    if any(op.order != _IDENTITY[len(op.order)] for op in domain.operators.values()):
        return None
    pattern = _PLAIN_ASCII_LINE if lowered.isascii() else _PLAIN_LINE
    matches: list[PlainLine] = pattern.findall(lowered)
    lines = lowered.count("\n") + (0 if lowered.endswith("\n") else 1)
    return matches if len(matches) == lines else None


def _plain_plan(lowered: str, domain: BlocksDomain) -> list[PlanStep] | None:
    """The steps when every line is a plain `(op args)` of the right arity, else None.

    One regex pass over the whole text; a plan that needs anything more (comments,
    prefixes, sentences, reordered parameters, blank lines, an error) returns None and
    takes the line-by-line path, which gives the same steps.
    """
    matches = plain_actions(lowered, domain)
    if matches is None:
        return None
    table = {name: (op.role, len(op.order)) for name, op in domain.operators.items()}
    steps: list[PlanStep] = []
    append = steps.append
    make = tuple.__new__  # PlanStep's own constructor is a Python-level call
    for number, (line, name, a, b, c) in enumerate(matches, start=1):
        entry = table.get(name)
        args = (a, b, c) if c else (a, b) if b else (a,)
        if entry is None or entry[1] != len(args):
            return None
        append(make(PlanStep, (entry[0], args, line, number)))
    return steps


def parse_blocks_plan(text: str, domain: BlocksDomain, declared: set[str], *,
                      unreadable: Callable[[int, str], object] | None = None
                      ) -> list[PlanStep]:
    """Every action line of a plan, in order; an empty plan is valid input.

    A line that is exactly `(op args)` with the right arity (VAL's and planners' format,
    nearly every line of a long plan) takes an inlined path; any other line goes through
    the general forms above, which also produce every error. With `unreadable`, a line
    that is no action is handed to it (its number and the line as written) and reading
    goes on, instead of the PlanParseError; a name that is not ASCII is still refused.
    """
    if not text.isascii():
        ascii_names(text)
    plain = _plain_plan(text.lower(), domain)
    if plain is not None:
        return plain
    fast = {name: (op.role, op.order, len(op.order), op.order == _IDENTITY[len(op.order)])
            for name, op in domain.operators.items()}
    steps: list[PlanStep] = []
    append = steps.append
    lines = text.splitlines()
    for number, body in enumerate(text.lower().splitlines(), start=1):
        body = body.strip()
        if not body:
            continue
        if body[0] == "(" and body[-1] == ")" and ";" not in body:
            inner = body[1:-1].split()
            entry = fast.get(inner[0]) if inner else None
            if entry is not None and len(inner) == entry[2] + 1:
                role, order, _, identity = entry
                args = tuple(inner[1:])
                shown = "(" + " ".join(inner) + ")"
                if not identity:
                    slots = [""] * len(args)
                    for i, a in enumerate(args):
                        slots[order[i]] = a
                    args = tuple(slots)
                append(PlanStep(role, args, shown, number))
                continue
        raw = lines[number - 1]
        body = raw.split(";", 1)[0].strip().lower()
        if not body or body.startswith("[plan"):
            continue
        if not (body[0] == "(" and body[-1] == ")"):  # prefixes, durations, full stops
            body = DURATION.sub("", STEP_PREFIX.sub("", body)).rstrip(".").strip()
            if not body:
                continue
        try:
            step = _sexpr_step(body, number, raw, domain) if body[0] == "(" else (
                _named_step(body, number, raw, domain, declared)
                or _english_step(body, number, raw, domain, declared))
        except PlanParseError:
            if unreadable is None:
                raise
            unreadable(number, raw)
            continue
        append(step)
    return steps
