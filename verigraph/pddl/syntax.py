"""PDDL's syntax for both engines: the S-expression reader and the plan-line forms.

The reader gives lists of lower-cased atoms, with line numbers.

PDDL is case-insensitive, so every atom is lower-cased here once; `;` starts a comment.
Two rules keep hostile files from reaching the rest of the code: nesting deeper than
`MAX_DEPTH` is refused while reading (everything downstream may then recurse safely),
and names are ASCII (PDDL's names are letters, digits, `-` and `_`; a non-ASCII name is
refused in every mode, with its line, rather than judged in one mode and crashing in
another). Comments may hold any text.

The plan-line forms are what a plan line may carry around its action in either engine:
a step number (`0:`, `1.`, `2)`, `-`), a duration (`[1]`), a comment (`;` to the end of
the line); `ascii_names` refuses a plan line whose names are not ASCII. The blocks-world
engine (`blocksworld/`) and the STRIPS engine both import them from here.
"""

from __future__ import annotations

import re
from typing import Any, NoReturn

from verigraph.errors import PlanParseError, VeriGraphError

_TOKEN = re.compile(r";[^\n]*|\(|\)|[^\s()]+|\n")
_FAST_TOKEN = re.compile(r"[()]|[^\s()]+")
_INNERMOST = re.compile(r"\(([^()]*)\)")  # a list with no list inside
_MARK = "\x00"  # stands for one innermost list in the rest of the text
_MARKED_TOKEN = re.compile(r"[()\x00]|[^\s()\x00]+")
COMMENT = re.compile(r";[^\n]*")  # a comment, to the end of its line
# Possessive quantifiers (`*+`, `++`) never give back a run the next part could not use
# anyway; `DURATION`, searched at every position, starts only where a run of spaces
# starts (`(?<!\s)`), so a long run is read once, not once per space.
STEP_PREFIX = re.compile(r"^\s*+(?:\d++(?:\.\d++)?+\s*+:|\d++[.)]|[-*])\s*+")
DURATION = re.compile(r"(?<!\s)\s*+\[[\d.]++\]\s*+$")

SExpr = str | list["SExpr"]
MAX_DEPTH = 64  # real domains nest about 8 deep; far below Python's recursion limit


class PddlSyntaxError(VeriGraphError):
    """A PDDL file that does not read as balanced S-expressions of the expected shape."""


def parse_sexpr(text: str, *, what: str) -> list[SExpr]:
    """All top-level expressions in `text` (a domain or problem file's contents).

    The fast path splits the text at its innermost lists (a problem's thousands of atoms)
    with one regex pass and each list with `str.split`, leaves one marker token for each
    in the text between them, and builds the nesting from that text's tokens; line
    numbers are only computed for errors.
    """
    body = COMMENT.sub("", text)
    if not body.isascii():
        _non_ascii(text, what)
    body = body.lower()
    mark: str | None = _MARK
    flat: list[Any]  # the innermost lists' words, in order
    if _MARK in body:  # the text holds the marker: read it token by token
        mark, flat, tokens = None, [], _FAST_TOKEN.findall(body)
    else:  # one pass: the text between innermost lists, then the lists themselves
        parts: list[str] = _INNERMOST.split(body)
        flat = [content.split() for content in parts[1::2]]
        tokens = _MARKED_TOKEN.findall(_MARK.join(parts[0::2]))
    lists = iter(flat)
    stack: list[list[SExpr]] = [[]]
    for token in tokens:
        if token == mark:  # an innermost list: one level deeper than where it stands
            if len(stack) > MAX_DEPTH:
                _too_deep(text, what)
            stack[-1].append(next(lists))
        elif token == "(":
            if len(stack) > MAX_DEPTH:
                _too_deep(text, what)
            stack.append([])
        elif token == ")":
            if len(stack) == 1:
                _locate_error(text, what)
            done = stack.pop()
            stack[-1].append(done)
        else:
            stack[-1].append(token)
    if len(stack) > 1:
        _locate_error(text, what)
    return stack[0]


def _line_of(text: str, index: int) -> int:
    return text.count("\n", 0, index) + 1


def _too_deep(text: str, what: str) -> NoReturn:
    depth = 0
    for match in _TOKEN.finditer(text):
        token = match.group()
        if token == "(":
            depth += 1
            if depth > MAX_DEPTH:
                line = _line_of(text, match.start())
                raise PddlSyntaxError(
                    f"parentheses nest more than {MAX_DEPTH} deep on line {line}",
                    field=what, value=line,
                    fix=f"PDDL domains and problems nest a few levels; keep it under {MAX_DEPTH}")
        elif token == ")":
            depth -= 1
    raise AssertionError("unreachable: the fast reader saw the same nesting")


def _non_ascii(text: str, what: str) -> NoReturn:
    for match in _TOKEN.finditer(text):
        token = match.group()
        if token[0] != ";" and not token.isascii():
            line = _line_of(text, match.start())
            raise PddlSyntaxError(
                f"name '{token[:40]}' on line {line} is not ASCII", field=what, value=line,
                fix="PDDL names are ASCII letters, digits, '-' and '_'; rename it "
                    "(comments may hold any text)")
    raise AssertionError("unreachable: non-ASCII text outside comments was seen")


def _locate_error(text: str, what: str) -> NoReturn:
    """Raise PddlSyntaxError naming the line of the unbalanced parenthesis."""
    opened: list[int] = []
    line = 1
    for match in _TOKEN.finditer(text):
        token = match.group()
        if token == "\n":
            line += 1
        elif token == "(":
            opened.append(line)
        elif token == ")":
            if not opened:
                raise PddlSyntaxError(f"unbalanced ')' on line {line}", field=what,
                                      value=line, fix="remove the extra closing parenthesis")
            opened.pop()
    raise PddlSyntaxError(f"'(' opened on line {opened[-1]} is never closed", field=what,
                          value=opened[-1], fix="add the missing closing parenthesis")


def define_body(text: str, *, what: str, kind: str) -> tuple[str, list[SExpr]]:
    """(define (KIND name) sections...) -> (name, sections)."""
    exprs = parse_sexpr(text, what=what)
    if len(exprs) != 1 or not isinstance(exprs[0], list) or not exprs[0] \
            or exprs[0][0] != "define":
        raise PddlSyntaxError(f"a PDDL {kind} file holds one (define ({kind} NAME) ...)",
                              field=what, value=None, fix=f"start the file with (define ({kind} "
                              "NAME)")
    head = exprs[0][1] if len(exprs[0]) > 1 else None
    if not (isinstance(head, list) and len(head) == 2 and head[0] == kind
            and isinstance(head[1], str)):
        raise PddlSyntaxError(f"expected ({kind} NAME) after define", field=what,
                              value=str(head)[:80], fix=f"write (define ({kind} NAME) ...)")
    return head[1], exprs[0][2:]


def typed_names(items: list[SExpr], *, what: str) -> list[tuple[str, str | None]]:
    """`a b - block c` -> [(a, block), (b, block), (c, None)] (PDDL typed lists)."""
    out: list[tuple[str, str | None]] = []
    pending: list[str] = []
    i = 0
    while i < len(items):
        item = items[i]
        if not isinstance(item, str):
            raise PddlSyntaxError(f"expected a name in a typed list, got {item}", field=what,
                                  value=str(item)[:80], fix="write names as `a b - type`")
        if item == "-":
            kind = items[i + 1] if i + 1 < len(items) else None
            if not isinstance(kind, str):
                raise PddlSyntaxError("'-' must be followed by a type name", field=what,
                                      value=None, fix="write names as `a b - type`")
            out.extend((name, kind) for name in pending)
            pending = []
            i += 2
            continue
        pending.append(item)
        i += 1
    out.extend((name, None) for name in pending)
    return out


def ascii_names(text: str) -> None:
    """Refuse a plan whose names (outside comments) are not ASCII, naming the line."""
    for number, raw in enumerate(text.splitlines(), start=1):
        body = raw.split(";", 1)[0]
        if not body.isascii():
            raise PlanParseError("names are ASCII (letters, digits, '-' and '_'), as in PDDL "
                                 "domain and problem files", line=number, column=1,
                                 text=raw[:80], expected="the problem's ASCII object names")
