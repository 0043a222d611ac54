"""Turn whatever a model answered into actions, or into feedback it can act on.

Accepted: `{"actions": [...]}`, a bare JSON list, a single action object, JSON inside a
Markdown code fence, or the text plan form (`move(cup, on, table)` per line). Anything
else becomes a `ParseFailure` whose message names the offending item and field and
shows the expected form, so the next iteration can fix it; it is never an exception
that ends the run. `split_proposal` then reads the parsed actions as the loop and the
environment both do: at most k moves, and nothing after the end token `done` counts.
"""

from __future__ import annotations

import json
import re
from typing import Any

from pydantic import ValidationError

from verigraph.actions.model import ActionAdapter, AnyAction, DoneAction, MoveAction
from verigraph.actions.parser import parse_plan
from verigraph.errors import PlanParseError

# `\s*+` possessive: the spaces after an opening fence are read once, not again by the
# lazy body at each split (an unclosed fence then a long run of spaces was quadratic).
_FENCE = re.compile(r"```(?:json|JSON)?\s*+(?P<body>.*?)```", re.DOTALL)
EXPECTED = ('{"actions": [{"action": "move", "object": "cup", "relation": "on", '
            '"target": "table"}, {"action": "done"}]}')
MAX_SHOWN = 160


class ParseFailure(Exception):
    """The answer could not be read as actions; `str()` is the feedback for the model."""


def _shown(text: str) -> str:
    text = text.strip().replace("\n", " ")
    return text if len(text) <= MAX_SHOWN else text[: MAX_SHOWN - 3] + "..."


def _items(data: Any) -> list[Any]:
    if isinstance(data, dict) and "actions" in data:
        items = data["actions"]
        if not isinstance(items, list):
            raise ParseFailure(f"'actions' must be a list, got {type(items).__name__}; "
                               f"write it as {EXPECTED}")
        return items
    if isinstance(data, dict) and "action" in data:
        return [data]
    if isinstance(data, list):
        return data
    raise ParseFailure(f"expected an object with an 'actions' list, got {_shown(json.dumps(data))}"
                       f"; write it as {EXPECTED}")


def _action(index: int, item: Any) -> AnyAction:
    if isinstance(item, str):
        try:
            parsed = parse_plan(item)
        except PlanParseError as exc:
            raise ParseFailure(f"actions[{index}]: {exc.message} in {item!r} "
                               f"(fix: {exc.fix})") from None
        if len(parsed) != 1:
            raise ParseFailure(f"actions[{index}]: expected one action, got {item!r}")
        return parsed[0]
    try:
        return ActionAdapter.validate_python(item)
    except ValidationError as exc:
        err = exc.errors()[0]
        loc = [str(p) for p in err["loc"] if str(p) not in ("move", "align", "done")]
        where = ".".join([f"actions[{index}]", *loc])
        raise ParseFailure(f"{where}: {err['msg']} (got {_shown(json.dumps(item))}); each "
                           "action is move {object, relation, target}, open/close/toggle_on/"
                           "toggle_off {object}, align {object, side, target, target_side} "
                           "or done") from None


def parse_answer(text: str, *, truncated: bool = False) -> list[AnyAction]:
    """Actions from a model's answer; raises ParseFailure with feedback for the model.

    `truncated` (the endpoint hit its token limit) turns any parse error into a message
    that says so, since "invalid JSON" would send the model looking for the wrong fix.
    """
    try:
        return _parse_answer(text)
    except ParseFailure:
        if not truncated:
            raise
        raise ParseFailure("the answer was cut off by the token limit before it was complete"
                           f" (it ended with {_shown(text[-60:])!r}); propose fewer actions "
                           "and write only the JSON object") from None


def _parse_answer(text: str) -> list[AnyAction]:
    stripped = text.strip()
    if not stripped:
        raise ParseFailure(f"the answer was empty; write the actions as {EXPECTED}")
    fenced = _FENCE.search(stripped)
    body = fenced.group("body").strip() if fenced else stripped
    if body[:1] in "{[":
        try:
            data = json.loads(body)
        except json.JSONDecodeError as exc:
            raise ParseFailure(f"the answer is not valid JSON ({exc.msg} at character "
                               f"{exc.pos}: {_shown(body)!r}); write it as {EXPECTED}") from None
        except (RecursionError, ValueError) as exc:
            # Valid JSON that Python will not hold: nesting past the recursion limit, or an
            # integer past int_max_str_digits (4,300 digits). The answer is still unreadable.
            why = "nests too deeply" if isinstance(exc, RecursionError) \
                else "holds a number too long to read"
            raise ParseFailure(f"the answer {why} ({_shown(body)!r}); write it as "
                               f"{EXPECTED}") from None
        try:
            return [_action(i, item) for i, item in enumerate(_items(data))]
        except RecursionError:  # a nested item's error message recursed too deeply
            raise ParseFailure(f"the answer nests too deeply ({_shown(body)!r}); write it as "
                               f"{EXPECTED}") from None
    try:
        return parse_plan(body)
    except PlanParseError as exc:
        raise ParseFailure(f"could not read the answer as JSON or as a text plan: "
                           f"{exc.message} ({_shown(exc.text)!r}); write it as {EXPECTED}"
                           ) from None


def parse_tool_input(data: Any) -> list[AnyAction]:
    """Actions from a tool-call input object (Anthropic tool use, OpenAI tool calls)."""
    return [_action(i, item) for i, item in enumerate(_items(data))]


def refused_action(data: dict[str, Any]) -> AnyAction | None:
    """The action a violation reports (its `model_dump`), or None if it is not one."""
    try:
        if data.get("action") in (None, "move"):
            return MoveAction.model_validate(data)
        return ActionAdapter.validate_python(data)
    except ValueError:
        return None


def split_proposal(actions: list[AnyAction], k: int | None
                   ) -> tuple[list[AnyAction], bool, list[AnyAction]]:
    """(moves to send, end token reached, dropped): obey k; nothing after `done` counts."""
    moves: list[AnyAction] = []
    done = False
    rest: list[AnyAction] = []
    for index, action in enumerate(actions):
        if isinstance(action, DoneAction):
            done = True
            rest = actions[index + 1:]
            break
        moves.append(action)
    if k is not None and len(moves) > k:
        return moves[:k], False, [*moves[k:], *([DoneAction()] if done else []), *rest]
    return moves, done, rest
