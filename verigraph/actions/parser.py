"""Plan parsing: the text format (one action per line) and JSON plans.

Text, one action per line, `#` starts a comment, `done` ends the plan:

    move(cup, on, table)
    move(book, shelf)        # move(x, y) means move(x, on, y)
    open(fridge)             # also close(x), toggle_on(x), toggle_off(x)
    align(small_triangle_1, 1, square, 3)
    done

Errors name the line and column and show the expected form. Parsing is linear in the
size of the plan.
"""

from __future__ import annotations

import json
import re
from typing import Any, get_args

from pydantic import ValidationError

from verigraph.actions.model import (
    ActionAdapter,
    AlignAction,
    AnyAction,
    DoneAction,
    MoveAction,
    StateAction,
    StateActionName,
)
from verigraph.budget import checkpoint
from verigraph.errors import PlanParseError

MOVE_FORM = "move(object, relation, target) or move(object, target)"
ALIGN_FORM = "align(piece, side, target_piece, target_side)"
STATE_NAMES: tuple[str, ...] = get_args(StateActionName)
STATE_FORM = ", ".join(f"{name}(object)" for name in STATE_NAMES)
ANY_FORM = f"{MOVE_FORM}, {STATE_FORM}, {ALIGN_FORM} or done"

# Possessive quantifiers (`*+`, `++`, `?+`): a run that may not be given back cannot be
# tried at every split against the next run (`move` + 30,000 spaces + `x` took seconds
# while holding the interpreter); each pattern reads its text in linear time.
_CALL = re.compile(r"^(?P<name>[A-Za-z_]++)\s*+(?:\((?P<args>.*)\))?+\s*+$")
_NUMBERING = re.compile(r"^\s*+(?:\d++[.)]|-|\*)\s+")
_NAME = re.compile(r"^[A-Za-z0-9_][A-Za-z0-9_.\-]*+$")
MAX_NAME = 128


def parse_action_text(text: str, line: int = 1) -> AnyAction:
    """One action in text form, e.g. `move(cup, on, table)`."""
    body = text.split("#", 1)[0].rstrip()
    numbering = _NUMBERING.match(body)
    offset = numbering.end() if numbering else len(body) - len(body.lstrip())
    stripped = body[offset:]
    match = _CALL.match(stripped)
    if not match:
        raise PlanParseError("not an action", line=line, column=offset + 1, text=text,
                             expected=ANY_FORM)
    name = match.group("name").lower()
    args_text = match.group("args")
    if name == "done":
        if args_text not in (None, ""):
            raise PlanParseError("done takes no arguments", line=line,
                                 column=offset + match.start("args") + 1, text=text,
                                 expected="done")
        return DoneAction()
    if name not in ("move", "align", *STATE_NAMES):
        raise PlanParseError(f"unknown action '{name}'", line=line, column=offset + 1,
                             text=text, expected=ANY_FORM)
    form = MOVE_FORM if name == "move" else ALIGN_FORM if name == "align" else f"{name}(object)"
    if args_text is None:
        raise PlanParseError(f"'{name}' needs arguments in parentheses", line=line,
                             column=offset + len(match.group("name")) + 1, text=text,
                             expected=form)
    args_start = offset + match.start("args")
    args, columns = _split_args(args_text, args_start)
    for arg, col in zip(args, columns, strict=True):
        if not arg:
            raise PlanParseError("empty argument", line=line, column=col + 1, text=text,
                                 expected=form)
    if name in STATE_NAMES:
        if len(args) != 1:
            raise PlanParseError(f"{name} takes 1 argument, got {len(args)}", line=line,
                                 column=args_start + 1, text=text, expected=form)
        _check_name(args[0], columns[0], line, text, form)
        return StateAction(action=name, object=args[0])  # type: ignore[arg-type]
    if name == "move":
        if len(args) == 2:
            args = [args[0], "on", args[1]]
            columns = [columns[0], columns[0], columns[1]]
        if len(args) != 3:
            raise PlanParseError(f"move takes 2 or 3 arguments, got {len(args)}", line=line,
                                 column=args_start + 1, text=text, expected=MOVE_FORM)
        for arg, col in zip(args, columns, strict=True):
            _check_name(arg, col, line, text, MOVE_FORM)
        return MoveAction(object=args[0], relation=args[1].lower(), target=args[2])
    if len(args) != 4:
        raise PlanParseError(f"align takes 4 arguments, got {len(args)}", line=line,
                             column=args_start + 1, text=text, expected=ALIGN_FORM)
    sides = []
    for index in (1, 3):
        try:
            sides.append(int(args[index]))
        except ValueError:
            raise PlanParseError(f"side '{args[index]}' is not a whole number", line=line,
                                 column=columns[index] + 1, text=text,
                                 expected=ALIGN_FORM) from None
    for index in (0, 2):
        _check_name(args[index], columns[index], line, text, ALIGN_FORM)
    return AlignAction(object=args[0], side=sides[0], target=args[2], target_side=sides[1])


def _split_args(args_text: str, start: int) -> tuple[list[str], list[int]]:
    """Comma-separated arguments with the 0-based column each starts at."""
    args, columns = [], []
    pos = 0
    for part in args_text.split(","):
        lead = len(part) - len(part.lstrip())
        args.append(part.strip().strip("'\""))
        columns.append(start + pos + lead)
        pos += len(part) + 1
    return args, columns


def _check_name(arg: str, col: int, line: int, text: str, expected: str) -> None:
    if len(arg) > MAX_NAME or not _NAME.match(arg):
        raise PlanParseError(f"'{arg[:40]}' is not a valid object id or relation", line=line,
                             column=col + 1, text=text, expected=expected)


MAX_REPORTED_ERRORS = 10  # bad lines named in one error; a garbage file stops there
_ID = r"[A-Za-z0-9_][A-Za-z0-9_.\-]{0,127}"  # _NAME, at most MAX_NAME characters
_PLAIN_MOVE = re.compile(  # `move(a, on, b)` or `move(a, b)`: what planners write most
    rf"^[ \t]*+(?i:move)[ \t]*+\([ \t]*+({_ID})[ \t]*+,[ \t]*+"
    rf"(?:([A-Za-z0-9_][A-Za-z0-9_.\-]{{0,31}}+)[ \t]*+,[ \t]*+)?({_ID})[ \t]*+\)[ \t]*+$",
    re.MULTILINE)


def _plain_moves(text: str) -> list[AnyAction] | None:
    """The plan when every line that holds something is a plain move with valid names
    (one regex pass over the whole text; the same actions `parse_action_text` reads),
    else None: comments, numbering, quotes, `align`, `done` and every error go through
    the line-by-line reader."""
    if not text.isascii() or "#" in text:
        return None
    moves = _PLAIN_MOVE.findall(text)
    if len(moves) != sum(1 for line in text.splitlines() if line.strip()):
        return None
    return [MoveAction(object=obj, relation=relation.lower() if relation else "on",
                       target=target) for obj, relation, target in moves]


def parse_text_plan(text: str) -> list[AnyAction]:
    """A text plan; blank lines and comments are skipped; nothing may follow `done`."""
    fast = _plain_moves(text)
    if fast is not None:
        return fast
    actions: list[AnyAction] = []
    errors: list[PlanParseError] = []
    done_line = 0
    for number, raw in enumerate(text.splitlines(), start=1):
        checkpoint()  # a long plan stops at its call's budget (a clock read when not due)
        if not raw.split("#", 1)[0].strip():
            continue
        if done_line:
            errors.append(PlanParseError(f"action after done (line {done_line})", line=number,
                                         column=1, text=raw, expected="done as the last action"))
            break
        try:
            action = parse_action_text(raw, number)
        except PlanParseError as exc:
            errors.append(exc)  # keep going: report every bad line at once
            if len(errors) > MAX_REPORTED_ERRORS:
                break
            continue
        if isinstance(action, DoneAction):
            done_line = number
        actions.append(action)
    if errors:
        raise errors[0].with_more(errors[1:MAX_REPORTED_ERRORS])
    return actions


def parse_json_plan(data: Any) -> list[AnyAction]:
    """A JSON plan: a list of action objects (or text actions), or {"actions": [...]}."""
    if isinstance(data, dict):
        data = data.get("actions", data.get("plan"))
    if not isinstance(data, list):
        raise PlanParseError("a JSON plan is a list of actions or {\"actions\": [...]}",
                             line=1, column=1, text=str(data)[:80],
                             expected='[{"action": "move", "object": ..., "relation": "on", '
                                      '"target": ...}]')
    actions: list[AnyAction] = []
    for index, item in enumerate(data):
        if isinstance(item, str):
            actions.append(parse_action_text(item, index + 1))
            continue
        try:
            actions.append(ActionAdapter.validate_python(item))
        except ValidationError as exc:
            err = exc.errors()[0]
            loc = ".".join(str(p) for p in err["loc"])
            raise PlanParseError(f"action {index + 1}: {loc}: {err['msg']}", line=index + 1,
                                 column=1, text=json.dumps(item)[:120] if isinstance(
                                     item, dict | list) else str(item)[:120],
                                 expected='{"action": "move", "object": "cup", "relation": '
                                          '"on", "target": "table"}') from None
    return actions


def parse_plan(plan: str | list[Any] | dict[str, Any], *, allow_empty: bool = False
               ) -> list[AnyAction]:
    """Text or JSON (string or already decoded); raises PlanParseError on any problem.

    An empty plan is an error unless `allow_empty`: a plan validator treats it as the
    plan that does nothing (the goal check decides), an agent's reply must act.
    """
    if isinstance(plan, list | dict):
        actions = parse_json_plan(plan)
    else:
        stripped = plan.lstrip()
        if stripped.startswith(("[", "{")):
            try:
                decoded = json.loads(plan)
            except json.JSONDecodeError as exc:
                raise PlanParseError(f"invalid JSON: {exc.msg}", line=exc.lineno,
                                     column=exc.colno, text=plan.splitlines()[exc.lineno - 1]
                                     if plan.splitlines() else "", expected="a JSON list of "
                                     "actions") from None
            except (RecursionError, ValueError) as exc:
                # valid JSON Python will not hold: nesting past the recursion limit, or an
                # integer past int_max_str_digits (4,300 digits)
                why = "nests too deeply" if isinstance(exc, RecursionError) \
                    else "holds a number too long to read"
                raise PlanParseError(f"the JSON plan {why}", line=1, column=1,
                                     text=plan[:80], expected="a JSON list of actions") from None
            actions = parse_json_plan(decoded)
        else:
            actions = parse_text_plan(plan)
    if not actions and not allow_empty:
        raise PlanParseError("the plan is empty", line=1, column=1, text="",
                             expected=f"at least one action: {ANY_FORM}")
    return actions
