"""Typed errors that carry the field, the offending value and the fix.

Every failure a user can cause (bad files, bad plans, bad tool arguments) is one of
these, so the CLI can exit with code 2 and the MCP server can answer with a tool
error instead of a traceback.
"""

from __future__ import annotations

from typing import Any


class VeriGraphError(Exception):
    """Base class: a user-facing error with a field, the value seen and a fix."""

    def __init__(self, message: str, *, field: str | None = None, value: Any = None,
                 fix: str | None = None) -> None:
        super().__init__(message)
        self.message = message
        self.field = field
        self.value = value
        self.fix = fix

    def __str__(self) -> str:
        text = self.message
        if self.field:
            text = f"{self.field}: {text}"
        if self.fix:
            text = f"{text} (fix: {self.fix})"
        return text

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready form used by the CLI's --json output and the server."""
        value = self.value if isinstance(self.value, str | int | float | bool | None) \
            else repr(self.value)
        return {"error": type(self).__name__, "message": self.message, "field": self.field,
                "value": value, "fix": self.fix}


class DictionaryError(VeriGraphError):
    """An object name or property that the dictionary D cannot resolve."""


class MalformedGraphError(VeriGraphError):
    """A scene graph that breaks a well-formedness rule; `problems` lists every one."""

    def __init__(self, problems: list[Any]) -> None:
        first = problems[0]
        more = f" (and {len(problems) - 1} more)" if len(problems) > 1 else ""
        super().__init__(f"malformed scene graph: [{first.rule}] {first.message}{more}",
                         field=first.field, value=first.node, fix=first.fix)
        self.problems = problems

    def to_dict(self) -> dict[str, Any]:
        return {**super().to_dict(), "problems": [p.model_dump() for p in self.problems]}


class PlanParseError(VeriGraphError):
    """A plan line that does not parse; carries line and column (1-based)."""

    def __init__(self, message: str, *, line: int, column: int, text: str,
                 expected: str) -> None:
        # The field carries the location once: "plan line 2, column 6: not an action".
        super().__init__(message, field=f"plan line {line}, column {column}", value=text,
                         fix=f"write it as {expected}")
        self.line = line
        self.column = column
        self.text = text
        self.expected = expected
        self.more: list[PlanParseError] = []  # later lines that do not parse either

    def with_more(self, later: list[PlanParseError]) -> PlanParseError:
        """This error, naming the other bad lines too, so one round fixes them all."""
        self.more = later
        if later:
            self.message += "; also " + "; ".join(
                f"line {e.line}, column {e.column}: {e.message}" for e in later)
        return self


class InputFileError(VeriGraphError):
    """A file that cannot be read or decoded (missing, bad JSON/YAML, wrong shape)."""


class GoalError(VeriGraphError):
    """A goal that cannot be interpreted (unknown predicate, bad graph)."""


class ServerUnreachableError(VeriGraphError):
    """No MCP server answers at the URL (connection refused, unknown host, timeout)."""

    exit_code = 3


class MissingTokenError(VeriGraphError):
    """The server needs a bearer token and none was given."""

    exit_code = 4


class TokenRejectedError(VeriGraphError):
    """The server refused the bearer token that was given (401 or 403)."""

    exit_code = 5
